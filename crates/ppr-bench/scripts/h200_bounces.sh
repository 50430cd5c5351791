#!/usr/bin/env bash
# Not run yet: the bounce rows of docs/perf/comparison.md ("Mirror facing mirror") on the
# lent H200, with the same carried files as h200.sh (`.gl` loader debs, `.gpu/ppr-bench`,
# `.gpu/scenes/`); results go to $OUT/results.tar.gz. One device call (the `rooms` step of
# h200.sh took under 330 s with as many scored rows).
source crates/ppr-bench/scripts/h200_env.sh
step bounces 540 $B compare $C --out $R/bounces \
  --scene mirror-room --scene mirror-room-6 --scene mirror-corridor --resolution 4k --frames 20 \
  --technique ppr --technique ppr:reference-bounces=2 --technique ppr:bounces=2 \
  --technique ppr:tier=half,bounces=2 --technique ssr-brute:reference-bounces=2 \
  --technique exact --technique exact:bounces=2
