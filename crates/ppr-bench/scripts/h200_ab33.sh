#!/usr/bin/env bash
# The thirty-third session's A/B call: `bash h200_ab33.sh "X Y ..." [ROW...]` times the
# binaries carried gzipped as .gpu/ppr-bench-X.gz, … over the demo's and the kitchen's
# default frames at 1080p and 4K (the `frame span` rows and every ROW given, which every
# binary must know), in the order X Y … X Y …, 20 frames. Same setup as h200.sh.
# With BOUND=Z in the environment, then binary Z alone with `frame span` and
# `frame span, copied upload` (the upload bound where it is written against copied, in one
# process). Expected: 25 s a run.
#   BOUND=h h200_ab33.sh "e f h"   e: main (faa5eff), f: the classification clears the next slot
#                          (52a9650), h: f + the bound upload + the lists per slot (cc4cda9)
source crates/ppr-bench/scripts/h200_env.sh
BINS=($1)
shift
ROWS=(--profile-row "frame span")
for row in "$@"; do ROWS+=(--profile-row "$row"); done
for v in "${BINS[@]}"; do gunzip -c .gpu/ppr-bench-$v.gz > .gpu/ppr-bench-$v && chmod +x .gpu/ppr-bench-$v; done
for round in 1 2; do
  for v in "${BINS[@]}"; do
    step ab_${v}_$round 80 .gpu/ppr-bench-$v runtime $C --projection-profile "${ROWS[@]}" --frames 20 --out $R/ab_${v}_$round
  done
done
if [ -n "${BOUND:-}" ]; then
  step bound 120 .gpu/ppr-bench-$BOUND runtime $C --projection-profile --profile-row "frame span" \
    --profile-row "frame span, copied upload" --frames 20 --out $R/bound
fi
