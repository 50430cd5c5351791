#!/usr/bin/env bash
# The thirty-second session's A/B calls: `bash h200_ab32.sh X Y [ROW...]` times two binaries
# carried gzipped as .gpu/ppr-bench-X.gz and .gpu/ppr-bench-Y.gz, each over the demo's and
# the kitchen's default frames at 1080p and 4K (passes and whole frames: the `frame span`
# rows, and every ROW given), in the order X Y X Y, 20 frames. Same setup as h200.sh.
# Expected: 4 x 20-25 s. The three calls (runtime.md, "The thirty-second session"):
#   h200_ab32.sh a b "reflection: no glossy"   a: 7f165e2, b: the glossy taps (f092563)
#   h200_ab32.sh b c "layers: own pass"        c: b + the layer pass over its tiles
#   h200_ab32.sh c d "layers: own pass"        d: c + no barrier before the reflection (7a25077)
#   h200_ab32.sh d e "layers: own pass"        e: d + the layers' tests sorted out with the
#                                               fused block lists
# With STATS=1 in the environment, also the driver's counts of Y's pipelines (pipeline-stats).
source crates/ppr-bench/scripts/h200_env.sh
X=$1 Y=$2
shift 2
ROWS=(--profile-row "frame span")
for row in "$@"; do ROWS+=(--profile-row "$row"); done
for v in "$X" "$Y"; do gunzip -c .gpu/ppr-bench-$v.gz > .gpu/ppr-bench-$v && chmod +x .gpu/ppr-bench-$v; done
for round in 1 2; do
  for v in "$X" "$Y"; do
    step ab_${v}_$round 80 .gpu/ppr-bench-$v runtime $C --projection-profile "${ROWS[@]}" --frames 20 --out $R/ab_${v}_$round
  done
done
if [ "${STATS:-0}" = 1 ]; then
  step stats 90 .gpu/ppr-bench-$Y pipeline-stats $C --out $R/stats
fi
