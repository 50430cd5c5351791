# Sourced by the h200*.sh scripts (from the repository root on the lent H200, `.gl` and
# `.gpu` carried): the Vulkan loader from the carried debs, the binary and scene paths,
# the results folder, the GPU's name and driver, and `step NAME LIMIT CMD...`, which runs a
# command under a time limit into $R/NAME.log and packs $OUT/results.tar.gz again after
# each step, so that a call cut short still brings back what it measured.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export WGPU_BACKEND=vulkan
ICD=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -f "$ICD" ]; then export VK_DRIVER_FILES=$ICD; fi
B=.gpu/ppr-bench
# The binary may travel gzipped (the carry limit is 64 MiB).
if [ -f "$B.gz" ] && [ ! -x "$B" ]; then gunzip -c "$B.gz" > "$B" && chmod +x "$B"; fi
C="--scenes-dir .gpu/scenes"
R=/tmp/results
mkdir -p "$R"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem --format=csv > "$R/nvidia-smi.txt" 2>&1
step() { local name=$1 limit=$2; shift 2; local t0=$(date +%s)
  timeout "$limit" "$@" > "$R/$name.log" 2>&1; local rc=$?
  echo "$name rc=$rc $(( $(date +%s) - t0 )) s"; tail -n 2 "$R/$name.log"
  tar czf "$OUT/results.tar.gz" -C /tmp results; }
