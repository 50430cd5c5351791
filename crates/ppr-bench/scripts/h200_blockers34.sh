#!/usr/bin/env bash
# The thirty-fourth session's call for the path blockers (ppr_runtime::path_blockers), binary
# .gpu/ppr-bench.gz with them on by default. Same setup as h200.sh. Steps (`bash
# h200_blockers34.sh STEP...`, none: all): ab (the demo's and the kitchen's frames at 1080p
# and 4K, each pass and as whole frames, with the blockers and without, in one process;
# about 60 s), generated (the same for the 1-, 1 000- and 10 000-tread stairways and the
# rooms of 1 and 1 000 walls at 4K; about 60 s), compare (PPR with and without blockers, as mirrors too, and ssr-low,
# each by passes and as whole frames: PSNR beside time; about 150 s), collision (about 60
# s), scalecounts (h200.sh's; about 100 s; only with SCALECOUNTS=1 in the environment: the
# generated step holds the scaling goal's frames, with and without the blockers).
STEPS=" $* "
want() { [ "$STEPS" = "  " ] || [[ "$STEPS" == *" $1 "* ]]; }
source crates/ppr-bench/scripts/h200_env.sh
ROWS=(--projection-profile --profile-row "frame span" --profile-row "frame span, path blockers off" --profile-row "path blockers off")
want ab && step ab 150 $B runtime $C "${ROWS[@]}" --frames 20 --out $R/ab
want generated && step generated 150 $B runtime $C "${ROWS[@]}" --frames 10 --scene stairway-1 --scene stairway-1000 --scene stairway-10000 --scene rooms-1 --scene rooms-1000 --resolution 4k --out $R/generated
want compare && step compare 300 $B compare $C --out $R/compare --reference mirror --scene demo --scene kitchen --resolution 1080p --resolution 4k --frames 20 --technique ppr --technique ppr:blockers=off --technique ppr:glossy=off --technique ppr:glossy=off,blockers=off --technique ppr:timing=frame --technique ppr:glossy=off,timing=frame --technique ssr-low --technique ssr-low:timing=frame
want collision && step collision 110 $B compare $C --out $R/collision --scene collision-world --reference mirror --resolution 1080p --resolution 4k --frames 10 --technique ppr --technique ppr:blockers=off --technique ppr:timing=frame --technique ssr-low --technique ssr-low:timing=frame --technique exact
want scalecounts && [ -n "${SCALECOUNTS:-}" ] && step scalecounts 240 $B scaling $C --out $R/scalecounts --frames 10 --counts 1,10,100,1000,10000 --threshold-counts 8 --coverages 0.3
