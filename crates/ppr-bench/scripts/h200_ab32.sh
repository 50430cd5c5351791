#!/usr/bin/env bash
# The thirty-second session's first A/B: two binaries carried gzipped as
# .gpu/ppr-bench-{a,b}.gz (a: main at 7f165e2; b: the glossy taps with one transcendental
# each, a turn and an inverse square root instead of a division, a square root, a sine and
# a cosine), each timing the demo's and the kitchen's default frames at 1080p and 4K
# (passes and whole frames), in the order a b a b. Same setup as h200.sh. Expected: 4 x 35 s.
source crates/ppr-bench/scripts/h200_env.sh
for v in a b; do gunzip -c .gpu/ppr-bench-$v.gz > .gpu/ppr-bench-$v && chmod +x .gpu/ppr-bench-$v; done
for round in 1 2; do
  for v in a b; do
    step ab_${v}_$round 80 .gpu/ppr-bench-$v runtime $C --projection-profile --profile-row "frame span" \
      --profile-row "reflection: no glossy" --frames 20 --out $R/ab_${v}_$round
  done
done
