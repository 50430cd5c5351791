//! `ppr-bench goals`: issue 13's goals judged from the CSV files that `runtime` and
//! `compare` wrote (on the lent GPU), so that a record is read the same way every time:
//! which goals a run meets and by how much the others are missed.

pub mod bench_rows;
pub mod checks;

use std::path::PathBuf;

use crate::error::BenchError;
use crate::report::goals_report::goals_markdown;
use bench_rows::{CompareRow, RuntimeRow, csv_path, read_rows};
use checks::{Check, GoalInputs, check_goals};

/// The files a judgement reads.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GoalFiles {
    /// `runtime.csv` files (or the folders holding them): the demo's and the kitchen's
    /// frames, the generated levels' (`stairway-1000`, …).
    pub runtime: Vec<PathBuf>,
    /// `comparison.csv` files (or folders): the demo and the kitchen, collision-world.
    pub compare: Vec<PathBuf>,
    /// A `comparison.csv` of the code the PSNR goal compares with.
    pub baseline: Option<PathBuf>,
    pub psnr_tolerance_db: f64,
}

/// The checks and their markdown report.
#[derive(Clone, Debug, PartialEq)]
pub struct GoalJudgement {
    pub checks: Vec<Check>,
    /// What could not be judged and why.
    pub notes: Vec<String>,
    pub markdown: String,
}

/// Reads the files and judges every goal they measure.
///
/// # Errors
/// No file given, or a file that cannot be read (the error names it, the line and the
/// column).
pub fn judge_files(files: &GoalFiles) -> Result<GoalJudgement, BenchError> {
    if files.runtime.is_empty() && files.compare.is_empty() {
        return Err(BenchError::Spec("goals: give at least one --runtime or --compare file".into()));
    }
    let mut read: Vec<PathBuf> = Vec::new();
    let mut runtime: Vec<RuntimeRow> = Vec::new();
    for p in &files.runtime {
        let path = csv_path(p, "runtime.csv");
        runtime.extend(read_rows::<RuntimeRow>(&path)?);
        read.push(path);
    }
    let mut compare: Vec<CompareRow> = Vec::new();
    for p in &files.compare {
        let path = csv_path(p, "comparison.csv");
        compare.extend(read_rows::<CompareRow>(&path)?);
        read.push(path);
    }
    let baseline = match &files.baseline {
        Some(p) => {
            let path = csv_path(p, "comparison.csv");
            let rows = read_rows::<CompareRow>(&path)?;
            read.push(path);
            Some(rows)
        }
        None => None,
    };
    let verdicts = check_goals(&GoalInputs {
        runtime: &runtime,
        compare: &compare,
        baseline: baseline.as_deref(),
        psnr_tolerance_db: files.psnr_tolerance_db,
    });
    let markdown = goals_markdown(&verdicts, &read, files.baseline.is_some());
    Ok(GoalJudgement { checks: verdicts.checks, notes: verdicts.notes, markdown })
}
