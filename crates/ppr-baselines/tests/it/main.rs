//! Integration tests of ppr-baselines (one binary). GPU tests run on whatever adapter wgpu
//! finds (llvmpipe through GL here) and fail when there is none.

mod common;
mod hiz_tests;
mod planar_tests;
mod scenes;
mod sspr_tests;
mod ssr_glossy_tests;
mod ssr_tests;
mod technique_tests;
