//! Harness of the workspace-level end-to-end tests: a headless GPU device, analytic scenes
//! ray-cast on the CPU (colour, depth and the exact reflection), and a runner that feeds
//! them to `ppr-runtime` and reads everything back.
//!
//! Test targets: `it/` (the runtime against the exact reflection: encoding parity,
//! quality, artefacts, tiles) and `stability/` (hard cases; see docs/stability.md).

pub mod gpu;
pub mod harness;
pub mod masks;
pub mod random_scenes;
pub mod scene;
pub mod views;
