//! Integration tests of the bench: the library entry point end to end on the software
//! adapter (llvmpipe through wgpu's GL backend where there is no GPU).

mod bounces;
mod error_causes;
mod frame_parts;
mod glossy_compare;
mod goals;
mod mirror_rooms;
mod pipeline_stats;
mod quick_compare;
mod quick_scaling;
mod resolution_tiers;
mod scaling_levels;
mod shared_scenes;
mod upload_probe;
