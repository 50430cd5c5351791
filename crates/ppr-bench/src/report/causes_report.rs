//! Full PPR's error by cause: `comparison_causes.csv` (one row per camera, size, technique
//! and cause) and the section of `comparison.md` (pooled over each scene's cameras).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use crate::config::Resolution;
use crate::error_causes::{Cause, CauseRow, ErrorBreakdown, Group};
use crate::report::csv_file::{CsvTable, num};
use crate::report::markdown::MarkdownTable;

/// Columns of `comparison_causes.csv`.
pub const CAUSE_COLUMNS: [&str; 14] = [
    "scene",
    "camera",
    "width",
    "height",
    "technique",
    "score",
    "cause",
    "pixels",
    "pixel_share",
    "squared_error",
    "error_share",
    "score_psnr_db",
    "psnr_without_db",
    "parallel_rule",
];

/// `comparison_causes.csv`: shares are of the cause's score (on-screen or off-screen
/// reflector pixels), the PSNR is that score's, and without the cause's error.
pub fn causes_csv(rows: &[CauseRow]) -> CsvTable {
    let mut t = CsvTable::new(&CAUSE_COLUMNS);
    for r in rows {
        for cause in Cause::ALL {
            let b = &r.breakdown;
            t.push(vec![
                r.scene.clone(),
                r.camera.clone(),
                r.resolution.width.to_string(),
                r.resolution.height.to_string(),
                r.technique.clone(),
                cause.group().as_str().into(),
                cause.as_str().into(),
                b.pixels_of(cause).to_string(),
                num(b.pixel_share(cause), 5),
                num(b.error_of(cause), 4),
                num(b.error_share(cause), 5),
                num(b.psnr(cause.group()), 3),
                num(b.psnr_without(cause), 3),
                if b.parallel_rule { "on" } else { "off" }.into(),
            ]);
        }
    }
    t
}

/// Breakdowns pooled over each scene's cameras, by scene, size and technique.
pub fn pooled(rows: &[CauseRow]) -> BTreeMap<(String, Resolution, String), (ErrorBreakdown, usize)> {
    let mut out: BTreeMap<(String, Resolution, String), (ErrorBreakdown, usize)> = BTreeMap::new();
    for r in rows {
        let e = out.entry((r.scene.clone(), r.resolution, r.technique.clone())).or_default();
        e.0.add(&r.breakdown);
        e.1 += 1;
    }
    out
}

/// The section of `comparison.md` (empty without breakdowns).
pub fn causes_markdown(rows: &[CauseRow]) -> String {
    if rows.is_empty() {
        return String::new();
    }
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Where full PPR's error comes from\n\n\
         Every reflector pixel gets one cause and its squared error, as the scores above count it \
         (the reflection over the scene-colour fallback by its alpha), goes to that cause; pooled \
         over the scene's cameras (`comparison_causes.csv` has each camera). Off-screen pixels \
         (what no screen-space method can see): the reflected point is *hidden in the main view* \
         (inside the viewport, another surface in front), *outside the view*, or the *background*. \
         On-screen pixels take the first that applies, from four untimed renders of the frame (raw, \
         hole filling, full without the border fade, full) and raw PPR's intermediate buffer: the \
         surface point is *outside the fitted rectangle*; the *border fade* costs more than half of \
         the pixel's error; the *parallel rule* lost it (empty unless the plan had the rule on, \
         as each table's first line says: `PlanParams::parallel_rule` is never on by `Auto`); raw PPR had no data and hole filling supplied it (*hole \
         filled*) or nothing did (*hole left*); raw PPR's source pixel is more than a pixel from \
         where the exact reflected point projects (*wrong source*: an occluder missed or a wrong \
         surface won); filtering and anti-bleeding raised the error by more than half of it \
         (*filtered*); else the *right source*, whose error is sampling and view-dependent shading. \
         Shares are of the score's pixels and squared error; \"PSNR without\" is the score's PSNR \
         (of its pooled mean squared error, so not the mean of the cameras' PSNRs above) with that \
         cause's pixels exact.\n"
    );
    for ((scene, res, technique), (b, cameras)) in pooled(rows) {
        let _ = writeln!(
            md,
            "### {scene}, {res}, `{technique}` ({cameras} camera{})\n",
            if cameras == 1 { "" } else { "s" }
        );
        let _ = writeln!(
            md,
            "On screen {:.2} dB over {} pixels; off screen {:.2} dB over {} pixels; parallel rule {}. \
             Largest on-screen error: {}.\n",
            b.psnr(Group::OnScreen),
            b.group_pixels(Group::OnScreen),
            b.psnr(Group::OffScreen),
            b.group_pixels(Group::OffScreen),
            if b.parallel_rule { "on" } else { "off" },
            dominant(&b).map_or("none".into(), |c| format!(
                "{} ({:.0} %)",
                c.as_str(),
                100.0 * b.error_share(c)
            )),
        );
        let mut t = MarkdownTable::new(&["score", "cause", "#pixels %", "#error %", "#PSNR without (dB)"]);
        for cause in Cause::ALL {
            t.push(vec![
                cause.group().as_str().into(),
                cause.as_str().into(),
                format!("{:.1}", 100.0 * b.pixel_share(cause)),
                format!("{:.1}", 100.0 * b.error_share(cause)),
                num(b.psnr_without(cause), 2),
            ]);
        }
        md.push_str(&t.render());
        let _ = writeln!(md);
    }
    md
}

/// The on-screen cause with the largest error, if any has error.
pub fn dominant(b: &ErrorBreakdown) -> Option<Cause> {
    Cause::ALL
        .into_iter()
        .filter(|c| c.group() == Group::OnScreen && b.error_of(*c) > 0.0)
        .max_by(|a, c| b.error_of(*a).total_cmp(&b.error_of(*c)))
}
