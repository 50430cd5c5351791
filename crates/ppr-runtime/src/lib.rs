//! Pixel-projected reflections on wgpu: what a game links.
//!
//! A game creates a [`ReflectionRenderer`] once, gives it a [`ppr_format::ReflectorSet`],
//! and per frame calls [`ReflectionRenderer::prepare`] (CPU: cull, plan, upload) and
//! [`ReflectionRenderer::encode`] (GPU: clear, projection, reflection passes) with its
//! colour and depth. The passes follow Cichocki's "Optimized pixel-projected
//! reflections for planar reflectors"; see `encoding` for where and why they differ.
//!
//! This crate does no file I/O and knows nothing about glTF or any UI.

// The game-facing API is what the crate root re-exports below. The modules are public for
// the workspace's tests, bench and debug views (CPU references of the encoding, the shape
// table, the passes and their WGSL) but hidden from the documentation: they are not part
// of the API a game should build on.
#[doc(hidden)]
pub mod camera;
#[doc(hidden)]
pub mod encoding;
mod frame_buffers;
mod frame_upload;
mod glossy;
#[doc(hidden)]
pub mod gpu_types;
#[doc(hidden)]
pub mod parallel_trees;
mod pass_layout;
#[doc(hidden)]
pub mod passes;
pub mod path_blockers;
#[cfg(feature = "pipeline-log")]
#[doc(hidden)]
pub mod pipeline_log;
#[doc(hidden)]
pub mod plan;
#[doc(hidden)]
pub mod plane_groups;
mod reduced_targets;
#[doc(hidden)]
pub mod renderer;
#[doc(hidden)]
pub mod settings;
#[doc(hidden)]
pub mod shader;
#[doc(hidden)]
pub mod shape_tests;
#[doc(hidden)]
pub mod shapes;
#[doc(hidden)]
pub mod source_box;
mod stereo;
#[doc(hidden)]
pub mod timestamps;
// Reused staging buffers for the frame uploads.
#[cfg(test)]
mod test_device;
mod upload_layout;
mod upload_ring;
mod wgpu_compat;

pub use camera::{Camera, CameraError, DepthMode, Projection};
pub use encoding::{CLEAR_VALUE, EncodingLayout};
pub use passes::layer_reflection::LayerPlacement;
pub use passes::projection::{Ablation, BoxReduction};
pub use passes::reflection::{OUTPUT_FORMAT, ReflectionAblation};
pub use passes::upsample::UpsampleProbe;
pub use plan::{Choice, FramePlan, PlanParams, ScreenRect, TestedEntry};
pub use renderer::{DebugOptions, FrameInputs, ReflectionRenderer, RendererDesc, TILE_LOOP_GROUPS};
pub use settings::{ReflectionSettings, ResolutionTier, WriteMode};
pub use timestamps::PassTimings;
