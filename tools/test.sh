#!/usr/bin/env bash
# The whole test suite, as the README and CI run it. GPU tests use Mesa's llvmpipe through
# wgpu's GL backend when no GPU is present (see README "Tests").
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace --all-targets "$@"
cargo test --workspace --doc
