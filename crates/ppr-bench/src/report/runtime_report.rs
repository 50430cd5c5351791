//! `runtime.md` and `runtime.csv`: each pass's GPU time against its bandwidth floor.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::BenchError;
use crate::goals::bench_rows::RuntimeRow;
use crate::report::csv_file::{CsvTable, num};
use crate::report::frame_parts::frame_parts_table;
use crate::report::markdown::{MarkdownTable, ms};
use crate::suites::runtime::RuntimeOutcome;

/// Writes the report files under `dir`.
///
/// # Errors
/// A file cannot be written.
pub fn write_runtime_report(
    dir: &Path,
    outcome: &RuntimeOutcome,
    command: &str,
) -> Result<Vec<PathBuf>, BenchError> {
    std::fs::create_dir_all(dir).map_err(|e| BenchError::io(dir, e))?;
    let mut csv = CsvTable::new(&[
        "scene",
        "camera",
        "width",
        "height",
        "visible_shapes",
        "indirect",
        "active_tiles",
        "tiles",
        "written_pixels",
        "pass",
        "median_ms",
        "p95_ms",
        "frames",
        "timing_source",
        "bytes",
        "floor_ms",
        "ratio_to_floor",
        "adapter",
        "cpu_ms",
    ]);
    let mut table = MarkdownTable::new(&[
        "scene",
        "camera",
        "size",
        "#visible",
        "#active tiles",
        "pass",
        "#median ms",
        "#p95 ms",
        "#MB moved",
        "#floor ms",
        "#× floor",
        "#CPU ms",
    ]);
    let bw = outcome.bandwidth;
    for r in &outcome.rows {
        let [w, h] = r.resolution.size();
        let mut total_bytes = 0;
        for (pass, s) in r.timings.passes() {
            let bytes = pass_bytes_of(&r.bytes, &pass);
            total_bytes += bytes.unwrap_or(0);
            let floor = match (bw, bytes) {
                (Some(bw), Some(b)) => bw.floor_ms(b),
                _ => f64::NAN,
            };
            csv.push(vec![
                r.scene.clone(),
                r.camera.clone(),
                w.to_string(),
                h.to_string(),
                r.visible.to_string(),
                r.facts.indirect.to_string(),
                r.facts.active_tiles.to_string(),
                r.facts.tiles.to_string(),
                r.facts.written_pixels.to_string(),
                pass.clone(),
                num(s.median, 4),
                num(s.p95, 4),
                s.count.to_string(),
                r.source.as_str().into(),
                bytes.map_or("0".into(), |b| b.to_string()),
                num(floor, 4),
                num(s.median / floor, 2),
                outcome.adapter.clone(),
                num(r.cpu_ms, 4),
            ]);
            table.push(vec![
                r.scene.clone(),
                r.camera.clone(),
                r.resolution.to_string(),
                r.visible.to_string(),
                format!("{} / {}", r.facts.active_tiles, r.facts.tiles),
                pass,
                ms(s.median),
                ms(s.p95),
                bytes.map_or("–".into(), |b| format!("{:.1}", b as f64 / 1e6)),
                ms(floor),
                if floor.is_nan() { "–".into() } else { format!("{:.1}", s.median / floor) },
                String::new(),
            ]);
        }
        if let Some(t) = r.timings.total() {
            let floor = bw.map_or(f64::NAN, |bw| bw.floor_ms(total_bytes));
            table.push(vec![
                r.scene.clone(),
                r.camera.clone(),
                r.resolution.to_string(),
                r.visible.to_string(),
                format!("{} / {}", r.facts.active_tiles, r.facts.tiles),
                "**frame**".into(),
                format!("**{}**", ms(t.median)),
                ms(t.p95),
                format!("{:.1}", total_bytes as f64 / 1e6),
                ms(floor),
                if floor.is_nan() { "–".into() } else { format!("**{:.1}**", t.median / floor) },
                ms(r.cpu_ms),
            ]);
        }
    }
    let mut md = String::new();
    let _ = writeln!(md, "# Runtime: PPR passes against the bandwidth floor\n");
    let _ = writeln!(md, "Machine: **{}**.\n", outcome.adapter);
    let _ = writeln!(md, "Command:\n\n```sh\n{command}\n```\n");
    match bw {
        Some(b) => {
            let _ = writeln!(
                md,
                "Copy bandwidth, measured in the same run: a vec4-per-thread copy kernel (256-thread \
                 workgroups) moving {} MiB (read + write) in a median {:.4} ms = **{:.0} GB/s**.\n",
                b.bytes >> 20,
                b.median_ms,
                b.bytes_per_second() / 1e9
            );
        }
        None => {
            let _ = writeln!(md, "No copy bandwidth: the adapter has no timestamp queries.\n");
        }
    }
    let _ = writeln!(
        md,
        "Times are medians (and 95th percentiles) of GPU timestamps over the timed frames, \
         after warm-up, the faster of two rounds over every variant, camera and size (the second in reverse order); before each frame a 256 MiB scratch write evicts the L2 cache. \
         Bytes per pass, given the frame's plan and a read-back of its buffers: classify \
         (indirect frames only) reads depth 4 B/px, writes 4 B per tile flag and per active \
         tile and clears the active tiles, 4 B/px; clear (direct frames) writes 4 B/px over the \
         whole buffer, in the clear pass or (where the frame before cleared this frame's \
         buffer) in the reflection pass, for the next frame; \
         projection reads depth 4 B/px and writes 4 B per written pixel; reflection reads the \
         intermediate 4 B/px (neighbours from cache) and writes the output 8 B/px over the \
         dispatched pixels, and reads colour 8 B per pixel with data. Floor = bytes / copy \
         bandwidth; × floor = median / floor. CPU ms (on the frame's row): the median CPU time \
         of the renderer's `prepare` and `encode` a frame, on this machine's CPU (planning, \
         packing the upload, recording the passes; not the submit).\n"
    );
    for n in &outcome.notes {
        let _ = writeln!(md, "- {n}");
    }
    let _ = writeln!(md);
    for (res, probe) in &outcome.write_probe {
        let _ = writeln!(md, "Full-screen image writes at {res} (`--write-probe`), medians:\n");
        let _ = writeln!(md, "| variant | MB written | median ms | × floor |\n| --- | ---: | ---: | ---: |");
        for p in probe {
            let floor = bw.map_or(f64::NAN, |bw| bw.floor_ms(p.bytes));
            let _ = writeln!(
                md,
                "| {} | {:.1} | {} | {:.1} |",
                p.variant,
                p.bytes as f64 / 1e6,
                ms(p.median_ms),
                p.median_ms / floor
            );
        }
        let _ = writeln!(md);
    }
    if !outcome.upload_probe.is_empty() {
        let _ = writeln!(
            md,
            "A frame's upload before its first pass (`--upload-probe`): 256-byte parts copied from \
             a staging buffer in host memory, then one dispatch that reads them, between two \
             encoder timestamps; medians:\n"
        );
        let _ = writeln!(md, "| variant | copies | median ms |\n| --- | ---: | ---: |");
        for p in &outcome.upload_probe {
            let _ = writeln!(md, "| {} | {} | {} |", p.variant, p.copies, ms(p.median_ms));
        }
        let _ = writeln!(md);
    }
    if !outcome.stereo.is_empty() {
        let _ = writeln!(
            md,
            "Stereo (`--stereo`): both eyes (64 mm apart) from one renderer (`prepare_stereo` + \
             `encode_stereo`) against two mono frames (`prepare`, `encode` twice) into one \
             encoder; medians of encoder timestamps around the PPR commands:\n"
        );
        let _ = writeln!(
            md,
            "| scene | camera | per eye | stereo ms | two mono ms | stereo / mono pair | frames |\n| --- | --- | --- | ---: | ---: | ---: | ---: |"
        );
        for s in &outcome.stereo {
            let _ = writeln!(
                md,
                "| {} | {} | {}x{} | {} | {} | {:.2} | {} |",
                s.scene,
                s.camera,
                s.size[0],
                s.size[1],
                ms(s.stereo_ms),
                ms(s.mono_pair_ms),
                s.stereo_ms / s.mono_pair_ms,
                s.frames
            );
        }
        let _ = writeln!(md);
    }
    md.push_str(&table.render());
    if let Some(parts) = frame_parts_table(&csv_rows(outcome)) {
        let _ = writeln!(md, "\n{parts}");
    }
    let _ = writeln!(md, "\nPlans:\n");
    for r in &outcome.rows {
        let _ = writeln!(md, "- {} {} {}: {}", r.scene, r.camera, r.resolution, r.plan);
    }
    let csv_path = dir.join("runtime.csv");
    csv.write(&csv_path)?;
    let md_path = dir.join("runtime.md");
    std::fs::write(&md_path, md).map_err(|e| BenchError::io(&md_path, e))?;
    Ok(vec![md_path, csv_path])
}

