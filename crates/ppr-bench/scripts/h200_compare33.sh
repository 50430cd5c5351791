#!/usr/bin/env bash
# The thirty-third session's compare of the head (.gpu/ppr-bench.gz): full PPR, PPR as
# mirrors and ssr-low on the demo and the kitchen at 1080p and 4K, each timed by its passes'
# own timestamps (as every earlier compare) and as a whole frame (`timing=frame`: PPR's
# upload and barriers included). Same setup as h200.sh. Expected: about 150 s.
source crates/ppr-bench/scripts/h200_env.sh
step compare 400 $B compare $C --out $R/compare --reference mirror --scene demo --scene kitchen \
  --resolution 1080p --resolution 4k --frames 20 --technique ppr --technique ppr:glossy=off \
  --technique ppr:timing=frame --technique ppr:glossy=off,timing=frame --technique ssr-low \
  --technique ssr-low:timing=frame
