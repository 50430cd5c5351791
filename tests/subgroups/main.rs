//! The runtime's Vulkan-only paths on Mesa's lavapipe without a GPU (`.ci/run` installs
//! Debian's mesa-vulkan-drivers when missing): subgroup culling (the `it` binary runs the
//! same tests on llvmpipe through GL, without subgroup operations) and the frame upload
//! bound where it is written (GL has no mappable bindable buffers).

#[path = "../it/bound_upload.rs"]
mod bound_upload;
#[path = "../it/subgroup_cull.rs"]
mod subgroup_cull;

/// Every test of this binary asks for Vulkan (lavapipe) before the device opens.
fn select_backends() {
    ppr_tests::gpu::use_backends(wgpu::Backends::VULKAN);
}

/// The adapter must have subgroups: a device without them would test the fallback only.
const REQUIRE_SUBGROUPS: bool = true;
