#!/usr/bin/env bash
# The thirty-fifth session's call for the glossy colour pyramid (DebugOptions::glossy_pyramid,
# binary .gpu/ppr-bench.gz). Same setup as h200.sh. Steps (`bash h200_pyramid35.sh STEP...`):
# ab (the demo's and the kitchen's frames at 1080p and 4K, whole frames and the two passes,
# with the full-size taps and with the pyramid at two level biases and at 8 taps, in one
# process; about 100 s), mirror (compare against the mirror reference, the goal's measure:
# PPR with and without the pyramid and ssr-low, by passes and as whole frames; about 100 s),
# glossy (compare against the exact glossy reference, 64 views a rough plane: PPR's taps,
# the pyramid at two biases; about 150 s). One call of at most 600 s holds all three.
STEPS=" $* "
want() { [[ "$STEPS" == *" $1 "* ]]; }
source crates/ppr-bench/scripts/h200_env.sh
ROWS=(--projection-profile --profile-row "frame span" --profile-row "frame span, glossy pyramid"
  --profile-row "frame span, glossy pyramid, bias -20" --profile-row "frame span, glossy pyramid, 8 taps"
  --profile-row "frame span, glossy, 8 taps")
want ab && step ab 220 $B runtime $C "${ROWS[@]}" --frames 20 --out $R/ab
want mirror && step mirror 160 $B compare $C --out $R/mirror --reference mirror --scene demo --scene kitchen --resolution 1080p --resolution 4k --frames 20 --technique ppr --technique ppr:pyramid=on --technique ppr:timing=frame --technique ppr:pyramid=on,timing=frame --technique ssr-low --technique ssr-low:timing=frame --technique exact
want glossy && step glossy 200 $B compare $C --out $R/glossy --glossy-samples 64 --scene demo --scene kitchen --resolution 1080p --resolution 4k --frames 10 --technique ppr --technique ppr:pyramid=on --technique ppr:pyramid=on,lod-bias=-20 --technique exact
