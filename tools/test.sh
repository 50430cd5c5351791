#!/usr/bin/env bash
# The whole test suite, as the README and CI run it. GPU tests use Mesa's llvmpipe through
# wgpu's GL backend when no GPU is present (see README "Tests").
set -euo pipefail
cd "$(dirname "$0")/.."
# wgpu's default adapter choice puts Vulkan before GL among software adapters: with Mesa's
# lavapipe installed (CI installs it for bevy_ppr) the wgpu-30 tests would move from
# llvmpipe-GL, where their thresholds were measured, to lavapipe. Keep them on GL unless the
# caller names a backend. bevy_ppr's headless test asks Bevy for Vulkan itself.
export WGPU_BACKEND="${WGPU_BACKEND:-gl}"
cargo test --workspace --all-targets "$@"
# ppr-runtime-wgpu29's library is ppr-runtime's sources: their doc examples name
# `ppr_runtime` and run there (`doctest = false` does not stop an explicit --doc).
cargo test --workspace --doc --exclude ppr-runtime-wgpu29
