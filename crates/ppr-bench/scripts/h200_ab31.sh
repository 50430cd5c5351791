#!/usr/bin/env bash
# The thirty-first session's A/B: three binaries carried gzipped as .gpu/ppr-bench-{a,b,c}.gz
# (a: the layer tiles, e04d183; b: + the indirect reflection's flag and value loaded
# together, 6faca19; c: + the glossy blur's two depths loaded together, a6da814), each
# timing the demo's and the kitchen's default frames at 1080p and 4K (passes and whole
# frames), in the order a b c a b c; then the layer tiles' rows on c; then the scaling
# counts on c. Same setup as h200.sh. Expected: 6 x 35 + 60 + 95 s.
source crates/ppr-bench/scripts/h200_env.sh
for v in a b c; do gunzip -c .gpu/ppr-bench-$v.gz > .gpu/ppr-bench-$v && chmod +x .gpu/ppr-bench-$v; done
for round in 1 2; do
  for v in a b c; do
    step ab_${v}_$round 80 .gpu/ppr-bench-$v runtime $C --projection-profile --profile-row "frame span" \
      --frames 20 --out $R/ab_${v}_$round
  done
done
ROWS=()
for row in "layers: every tile" "layers: own pass" "layers: own pass, every tile" "frame span" \
    "frame span, layers every tile"; do
  ROWS+=(--profile-row "$row")
done
step layertiles 150 .gpu/ppr-bench-c runtime $C --projection-profile "${ROWS[@]}" --scene demo --frames 20 --out $R/layertiles
B=.gpu/ppr-bench-c
step scalecounts 240 $B scaling $C --out $R/scalecounts --frames 10 --counts 1,10,100,1000,10000 --threshold-counts 8 --coverages 0.3
