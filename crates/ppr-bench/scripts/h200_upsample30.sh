#!/usr/bin/env bash
# The thirtieth session's probes of the reduced tiers' upsample: what its 0.09-0.11 ms at
# 4K are made of (the twenty-ninth session's workgroup-memory variant took nothing off the
# demo's). `upsample=store-only` stores the empty reflection only, `depth-only` reads the
# pixel's depth and stores, `no-own-depth` is the upsample with the pixel's camera distance
# from its four samples' (no full-resolution read: a different image at silhouettes, its
# PSNR says how different). Same setup as h200.sh (from the repository root on the device,
# `.gl` and `.gpu` carried, results in $OUT/results.tar.gz). Expected: about 160 s.
source crates/ppr-bench/scripts/h200_env.sh
T=""
for t in ppr ppr:tier=quarter ppr:tier=quarter,upsample=store-only ppr:tier=quarter,upsample=depth-only \
  ppr:tier=quarter,upsample=no-own-depth ppr:tier=quarter,upsample=shared ppr:tier=half ppr:tier=half,upsample=no-own-depth; do
  T="$T --technique $t"
done
step probes 300 $B compare $C --out $R/probes --reference mirror --scene demo --scene kitchen \
  --resolution 1080p --resolution 4k --frames 20 $T
