#!/usr/bin/env bash
# Every ppr-bench suite on the lent H100 (recipe: shared/gpu/README.md). Run from the
# repository root on the device, with `.gl` (loader debs) and `.gpu` (the release binary
# `.gpu/ppr-bench` and the shared scenes under `.gpu/scenes/`) carried; results go to $OUT.
#   smoke: one frame of each suite at 1080p (start-up check and timing estimates)
#   full:  every suite (docs/perf/runtime.md, scaling.md, extract_trade.md)
#   compare: runtime again (a same-run check) and the comparison (docs/perf/comparison.md)
set -u
MODE=${1:-full}
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export WGPU_BACKEND=vulkan
ICD=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -f "$ICD" ]; then export VK_DRIVER_FILES=$ICD; fi
if ! ldconfig -p | grep -q libvulkan; then echo "no vulkan loader"; fi
B=.gpu/ppr-bench
C="--scenes-dir .gpu/scenes"
R=$OUT/results
mkdir -p "$R"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem,temperature.gpu --format=csv > "$R/nvidia-smi.txt" 2>&1
step() { # name, seconds, command...
  local name=$1 limit=$2; shift 2
  local t0=$(date +%s)
  timeout "$limit" "$@" > "$R/$name.log" 2>&1
  local rc=$?
  echo "$name rc=$rc $(( $(date +%s) - t0 )) s"
  tail -n 3 "$R/$name.log"
}
if [ "$MODE" = smoke ]; then
  F="--frames 1 --warmup 0"
  step compare 150 $B compare $C $F --out $R/compare --scene demo --scene kitchen --resolution 1080p --resolution 4k
  step runtime 60 $B runtime $C $F --out $R/runtime --resolution 1080p
  step scaling 90 $B scaling $C $F --out $R/scaling --resolution 1920x1080 --counts 1,1000,10000 --threshold-counts 1 --coverages 0.5
  step trade 60 $B extract-trade $C $F --out $R/trade --resolution 1080p --scene demo --scene kitchen
elif [ "$MODE" = compare ]; then
  step runtime 45 $B runtime $C --out $R/runtime
  step compare 300 $B compare $C --out $R/compare --scene demo --scene kitchen --scene small
else
  step runtime 45 $B runtime $C --out $R/runtime
  step compare 320 $B compare $C --out $R/compare --scene demo --scene kitchen --scene small
  step scaling 175 $B scaling $C --out $R/scaling
  step trade 75 $B extract-trade $C --out $R/trade
fi
cd "$OUT" && tar czf results.tgz results && rm -rf results
