//! `pipeline_stats.csv` (every statistic of every executable) and `pipeline_stats.md` (one
//! row per pipeline executable, one column per statistic, registers and memory first).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::BenchError;
use crate::pipeline_stats::spirv::nvidia_sm90_workgroups_by_registers;
use crate::pipeline_stats::statistic::{StatValue, usefulness};

/// The NVIDIA driver's name of the register count.
const REGISTER_COUNT: &str = "Register Count";
use crate::report::csv_file::CsvTable;
use crate::report::markdown::MarkdownTable;
use crate::suites::pipeline_stats::{PipelineStatsOutcome, constants_text};

/// Writes both files under `dir` (each to a temporary file, then renamed).
///
/// # Errors
/// A file cannot be written.
pub fn write_pipeline_stats_report(
    dir: &Path,
    outcome: &PipelineStatsOutcome,
    command: &str,
) -> Result<Vec<PathBuf>, BenchError> {
    std::fs::create_dir_all(dir).map_err(|e| BenchError::io(dir, e))?;
    let csv_path = dir.join("pipeline_stats.csv");
    write(&csv_path, &csv(outcome).to_text())?;
    let md_path = dir.join("pipeline_stats.md");
    write(&md_path, &markdown(outcome, command))?;
    Ok(vec![csv_path, md_path])
}

fn write(path: &Path, text: &str) -> Result<(), BenchError> {
    ppr_format::write_atomically(path, text.as_bytes()).map_err(|e| BenchError::io(path, e))
}

/// One row per statistic.
pub fn csv(outcome: &PipelineStatsOutcome) -> CsvTable {
    let mut csv =
        CsvTable::new(&["pipeline", "entry_point", "constants", "executable", "statistic", "value"]);
    for p in &outcome.pipelines {
        let constants = constants_text(&p.pipeline);
        for e in &p.executables {
            for s in &e.statistics {
                csv.push(vec![
                    p.pipeline.label.clone(),
                    p.pipeline.entry_point.clone(),
                    constants.clone(),
                    e.name.clone(),
                    s.name.clone(),
                    s.value.to_string(),
                ]);
            }
        }
    }
    csv
}

/// The statistic names in column order: the most useful for occupancy first, then as the
/// driver listed them; with each one's description.
pub fn statistic_columns(outcome: &PipelineStatsOutcome) -> Vec<(String, String)> {
    let mut columns: Vec<(String, String)> = Vec::new();
    for s in outcome.pipelines.iter().flat_map(|p| &p.executables).flat_map(|e| &e.statistics) {
        if !columns.iter().any(|(n, _)| *n == s.name) {
            columns.push((s.name.clone(), s.description.clone()));
        }
    }
    // Stable: within a rank, the driver's order.
    columns.sort_by_key(|(n, _)| usefulness(n));
    columns
}

