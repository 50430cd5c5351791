//! Tools-side GPU harness for pixel-projected reflections: glTF levels to GPU meshes,
//! G-buffer raster, the exact mirrored-camera reference and its glossy counterpart
//! ([`GlossyParams`]), compositing, image I/O and metrics.
//!
//! Tests, the bench and the inspector use it; a game never links it.
//!
//! A frame: [`GpuContext::new_headless`], [`Level::load_gltf`] (or a [`SyntheticScene`]),
//! [`LevelRenderer::new`], then [`LevelRenderer::render`] for a camera; the main
//! [`GBuffer`] (colour, depth, normal, reflector id) and the [`ReferenceTargets`] (exact
//! reflection, reflected position, [`ReflectedPointClass`]) are then ready to read back
//! ([`readback`]), composite ([`CompositePass`]), write ([`image_io`]) and measure ([`metrics`]).

pub mod bounce_composite;
pub mod bounce_plan;
pub mod camera_spec;
pub mod composite;
pub mod depth_copy;
pub mod encoder_timer;
mod error;
pub mod frame_images;
pub mod gbuffer;
pub mod gbuffer_targets;
pub mod glossy_accumulate;
pub mod glossy_plan;
pub mod glossy_resolve;
pub mod glossy_views;
mod gltf_loader;
pub mod gpu;
pub mod image_io;
pub mod level;
pub mod metrics;
pub mod mirror_camera;
pub mod mirror_chain;
pub mod pixel_mask;
pub mod ppr_technique;
pub mod previous_frame_feed;
pub mod readback;
pub mod reference;
pub mod reflector_planes;
pub mod render_job;
pub mod renderer;
pub mod scene_layouts;
pub mod shape_meshes;
pub mod synthetic;
pub mod target_clear;
pub mod technique;
pub mod view;

pub use composite::{CompositeInputs, CompositeParams, CompositePass};
pub use error::TestbedError;
pub use frame_images::FrameImages;
pub use gbuffer::{GBUFFER_SURFACES, GBufferDraw, GBufferPass, ViewKind};
pub use gbuffer_targets::GBuffer;
pub use glossy_accumulate::GlossyStats;
pub use glossy_views::GlossyParams;
pub use gpu::GpuContext;
pub use image_io::ToneMap;
pub use level::{Level, LevelCamera, Material};
pub use metrics::ImageComparison;
pub use pixel_mask::PixelMask;
pub use ppr_scene_gpu::LevelMeshes;
pub use ppr_technique::PprTechnique;
pub use readback::U32Image;
pub use reference::{MirrorReference, ReferenceTargets, ReflectedPointClass};
pub use render_job::{RenderJob, RenderReport};
pub use renderer::{FrameSummary, LevelRenderer, RenderSettings};
pub use scene_layouts::SceneLayouts;
pub use synthetic::{FloorMirrorParams, SyntheticScene};
pub use target_clear::clear_target;
pub use technique::{ReflectionInputs, ReflectionTechnique, format_timings};
pub use view::{Lighting, ReflectorMaskParams, ViewBindings};
