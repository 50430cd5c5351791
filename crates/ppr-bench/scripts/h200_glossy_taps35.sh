#!/usr/bin/env bash
# For the next call (written in the thirty-fifth session, not yet run): what the glossy
# blur's most taps cost and buy. Same setup as h200.sh. Steps (`bash h200_glossy_taps35.sh
# STEP...`): frames (the demo's and the kitchen's whole frames at 1080p and 4K with 12 and
# with 8 taps at most, in one process; about 40 s), glossy (compare against the exact
# glossy reference, 32 views a rough plane: PPR with 12, 8 and 6 taps at most, without its
# blur, and ssr-glossy; the thirty-fifth session's 64-view step with four techniques needed
# more than 200 s for the demo alone, so this one is given 500 s and the demo goes first).
STEPS=" $* "
want() { [[ "$STEPS" == *" $1 "* ]]; }
source crates/ppr-bench/scripts/h200_env.sh
want frames && step frames 90 $B runtime $C --projection-profile --profile-row "frame span" --profile-row "frame span, glossy, 8 taps" --frames 20 --out $R/frames
want glossy && step glossy 500 $B compare $C --out $R/glossy --glossy-samples 32 --scene demo --scene kitchen --resolution 4k --resolution 1080p --frames 10 --technique ppr --technique ppr:glossy-taps=8 --technique ppr:glossy-taps=6 --technique ppr:glossy=off --technique ssr-glossy --technique exact
