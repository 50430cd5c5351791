#!/usr/bin/env bash
# Not run yet: the bounce rows of docs/perf/comparison.md ("Mirror facing mirror") on the
# lent H200, with the same carried files as h200.sh (`.gl` loader debs, `.gpu/ppr-bench`,
# `.gpu/scenes/`); results go to $OUT/results.tar.gz. One device call (the `rooms` step of
# h200.sh took under 330 s with as many scored rows).
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export WGPU_BACKEND=vulkan
ICD=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -f "$ICD" ]; then export VK_DRIVER_FILES=$ICD; fi
R=/tmp/results
mkdir -p "$R"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem --format=csv > "$R/nvidia-smi.txt" 2>&1
timeout 540 .gpu/ppr-bench compare --scenes-dir .gpu/scenes --out $R/bounces \
  --scene mirror-room --scene mirror-room-6 --scene mirror-corridor --resolution 4k --frames 20 \
  --technique ppr --technique ppr:reference-bounces=2 --technique ppr:bounces=2 \
  --technique ppr:tier=half,bounces=2 --technique ssr-brute:reference-bounces=2 \
  --technique exact --technique exact:bounces=2 > "$R/bounces.log" 2>&1
echo "bounces rc=$?"; tail -n 2 "$R/bounces.log"
tar czf "$OUT/results.tar.gz" -C /tmp results
