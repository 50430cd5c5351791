//! A glTF level on the GPU, shared by the tools that draw levels themselves (the testbed
//! and the walkthrough): one place for what both need, so neither keeps a copy.
//!
//! - [`LevelData`] (`level_data.rs`, `scene_import.rs`, `level_camera.rs`): the level on the
//!   CPU, from `ppr-level`'s `Scene` or built in code, with its cameras;
//! - [`LevelMeshes`] (`level_meshes.rs`, `material_textures.rs`): the level uploaded, drawn
//!   camera-relative with each pass's [`SurfaceRules`];
//! - [`SceneLayouts`], [`scene_raster`] and `shaders/scene_raster.wgsl`: the bind-group
//!   layouts, pipelines, render pass and WGSL a scene raster pass is built from;
//!   [`layout_entries`] for every pass's bind-group layouts;
//! - [`screen_pass`]: the full-screen triangle of the screen passes;
//! - [`Lighting`]: the sun and ambient both passes light with;
//! - [`Target`] and the colour and depth formats the runtime reads;
//! - [`request_device`]: adapter, device and queue;
//! - [`camera_spec`]: `--camera` by name or as `eye=...;target=...;fov=...`.
//!
//! Architecture invariant: it depends on `ppr-level` and `ppr-runtime` only among the
//! workspace's crates (no testbed, extractor or UI), so the walkthrough can link it as a
//! game would link its own renderer.

pub mod camera_spec;
mod error;
pub mod gpu_device;
pub mod layout_entries;
pub mod level_camera;
pub mod level_data;
pub mod level_meshes;
pub mod lighting;
mod material_textures;
pub mod render_target;
mod scene_import;
pub mod scene_layouts;
pub mod scene_raster;
pub mod screen_pass;

pub use camera_spec::{CameraPick, ProjectionChoice, parse_camera, pick_camera};
pub use error::{CameraSpecError, GpuInitError};
pub use gpu_device::{DeviceRequest, GpuDevice, request_device};
pub use level_camera::LevelCamera;
pub use level_data::{LevelData, LevelTexture, Material, Mesh, MeshInstance, MeshPrimitive, Vertex};
pub use level_meshes::{DrawUniform, FaceCulling, LevelMeshes, MaterialUniform, MeshDraw, SurfaceRules};
pub use lighting::Lighting;
pub use render_target::{COLOR_FORMAT, DEPTH_FORMAT, Target};
pub use scene_layouts::{SceneLayouts, uniform_stride};
