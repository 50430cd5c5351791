//! Files the suites write: CSV, markdown tables, plots and image sheets.

pub mod causes_report;
pub mod compare_report;
pub mod csv_file;
pub mod frame_parts;
pub mod goals_report;
pub mod image_sheet;
pub mod markdown;
pub mod pipeline_stats_report;
pub mod plot;
pub mod runtime_report;
pub mod scaling_report;
pub mod trade_report;
