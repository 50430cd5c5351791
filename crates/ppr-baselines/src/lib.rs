//! The reflection techniques pixel-projected reflections are compared with, each a
//! [`ppr_testbed::ReflectionTechnique`] on the same inputs and output as the runtime
//! (colour `Rgba16Float` + depth `Depth32Float` in, reflection `Rgba16Float` out with
//! alpha 1 where one was found), so that swapping techniques is one line:
//!
//! - [`SsrTechnique`]: screen-space rays marched at pixel granularity
//!   ([`SsrSettings::brute_force`]) or in coarse steps with binary refinement
//!   ([`SsrSettings::low_quality`]);
//! - [`SsrGlossyTechnique`]: that march followed by a blur whose radius grows with each
//!   reflector's roughness and the hit distance ([`SsrGlossySettings`]), the glossy SSR of
//!   the kind Bevy and Godot ship;
//! - [`HiZSsrTechnique`]: rays walked through a min-depth pyramid ([`HiZPyramid`], its
//!   build timed apart);
//! - [`SsprTechnique`]: the screen-space planar reflection projection hash of Ghost Recon
//!   Wildlands, with its edge stretch as an option;
//! - [`PlanarReflectionTechnique`]: the scene rendered again from the mirrored camera of
//!   each plane: the quality ceiling, and a competitor on cost.
//!
//! The ray-marched techniques and SSPR read the reflector under each pixel from
//! [`ppr_testbed::ReflectionInputs::reflector_id`] and take its plane from the reflector
//! set (the comparison is on planar reflectors), so they need the testbed's G-buffer
//! inputs ([`ppr_testbed::ReflectionInputs::from_gbuffer`]).

pub mod error;
pub mod frame_data;
pub mod gpu_types;
pub mod hiz_pyramid;
pub mod hiz_technique;
pub mod passes;
pub mod planar_technique;
pub mod plane_table;
mod required_inputs;
pub mod settings;
pub mod shader;
pub mod sspr_technique;
pub mod ssr_glossy_technique;
pub mod ssr_technique;
pub mod timestamps;

pub use error::BaselineError;
pub use hiz_pyramid::HiZPyramid;
pub use hiz_technique::HiZSsrTechnique;
pub use planar_technique::PlanarReflectionTechnique;
pub use settings::{EdgeStretch, HiZSettings, SsprSettings, SsrGlossySettings, SsrSettings};
pub use sspr_technique::SsprTechnique;
pub use ssr_glossy_technique::SsrGlossyTechnique;
pub use ssr_technique::SsrTechnique;
