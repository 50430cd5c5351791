#!/usr/bin/env bash
# The thirty-second session's second A/B: .gpu/ppr-bench-{b,c}.gz (b: the glossy taps with
# one transcendental each; c: b + the layer pass dispatched over the list of the tiles its
# layers' rectangles meet instead of a grid over their common rectangle), each timing the
# demo's and the kitchen's default frames at 1080p and 4K (passes, whole frames, the layer
# pass on its own), in the order b c b c. Same setup as h200.sh. Expected: 4 x 30 s.
source crates/ppr-bench/scripts/h200_env.sh
for v in b c; do gunzip -c .gpu/ppr-bench-$v.gz > .gpu/ppr-bench-$v && chmod +x .gpu/ppr-bench-$v; done
for round in 1 2; do
  for v in b c; do
    step ab_${v}_$round 80 .gpu/ppr-bench-$v runtime $C --projection-profile --profile-row "frame span" \
      --profile-row "layers: own pass" --frames 20 --out $R/ab_${v}_$round
  done
done
