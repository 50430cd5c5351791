//! Integration tests of ppr-testbed (one binary). GPU tests run on whatever adapter wgpu
//! finds (llvmpipe through GL on CI) and fail when there is none.

mod common;
mod composite_tests;
mod cpu_trace;
mod demo_level_tests;
mod fused_layer_tests;
mod glossy_reference_tests;
mod gltf_tests;
mod image_tests;
mod layer_tiles_tests;
mod ppr_tests;
mod reference_tests;
mod render_tests;
mod target_clear_tests;
