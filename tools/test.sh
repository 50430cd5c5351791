#!/usr/bin/env bash
# The whole test suite, as the README and CI run it. GPU tests use Mesa's llvmpipe through
# wgpu's GL backend when no GPU is present (see README "Tests").
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace --all-targets "$@"
# ppr-runtime-wgpu29's library is ppr-runtime's sources: their doc examples name
# `ppr_runtime` and run there (`doctest = false` does not stop an explicit --doc).
cargo test --workspace --doc --exclude ppr-runtime-wgpu29
