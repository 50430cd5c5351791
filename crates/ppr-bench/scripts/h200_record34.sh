#!/usr/bin/env bash
# The thirty-fourth session's record of the head (.gpu/ppr-bench.gz), same setup as
# h200.sh: `bash h200_record34.sh STEP...` with steps compare (every technique, PPR and
# ssr-low, ssr-hiz and sspr also as whole frames, the baselines now without their own pass
# timestamps inside the span; about 330 s), collision (about 80 s), profile (h200.sh's,
# about 200 s) and scalecounts (about 100 s). Split into calls of at most 600 s.
STEPS=" $* "
want() { [[ "$STEPS" == *" $1 "* ]]; }
source crates/ppr-bench/scripts/h200_env.sh
T="--technique ppr-raw --technique ppr-holes --technique ppr-filter --technique ppr --technique ppr:glossy=off --technique ppr:fade=0.1 --technique ppr:tier=half --technique ppr:tier=quarter --technique exact --technique ssr-brute --technique ssr-low --technique ssr-low:stride=16,refine=4 --technique ssr-hiz --technique ssr-glossy --technique sspr"
F="--technique ppr:timing=frame --technique ppr:glossy=off,timing=frame --technique ssr-low:timing=frame --technique ssr-hiz:timing=frame --technique sspr:timing=frame"
want compare && step compare 420 $B compare $C --out $R/compare --reference mirror --scene demo --scene kitchen --resolution 1080p --resolution 4k --frames 20 $T $F
want collision && step collision 110 $B compare $C --out $R/collision --scene collision-world --reference mirror --resolution 1080p --resolution 4k --frames 10 --technique ppr --technique ppr:timing=frame --technique ppr:subgroups=off --technique ppr-raw --technique ppr:tier=half --technique ssr-low --technique ssr-low:timing=frame --technique exact
if want profile || want scalecounts; then
  bash crates/ppr-bench/scripts/h200.sh $(want profile && echo profile) $(want scalecounts && echo scalecounts)
fi