/// The report's rows as `runtime.csv` holds them (one a pass), for the tables built from
/// that file's rows.
fn csv_rows(outcome: &RuntimeOutcome) -> Vec<RuntimeRow> {
    let mut rows = Vec::new();
    for r in &outcome.rows {
        let [width, height] = r.resolution.size();
        for (pass, s) in r.timings.passes() {
            rows.push(RuntimeRow {
                scene: r.scene.clone(),
                camera: r.camera.clone(),
                width,
                height,
                pass,
                median_ms: s.median,
                ratio_to_floor: f64::NAN,
            });
        }
    }
    rows
}

/// The bytes of `pass` (passes recorded together, `a + b`, move both's; the frame's span,
/// every pass's).
fn pass_bytes_of(bytes: &[crate::bandwidth::PassBytes], pass: &str) -> Option<u64> {
    let one = |name: &str| bytes.iter().find(|b| b.pass == name).map(|b| b.bytes);
    match pass {
        "frame" => Some(bytes.iter().map(|b| b.bytes).sum()),
        joined if joined.contains(" + ") => joined.split(" + ").map(one).sum(),
        name => one(name),
    }
}

#[cfg(test)]
mod tests {
    use super::pass_bytes_of;
    use crate::bandwidth::PassBytes;

    #[test]
    fn passes_timed_together_move_both_passes_bytes() {
        let bytes = [
            PassBytes { pass: "projection", bytes: 10, rule: "" },
            PassBytes { pass: "reflection", bytes: 5, rule: "" },
            PassBytes { pass: "classify", bytes: 2, rule: "" },
        ];
        assert_eq!(pass_bytes_of(&bytes, "projection"), Some(10));
        assert_eq!(pass_bytes_of(&bytes, "projection + reflection"), Some(15));
        assert_eq!(pass_bytes_of(&bytes, "frame"), Some(17));
        assert_eq!(pass_bytes_of(&bytes, "layers"), None);
        assert_eq!(pass_bytes_of(&bytes, "projection + layers"), None);
    }
}
