//! The runtime on the GPU (software adapter in CI) against CPU references and the exact
//! reflection of analytic scenes.

mod api;
mod confidence;
mod encoding_parity;
mod features;
mod glossy;
mod parallel_trees;
mod path_blockers;
mod plane_groups;
mod reflection;
mod reflection_quads;
mod subgroup_cull;
mod tiles;

/// This binary runs on the adapter `WGPU_BACKEND` names (llvmpipe through GL in CI).
fn select_backends() {}

/// Whether the adapter must have subgroups (the `subgroups` binary's lavapipe has).
const REQUIRE_SUBGROUPS: bool = false;
