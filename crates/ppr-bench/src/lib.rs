//! Benchmark runner for pixel-projected reflections: PPR against the exact reflection and
//! the baselines (accuracy against GPU time), the runtime's passes against their bandwidth
//! floor, cost against shape count, and the extractor's rectangles-against-coverage trade.
//!
//! [`cli::run_cli`] is what the binary calls: it parses the arguments into a
//! [`config::BenchConfig`] and one suite's configuration, runs the suite on a headless GPU
//! context, and writes its CSV, markdown and PNG files. Every suite is also a library
//! function (`suites::*::run_*`) returning its results.
//!
//! Techniques plug in by name ([`technique_spec::TechniqueSpec`]): each one is a
//! [`technique::BenchTechnique`] that records its passes and reports per-pass GPU times.

pub mod bandwidth;
pub mod bounce_reference;
pub mod buffer_readback;
pub mod camera_ranking;
pub mod cameras;
pub mod cli;
pub mod config;
pub mod error;
pub mod error_causes;
pub mod exact_reference;
pub mod frame_loop;
pub mod goals;
pub mod mirror_room;
pub mod pipeline_stats;
pub mod ppr_runner;
pub mod quality;
pub mod quality_pool;
pub mod report;
pub mod run_result;
pub mod scaling;
pub mod scene;
pub mod stats;
pub mod stereo_probe;
pub mod suites;
pub mod technique;
pub mod technique_spec;
pub mod timing;
pub mod trait_runner;
pub mod upload_probe;
pub mod write_probe;

pub use config::{BenchConfig, Resolution};
pub use error::BenchError;
pub use run_result::RunResult;
pub use scene::{BenchScene, SceneSpec};
pub use technique::{BenchTechnique, Family};
pub use technique_spec::TechniqueSpec;
