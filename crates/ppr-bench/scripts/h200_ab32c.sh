#!/usr/bin/env bash
# The thirty-second session's third A/B: .gpu/ppr-bench-{c,d}.gz (c: the layer pass over its
# tiles; d: c + the reflection binding a storage part of the upload buffer and the layer pass
# the classification's tile buffers, so that wgpu puts no barrier between the layer and the
# reflection dispatches), in the order c d c d. Same setup as h200.sh. Expected: 4 x 30 s.
source crates/ppr-bench/scripts/h200_env.sh
for v in c d; do gunzip -c .gpu/ppr-bench-$v.gz > .gpu/ppr-bench-$v && chmod +x .gpu/ppr-bench-$v; done
for round in 1 2; do
  for v in c d; do
    step ab_${v}_$round 80 .gpu/ppr-bench-$v runtime $C --projection-profile --profile-row "frame span" \
      --profile-row "layers: own pass" --frames 20 --out $R/ab_${v}_$round
  done
done
