//! The "where a frame's time goes" table of `runtime.md`: each pass timed on its own as the
//! projection does more (empty, testing only, encoding without writing, writing without the
//! atomic, the real pass) and as the reflection does more (its launch, over nothing written,
//! mirrors only, no glossy blur, the real pass), from the `--projection-profile` rows that
//! time them.

use std::collections::BTreeMap;

use crate::goals::bench_rows::{RuntimeRow, split_label};
use crate::report::markdown::{MarkdownTable, ms};

/// The columns: header, profile row (`None`: the scene's default frame) and pass.
const COLUMNS: [(&str, Option<&str>, &str); 14] = [
    ("#whole frame", Some("frame span"), "frame"),
    ("#frame, projection empty", Some("frame span, empty"), "frame"),
    ("#classify", Some("classify own pass"), "classify"),
    ("#projection: empty", Some("empty, reflection own pass"), "projection"),
    ("#tests only", Some("tests only, reflection own pass"), "projection"),
    ("#no write", Some("no write, reflection own pass"), "projection"),
    ("#no atomic", Some("no atomic, reflection own pass"), "projection"),
    ("#default", Some("reflection own pass"), "projection"),
    ("#reflection: launch", Some("reflection: empty, reflection own pass"), "reflection"),
    ("#nothing written", Some("empty, reflection own pass"), "reflection"),
    ("#tests only", Some("tests only, reflection own pass"), "reflection"),
    ("#mirrors", Some("reflection: mirrors, reflection own pass"), "reflection"),
    ("#no glossy", Some("reflection: no glossy, reflection own pass"), "reflection"),
    ("#default", Some("reflection own pass"), "reflection"),
];

/// The table over `rows` (a `runtime.csv`'s), one line per scene, camera and size that has
/// any of its columns; `None` where no row has any.
pub fn frame_parts_table(rows: &[RuntimeRow]) -> Option<String> {
    // (scene, camera, width, height) in first-seen order → its columns' medians.
    let mut order = Vec::new();
    let mut found: BTreeMap<(String, String, u32, u32), [f64; COLUMNS.len()]> = BTreeMap::new();
    for r in rows {
        let (scene, row) = split_label(&r.scene);
        let Some(c) = COLUMNS.iter().position(|&(_, want, pass)| want == row && pass == r.pass) else {
            continue;
        };
        let key = (scene.to_owned(), r.camera.clone(), r.width, r.height);
        let cells = found.entry(key.clone()).or_insert_with(|| {
            order.push(key);
            [f64::NAN; COLUMNS.len()]
        });
        cells[c] = r.median_ms;
    }
    if order.is_empty() {
        return None;
    }
    let header: Vec<&str> = ["scene", "camera", "size"]
        .into_iter()
        .chain(COLUMNS.iter().map(|c| c.0))
        .chain(["#fixed part"])
        .collect();
    let mut table = MarkdownTable::new(&header);
    for key in &order {
        let cells = &found[key];
        // What the frame pays with the projection doing nothing: the empty projection's own
        // pass and the reflection over nothing written.
        let fixed = cells[3] + cells[9];
        let mut line = vec![key.0.clone(), format!("`{}`", key.1), format!("{}x{}", key.2, key.3)];
        line.extend(cells.iter().map(|&v| ms(v)));
        line.push(ms(fixed));
        table.push(line);
    }
    Some(format!(
        "Where a frame's time goes (`--projection-profile` rows that time each pass on its own, \
         ms; `–` where a row was not run). The projection's columns: it returns after its block \
         lists (`empty`), runs the shape tests (`tests only`), also encodes without writing \
         (`no write`), also loads, tests occlusion and encodes but leaves the atomicMin out \
         (`no atomic`; with nothing written no write loses at its load), and the real pass. \
         The reflection's: its launch (returning at once), over what each projection ablation \
         wrote (nothing for `empty` and `tests only`), mirrors only, the colour without the \
         glossy blur, and the real pass. Fixed part: the empty projection and the reflection \
         over nothing written.\n\n{}",
        table.render()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(scene: &str, pass: &str, median_ms: f64) -> RuntimeRow {
        RuntimeRow {
            scene: scene.into(),
            camera: "cam".into(),
            width: 3840,
            height: 2160,
            pass: pass.into(),
            median_ms,
            ratio_to_floor: f64::NAN,
        }
    }

    #[test]
    fn each_pass_lands_in_its_column_and_the_fixed_part_adds_the_empty_passes() {
        let rows = [
            row("demo", "projection + reflection", 0.3),
            row("demo [frame span]", "frame", 0.31),
            row("demo [empty, reflection own pass]", "projection", 0.02),
            row("demo [empty, reflection own pass]", "reflection", 0.09),
            row("demo [reflection own pass]", "projection", 0.15),
            row("demo [reflection own pass]", "reflection", 0.16),
            row("demo [no atomic]", "projection + reflection", 0.25),
            row("demo [no atomic, reflection own pass]", "projection", 0.12),
        ];
        let md = frame_parts_table(&rows).expect("a table");
        let line = md.lines().find(|l| l.starts_with("| demo")).expect("the demo's line");
        let cells: Vec<&str> = line.split('|').map(str::trim).filter(|c| !c.is_empty()).collect();
        // scene, camera, size, then the columns in order, then the fixed part.
        assert_eq!(cells[3], "0.310");
        assert_eq!(cells[4], "–", "no `frame span, empty` row was run");
        assert_eq!(cells[6], "0.020");
        assert_eq!(cells[9], "0.120");
        assert_eq!(cells[10], "0.150");
        assert_eq!(cells[12], "0.090");
        assert_eq!(cells[16], "0.160");
        assert_eq!(cells[17], "0.110");
        assert_eq!(md.lines().filter(|l| l.starts_with("| demo")).count(), 1);
    }

    #[test]
    fn no_table_without_its_rows() {
        assert!(frame_parts_table(&[row("demo", "projection + reflection", 0.3)]).is_none());
    }
}
