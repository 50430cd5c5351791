//! The runtime's subgroup paths on an adapter that has subgroups: Mesa's lavapipe through
//! Vulkan without a GPU (`.ci/run` installs Debian's mesa-vulkan-drivers when missing). The
//! `it` binary runs the same tests on llvmpipe through GL, without subgroup operations.

#[path = "../it/subgroup_cull.rs"]
mod subgroup_cull;

/// Every test of this binary asks for Vulkan (lavapipe) before the device opens.
fn select_backends() {
    ppr_tests::gpu::use_backends(wgpu::Backends::VULKAN);
}

/// The adapter must have subgroups: a device without them would test the fallback only.
const REQUIRE_SUBGROUPS: bool = true;
