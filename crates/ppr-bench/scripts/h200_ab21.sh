#!/usr/bin/env bash
# The twenty-first session's A/B, run in the twenty-third on an H100 (runtime.md, "The
# twenty-third session"; its glossy bench options' step is gone with them): times the head
# against the binary before that session's GPU changes, and each change on its own, on the
# default frames (runtime.md, "The twenty-first session"). Same setup as h200.sh (from the
# repository root on the device, `.gl` and `.gpu` carried, results in
# $OUT/results.tar.gz). Build each binary here (`git worktree add /tmp/wt <commit> && cd
# /tmp/wt && cargo build --release -p ppr-bench`), strip it and gzip it into `.gpu/` (the
# carry limit is 64 MiB: six stripped binaries fit only gzipped):
#   ppr-bench-base.gz   0f3bf37  the GPU code before the session
#   ppr-bench-forms.gz  b24b9d8  + the shape tests' axis forms
#   ppr-bench-deriv.gz  f80e63d  + the derivative tolerance and the glossy bench options
#   ppr-bench-zinit.gz  cfc650e  + no workgroup zeroing
#   ppr-bench-nobar.gz  3f1096a  + one barrier less in workgroup_box
#   ppr-bench.gz        the head (+ the encoding without integer divisions; the
#                       twenty-second session's CPU side, which does not touch the shaders)
# Missing binaries are skipped. BUDGET (s, default 290) bounds the call; base and head run
# twice, alternating, then the attribution,
# then the head's CPU side at 10 000 shapes on the host (cpu_ms). Tables:
# `python3 crates/ppr-bench/scripts/ab_table.py results projection,frame,cpu`.
for f in .gpu/*.gz; do gunzip -c "$f" > "${f%.gz}"; chmod +x "${f%.gz}"; done
source crates/ppr-bench/scripts/h200_env.sh
T0=$(date +%s)
left() { echo $(( ${BUDGET:-290} - ($(date +%s) - T0) )); }
run_bin() { local b=$1 tag=$2; local bin=.gpu/ppr-bench; [ $b != head ] && bin=.gpu/ppr-bench-$b
  [ -x $bin ] || return 0
  local l=$(left); [ $l -lt 20 ] && return 1
  step ${b}_${tag}_all $(( l < 60 ? l : 60 )) $bin runtime $C --frames 10 \
    --scene demo --scene kitchen --scene mirror-room-6 --scene collision-world --scene rooms-1000 --scene stairway-1000 \
    --resolution 1080p --resolution 4k --out $R/${b}_${tag}_all; }
run_bin base r1 && run_bin head r1 && run_bin head r2 && run_bin base r2 \
  && run_bin zinit r1 && run_bin deriv r1 && run_bin nobar r1 && run_bin forms r1 && {
  l=$(left); [ $l -gt 20 ] && step cpu10k $(( l < 45 ? l : 45 )) .gpu/ppr-bench runtime $C \
    --scene stairway-10000 --scene rooms-10000 --frames 10 --resolution 1080p --out $R/cpu10k; true; }
echo "total $(( $(date +%s) - T0 )) s"
