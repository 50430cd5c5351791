#!/usr/bin/env bash
# Packs what a call on the lent GPU carries (../shared/gpu/README.md is the recipe): `.gl/`,
# the Vulkan and EGL loader packages, and `.gpu/`, a stripped and gzipped release
# `ppr-bench` (h200_env.sh unpacks it there), the shared scenes under `.gpu/scenes/`, and
# `.gpu/BUILT_FROM` naming the commit the binary was built from. Run it from anywhere in
# the repository; then call the device's `run` with carry [".gl", ".gpu"] and a command
# such as `bash crates/ppr-bench/scripts/h200_record36.sh compare collision`.
#
# A clean release build takes several minutes on the development machine: run it before
# the device is needed, and again only when the code changed.
set -euo pipefail
cd "$(git rev-parse --show-toplevel)"
SHARED=../shared
[ -d "$SHARED/scenes" ] && [ -d "$SHARED/gpu/debs" ] || { echo "pack_gpu: no $SHARED/scenes or $SHARED/gpu/debs beside the checkout" >&2; exit 1; }
EXCLUDE=$(git rev-parse --git-path info/exclude)
mkdir -p "$(dirname "$EXCLUDE")"
for p in /.gl/ /.gpu/; do grep -qxF "$p" "$EXCLUDE" 2>/dev/null || printf '%s\n' "$p" >> "$EXCLUDE"; done
mkdir -p .gl .gpu
cp -f "$SHARED"/gpu/debs/*.deb .gl/
cargo build --release -p ppr-bench
# Written beside the target and renamed, so that a failed step leaves the old binary whole.
strip -o .gpu/ppr-bench.stripped target/release/ppr-bench
gzip -c .gpu/ppr-bench.stripped > .gpu/ppr-bench.gz.part
mv .gpu/ppr-bench.gz.part .gpu/ppr-bench.gz
rm -f .gpu/ppr-bench.stripped .gpu/ppr-bench
rm -rf .gpu/scenes.part && cp -r "$SHARED/scenes" .gpu/scenes.part && rm -rf .gpu/scenes && mv .gpu/scenes.part .gpu/scenes
DIRTY=""
if [ -n "$(git status --porcelain --untracked-files=no)" ]; then DIRTY=" + uncommitted changes"; fi
echo "$(git rev-parse --short HEAD)$DIRTY, built $(date -u +%FT%TZ)" > .gpu/BUILT_FROM
SIZE=$(du -sk .gl .gpu | awk '{s += $1} END {print s}')
echo "packed: $(cat .gpu/BUILT_FROM); .gl + .gpu = $((SIZE / 1024)) MiB (the carry limit is 64 MiB)"
[ "$SIZE" -le $((64 * 1024)) ] || { echo "pack_gpu: over the carry limit" >&2; exit 1; }
