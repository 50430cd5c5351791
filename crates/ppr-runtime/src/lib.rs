//! Pixel-projected reflections on wgpu: what a game links.
pub mod camera;
pub use camera::{Camera, DepthMode, Projection};
