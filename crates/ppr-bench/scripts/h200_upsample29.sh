#!/usr/bin/env bash
# The twenty-ninth session's option, built and tested but not timed (no device time left):
# the reduced tiers' upsample with each workgroup's reduced samples read once into
# workgroup memory (`ppr:upsample=shared`, `DebugOptions::shared_upsample`; bit-identical
# images on the software adapter) against the per-pixel upsample, the default. Same setup
# as h200.sh (from the repository root on the device, `.gl` and `.gpu` carried, results in
# $OUT/results.tar.gz, packed again after each step). The 4K upsample costs 0.090-0.104 ms
# per-pixel (runtime.md, "The head on the H200"); a plain full-screen write of its texture
# 0.026. Also the driver's counts (`pipeline-stats --projection-variants`, which builds all
# eight upsample pipelines: the renderer builds the per-pixel ones at creation, the shared
# ones on request): check that the per-pixel pipelines do not carry the shared variant's
# 6.3 KiB of workgroup memory. Expected: about 150 s for
# `tiers`, 60 for `collision_tiers`, 30 for `stats`.
source crates/ppr-bench/scripts/h200_env.sh
T=""
for t in ppr ppr:tier=half ppr:tier=half,upsample=shared ppr:tier=quarter ppr:tier=quarter,upsample=shared; do
  T="$T --technique $t"
done
step tiers 240 $B compare $C --out $R/tiers --reference mirror --scene demo --scene kitchen \
  --resolution 1080p --resolution 4k --frames 20 $T
step collision_tiers 120 $B compare $C --out $R/collision_tiers --reference mirror --scene collision-world \
  --resolution 1080p --resolution 4k --frames 10 $T
step stats 90 $B pipeline-stats $C --projection-variants --out $R/stats
