#!/usr/bin/env bash
# The thirty-fifth session's call for the glossy colour pyramid (DebugOptions::glossy_pyramid,
# binary .gpu/ppr-bench.gz). Same setup as h200.sh. Steps (`bash h200_pyramid35.sh STEP...`):
# ab (the demo's and the kitchen's frames at 1080p and 4K, whole frames and the two passes,
# with the full-size taps and with the pyramid at three level biases and 8 taps, in one
# process; about 250 s), mirror (compare against the mirror reference, the goal's measure:
# PPR with and without the pyramid and ssr-low, by passes and as whole frames; about 150 s),
# glossy (compare against the exact glossy reference: the same and the bias variants; about
# 200 s).
STEPS=" $* "
want() { [[ "$STEPS" == *" $1 "* ]]; }
source crates/ppr-bench/scripts/h200_env.sh
ROWS=(--projection-profile --profile-row "frame span" --profile-row "frame span, glossy pyramid"
  --profile-row "frame span, glossy pyramid, bias -1" --profile-row "frame span, glossy pyramid, bias -20"
  --profile-row "frame span, glossy pyramid, 8 taps" --profile-row "frame span, glossy, 8 taps"
  --profile-row "reflection own pass" --profile-row "reflection own pass, glossy pyramid"
  --profile-row "reflection: no glossy")
want ab && step ab 300 $B runtime $C "${ROWS[@]}" --frames 20 --out $R/ab
want mirror && step mirror 240 $B compare $C --out $R/mirror --reference mirror --scene demo --scene kitchen --resolution 1080p --resolution 4k --frames 20 --technique ppr --technique ppr:pyramid=on --technique ppr:timing=frame --technique ppr:pyramid=on,timing=frame --technique ssr-low --technique ssr-low:timing=frame --technique exact
want glossy && step glossy 330 $B compare $C --out $R/glossy --scene demo --scene kitchen --resolution 1080p --resolution 4k --frames 20 --technique ppr --technique ppr:pyramid=on --technique ppr:pyramid=on,lod-bias=-1 --technique ppr:pyramid=on,lod-bias=-20 --technique ppr:glossy=off --technique ssr-low --technique ssr-glossy --technique exact