/// The markdown report.
pub fn markdown(outcome: &PipelineStatsOutcome, command: &str) -> String {
    let columns = statistic_columns(outcome);
    let mut header = vec!["pipeline".to_owned(), "entry".to_owned(), "executable".to_owned()];
    header.extend(columns.iter().map(|(n, _)| format!("#{n}")));
    header.push("#declared workgroup B".to_owned());
    header.push("#workgroups per SM by registers (sm_90)".to_owned());
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut table = MarkdownTable::new(&header);
    for p in &outcome.pipelines {
        for e in &p.executables {
            let mut row = vec![p.pipeline.label.clone(), p.pipeline.entry_point.clone(), e.name.clone()];
            for (name, _) in &columns {
                let value = e.statistics.iter().find(|s| s.name == *name);
                row.push(value.map_or("–".into(), |s| s.value.to_string()));
            }
            row.push(p.declared_workgroup_bytes.to_string());
            let registers =
                e.statistics.iter().find(|s| s.name == REGISTER_COUNT).and_then(|s| match s.value {
                    StatValue::Int(v) => u32::try_from(v).ok(),
                    StatValue::Uint(v) => u32::try_from(v).ok(),
                    _ => None,
                });
            row.push(registers.map_or("–".into(), |r| {
                nvidia_sm90_workgroups_by_registers(r, p.workgroup_threads).to_string()
            }));
            table.push(row);
        }
    }
    let mut md = String::new();
    let _ = writeln!(md, "# Pipeline statistics: what the driver compiled\n");
    let _ = writeln!(md, "Vulkan device: **{}**.\n", outcome.vulkan_device);
    let _ = writeln!(
        md,
        "Pipelines logged on {} from {} frame(s) at {}, compiled again from their WGSL (naga, \
         wgpu's SPIR-V options) with `VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR`; the \
         constants of each are in `pipeline_stats.csv`.\n",
        outcome.adapter, outcome.frames, outcome.resolution
    );
    let _ = writeln!(md, "Command:\n\n```sh\n{command}\n```\n");
    if table.is_empty() {
        let _ = writeln!(md, "No pipeline statistics.\n");
    } else {
        md.push_str(&table.render());
        let _ = writeln!(md);
    }
    for (name, description) in &columns {
        let _ = writeln!(md, "- **{name}**: {description}");
    }
    let _ = writeln!(
        md,
        "- **declared workgroup B**: the workgroup variables the WGSL entry point refers to; \
         shared memory beyond it is the driver's own (NVIDIA spills registers there).\n\
         - **workgroups per SM by registers (sm_90)**: workgroups that fit on an H100/H200 \
         multiprocessor by the register count and 2 048 invocations alone (64 Ki registers, \
         allocated in steps of 8 per invocation); shared memory may allow fewer, and what it \
         takes of the 256 KiB it shares with L1 is L1 lost.\n\
         - NVIDIA's driver reports **Local Memory Size** as 2^36 plus the size; read the low \
         32 bits."
    );
    if !outcome.notes.is_empty() {
        let _ = writeln!(md, "\nNotes:\n");
        for n in &outcome.notes {
            let _ = writeln!(md, "- {n}");
        }
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Resolution;
    use crate::pipeline_stats::statistic::{ExecutableStats, StatValue, Statistic};
    use crate::suites::pipeline_stats::PipelineStats;
    use ppr_runtime::pipeline_log::PipelineSource;

    fn stat(name: &str, value: StatValue) -> Statistic {
        Statistic { name: name.into(), description: format!("{name} described"), value }
    }

    #[test]
    fn one_csv_row_per_statistic_and_registers_first_in_the_table() {
        let pipeline = PipelineSource {
            label: "ppr projection".into(),
            source: String::new(),
            entry_point: "main".into(),
            constants: vec![("TILE_CULLING".into(), 1.0), ("ABLATION".into(), 0.0)],
        };
        let executable = ExecutableStats {
            name: "Compute Shader".into(),
            description: String::new(),
            subgroup_size: 32,
            statistics: vec![
                stat("Instruction Count", StatValue::Uint(1234)),
                stat("Binary Size", StatValue::Uint(9000)),
                stat("Register Count", StatValue::Uint(40)),
                stat("Uses Barriers", StatValue::Bool(true)),
            ],
        };
        let outcome = PipelineStatsOutcome {
            adapter: "adapter".into(),
            vulkan_device: "device".into(),
            resolution: Resolution::UHD,
            frames: 1,
            pipelines: vec![PipelineStats {
                pipeline,
                executables: vec![executable],
                workgroup_threads: 256,
                declared_workgroup_bytes: 1336,
            }],
            notes: vec!["a note".into()],
        };
        let table = csv(&outcome);
        assert_eq!(table.rows.len(), 4);
        assert_eq!(
            table.rows[2],
            ["ppr projection", "main", "TILE_CULLING=1;ABLATION=0", "Compute Shader", "Register Count", "40"]
        );
        let md = markdown(&outcome, "ppr-bench pipeline-stats");
        let header = md.lines().find(|l| l.starts_with("| pipeline")).expect("table header");
        assert_eq!(
            header,
            "| pipeline | entry | executable | Register Count | Instruction Count | Binary Size | Uses Barriers \
             | declared workgroup B | workgroups per SM by registers (sm_90) |"
        );
        // 40 registers a invocation of 256: six workgroups.
        assert!(
            md.contains("| ppr projection | main | Compute Shader | 40 | 1234 | 9000 | true | 1336 | 6 |"),
            "{md}"
        );
        assert!(md.contains("- **Register Count**: Register Count described") && md.contains("- a note"));
    }
}
