#!/usr/bin/env bash
# The thirtieth session's threshold changes, read on an H100 (docs/perf/scaling.md, "The
# thresholds read from the head"), to confirm on the H200 of the numbers of record:
# super-tile lists and parallel trees from 768 (the sweep between 512 and 1 024, the plan's
# own choice in the `no subgroup culling` column) and indirect dispatch above 1920×1080
# (the demo's and the kitchen's cameras at 1080p and 1440p with it forced on and off, and
# one floor mirror's coverage sweep at 1080p). Same setup as h200.sh (from the repository
# root on the device, `.gl` and `.gpu` carried, results in $OUT/results.tar.gz). Expected
# on the H100: 105 + 55 + 10 s.
source crates/ppr-bench/scripts/h200_env.sh
step supersweep 200 $B scaling $C --out $R/supersweep --counts 1 --threshold-counts 512,640,768,896,1024 --coverages 0.3
step indirect 120 $B compare $C --out $R/indirect --reference mirror --scene demo --scene kitchen \
  --resolution 1080p --resolution 1440p --frames 20 --technique ppr --technique ppr:indirect=on --technique ppr:indirect=off
step coverage 60 $B scaling $C --out $R/coverage --resolution 1920x1080 --family facade --counts 1 \
  --threshold-counts 1 --coverages 0.05,0.1,0.2,0.3,0.4
