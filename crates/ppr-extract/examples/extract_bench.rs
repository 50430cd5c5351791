//! Extraction benchmark: per-stage time (median of N runs) and triangles per second on the
//! demo level and the largest shared scene, for every parameter preset.
//!
//! ```sh
//! CARGO_TARGET_DIR=/work/target-extract cargo run --release -p ppr-extract --example extract_bench -- 9
//! ```
//! The optional argument is the number of runs (default 9). Levels: `assets/demo_room.glb`
//! and `../shared/scenes/kitchen/kitchen.gltf`, relative to the workspace root.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use ppr_extract::summary::rate;
use ppr_extract::{ExtractParams, Stage, extract, load_level};

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort_unstable();
    v[v.len() / 2]
}

fn main() -> anyhow::Result<()> {
    let runs: usize = std::env::args().nth(1).map(|s| s.parse()).transpose()?.unwrap_or(9).max(1);
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let levels = [
        ("demo_room", root.join("assets/demo_room.glb")),
        ("kitchen", root.join("../shared/scenes/kitchen/kitchen.gltf")),
    ];
    println!("runs per measurement: {runs} (median)");
    for (name, path) in &levels {
        let mut load_times = Vec::new();
        let mut level = None;
        for _ in 0..runs {
            let t = Instant::now();
            level = Some(load_level(path)?);
            load_times.push(t.elapsed());
        }
        let level = level.ok_or_else(|| anyhow::anyhow!("no run"))?;
        let tris = level.triangles.len();
        for (preset, params) in ExtractParams::presets() {
            let mut per_stage: Vec<(Stage, Vec<Duration>)> = Vec::new();
            let mut totals = Vec::new();
            let mut shapes = 0;
            let mut write_times = Vec::new();
            for _ in 0..runs {
                let t = Instant::now();
                let x = extract(&level, &params, &|_, _| {});
                totals.push(t.elapsed());
                shapes = x.set.reflectors.len();
                for (stage, d) in x.timings {
                    match per_stage.iter_mut().find(|(s, _)| *s == stage) {
                        Some((_, v)) => v.push(d),
                        None => per_stage.push((stage, vec![d])),
                    }
                }
                let t = Instant::now();
                let text = x.set.to_json_string()?;
                let tmp = std::env::temp_dir().join("ppr-extract-bench.ppr.json");
                ppr_format::write_atomically(&tmp, text.as_bytes())?;
                write_times.push(t.elapsed());
            }
            println!("\n{name} ({tris} triangles), preset {preset}: {shapes} shapes");
            println!("| stage | median ms | triangles/s |");
            println!("| --- | ---: | ---: |");
            let load = median(load_times.clone());
            println!("| load | {:.2} | {} |", load.as_secs_f64() * 1e3, rate(tris, load));
            for (stage, v) in per_stage {
                let d = median(v);
                println!("| {} | {:.2} | {} |", stage.name(), d.as_secs_f64() * 1e3, rate(tris, d));
            }
            let write = median(write_times);
            println!("| write | {:.2} | {} |", write.as_secs_f64() * 1e3, rate(tris, write));
            let total = load + median(totals) + write;
            println!("| **total** | **{:.2}** | **{}** |", total.as_secs_f64() * 1e3, rate(tris, total));
        }
    }
    Ok(())
}
