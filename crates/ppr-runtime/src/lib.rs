//! Pixel-projected reflections on wgpu: what a game links.
//!
//! A game creates a [`ReflectionRenderer`] once, gives it a [`ppr_format::ReflectorSet`],
//! and per frame calls [`ReflectionRenderer::prepare`] (CPU: cull, plan, upload) and
//! [`ReflectionRenderer::encode`] (GPU: clear, projection, reflection passes) with its
//! colour and depth. The passes follow Cichocki's "Optimized pixel-projected
//! reflections for planar reflectors"; see `encoding` for where and why they differ.
//!
//! This crate does no file I/O and knows nothing about glTF or any UI.

pub mod camera;
pub mod encoding;
mod frame_buffers;
mod frame_upload;
pub mod gpu_types;
pub mod passes;
pub mod plan;
mod reduced_targets;
pub mod renderer;
pub mod settings;
pub mod shader;
pub mod shape_tests;
pub mod shapes;
pub mod source_box;
pub mod timestamps;

pub use camera::{Camera, DepthMode, Projection};
pub use encoding::{CLEAR_VALUE, EncodingLayout};
pub use passes::reflection::OUTPUT_FORMAT;
pub use plan::{Choice, FramePlan, PlanParams, ScreenRect};
pub use renderer::{FrameInputs, ReflectionRenderer, RendererDesc};
pub use settings::{ReflectionSettings, ResolutionTier, WriteMode};
pub use timestamps::PassTimings;
