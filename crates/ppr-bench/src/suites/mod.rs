//! The bench's suites, one per question.

pub mod compare;
pub mod extract_trade;
pub mod pipeline_stats;
pub mod runtime;
pub mod scaling;
