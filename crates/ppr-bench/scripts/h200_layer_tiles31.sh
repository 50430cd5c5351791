#!/usr/bin/env bash
# The thirty-first session's layer pass change timed: the layer reflection writes only the
# 16 x 16 tiles of the layers' common rectangle that meet a layer's own (the default)
# against every tile (`layers: every tile`, the pass before), in the reflection's compute
# pass (the default placement), in its own pass, and as whole frames; the demo's cameras
# (the kitchen has no layers) at 1080p and 4K. Then the numbers of record's compare and
# scaling counts on the same binary. Same setup as h200.sh (from the repository root on
# the device, `.gl` and `.gpu` carried, results in $OUT/results.tar.gz). Expected: about
# 60 + 255 + 95 s.
source crates/ppr-bench/scripts/h200_env.sh
ROWS=()
for row in "layers: every tile" "layers: own pass" "layers: own pass, every tile" "frame span" \
    "frame span, layers every tile"; do
  ROWS+=(--profile-row "$row")
done
step layertiles 150 $B runtime $C --projection-profile "${ROWS[@]}" --scene demo --frames 20 --out $R/layertiles
bash crates/ppr-bench/scripts/h200.sh compare scalecounts
