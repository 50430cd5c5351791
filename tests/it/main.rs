//! The runtime on the GPU (software adapter in CI) against CPU references and the exact
//! reflection of analytic scenes.

mod api;
mod confidence;
mod encoding_parity;
mod features;
mod glossy;
mod parallel_trees;
mod plane_groups;
mod reflection;
mod tiles;
