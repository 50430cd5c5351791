//! The markdown of `ppr-bench goals`: a summary, then one table per goal of the issue.

use std::path::PathBuf;

use crate::goals::checks::{Check, Goal, Verdicts};
use crate::report::markdown::MarkdownTable;

/// A check's value in its goal's unit.
fn value_text(c: &Check) -> String {
    match c.goal {
        Goal::Frame4k | Goal::Scaling1000 | Goal::Scaling10000 | Goal::CollisionWorld => {
            format!("{:.4} ms", c.value)
        }
        Goal::ProjectionFloor => format!("{:.1}×", c.value),
        Goal::CompareCost => format!("{:.2}×", c.value),
        Goal::ComparePsnr => format!("{:+.2} dB", c.value),
        Goal::SubLinear => format!("{:.2}", c.value),
    }
}

/// The report: which files, how many checks are met, and each goal's table (or why it has
/// none).
pub fn goals_markdown(verdicts: &Verdicts, files: &[PathBuf], has_baseline: bool) -> String {
    let checks = &verdicts.checks;
    let mut out = String::from("# Issue 13's goals, judged from the bench's CSV files\n\nFiles:\n\n");
    for f in files {
        out.push_str(&format!("- `{}`\n", f.display()));
    }
    let met = checks.iter().filter(|c| c.met).count();
    out.push_str(&format!("\n**{met} of {} checks met.** By goal:\n\n", checks.len()));
    for goal in Goal::ALL {
        let of: Vec<&Check> = checks.iter().filter(|c| c.goal == goal).collect();
        let state = if of.is_empty() && goal == Goal::ComparePsnr {
            "not judged (below)".to_owned()
        } else if of.is_empty() {
            "not measured in these files".to_owned()
        } else if of.iter().all(|c| c.met) {
            format!("**met** ({} of {})", of.len(), of.len())
        } else {
            format!("**missed** ({} of {} met)", of.iter().filter(|c| c.met).count(), of.len())
        };
        out.push_str(&format!("- {}: {state}\n", goal.title()));
    }
    for goal in Goal::ALL {
        out.push_str(&format!("\n## {}\n\n", goal.title()));
        let of: Vec<&Check> = checks.iter().filter(|c| c.goal == goal).collect();
        if goal == Goal::ComparePsnr {
            for n in &verdicts.notes {
                out.push_str(&format!("{n}\n\n"));
            }
        }
        if of.is_empty() {
            out.push_str(match goal {
                Goal::ComparePsnr if !has_baseline => {
                    "Not judged: give `--baseline-compare` (a compare run of the code to compare with).\n"
                }
                Goal::ComparePsnr => "Not judged: no scene and size comparable with the baseline.\n",
                _ => "Not measured: no rows for it in these files.\n",
            });
            continue;
        }
        let mut t = MarkdownTable::new(&["subject", "#measured", "verdict", "from"]);
        for c in of {
            t.push(vec![
                c.subject.clone(),
                value_text(c),
                if c.met { "met".into() } else { "missed".into() },
                c.detail.clone(),
            ]);
        }
        out.push_str(&t.render());
    }
    out
}
