//! Extraction of generated levels of growing size: the same room alone, as copies, inside
//! grids of rooms up to a million triangles, and the shared kitchen copied side by side.
//! Prints, per level, triangles, rectangles, rectangles per room copy, the wall time per
//! stage and the process's CPU time (minimum of N runs: on a shared machine the CPU time
//! is the steadier figure).
//!
//! ```sh
//! CARGO_TARGET_DIR=target cargo run --release -p ppr-extract --example extract_scaling -- 3
//! ```
//! The optional arguments are the number of runs (default 3) and a part of the level
//! names to run only those. `PPR_THREADS=1` (or any
//! count) limits the extraction's worker threads.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use ppr_extract::generated_levels::{RoomSpec, copies, level_of, room_grid, room_triangles};
use ppr_extract::summary::rate;
use ppr_extract::{ExtractParams, Extraction, Level, Stage, extract, load_level};

/// CPU time this process has used (user + system), seconds, from `/proc/self/stat`
/// (Linux; 0 elsewhere). Clock ticks of 10 ms.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    let fields: Vec<&str> = after.split_whitespace().collect();
    let ticks = |i: usize| fields.get(i).and_then(|f| f.parse::<f64>().ok()).unwrap_or(0.0);
    // Fields after the command: state is 0, utime 11, stime 12.
    (ticks(11) + ticks(12)) / 100.0
}

/// Extracts `level` `runs` times; the last extraction, the minimum time per stage (the
/// total under `Stage::Write`) and the minimum CPU time, seconds.
fn measure(level: &Level, params: &ExtractParams, runs: usize) -> (Extraction, Vec<(Stage, Duration)>, f64) {
    let mut best: Vec<(Stage, Duration)> = Vec::new();
    let mut last = None;
    let mut cpu = f64::INFINITY;
    for _ in 0..runs {
        let (t, c) = (Instant::now(), cpu_seconds());
        let x = extract(level, params, &|_, _| {});
        let total = t.elapsed();
        cpu = cpu.min(cpu_seconds() - c);
        for &(stage, d) in x.timings.iter().chain([(Stage::Write, total)].iter()) {
            match best.iter_mut().find(|(s, _)| *s == stage) {
                Some((_, b)) => *b = (*b).min(d),
                None => best.push((stage, d)),
            }
        }
        last = Some(x);
    }
    (last.expect("at least one run"), best, cpu)
}

fn row(name: &str, level: &Level, params: &ExtractParams, runs: usize, copies: usize) {
    if std::env::args().nth(2).is_some_and(|only| !name.contains(&only)) {
        return;
    }
    let (x, times, cpu) = measure(level, params, runs);
    let ms = |s: Stage| times.iter().find(|(t, _)| *t == s).map_or(0.0, |(_, d)| d.as_secs_f64() * 1e3);
    let total = times.iter().find(|(t, _)| *t == Stage::Write).map_or(Duration::ZERO, |(_, d)| *d);
    println!(
        "| {name} | {} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | **{:.1}** | {:.2} | {} |",
        level.triangles.len(),
        x.set.reflectors.len(),
        x.set.reflectors.len() as f64 / copies as f64,
        ms(Stage::Select),
        ms(Stage::Cluster),
        ms(Stage::Regions),
        ms(Stage::Fit),
        ms(Stage::Occluders),
        ms(Stage::Write)
            - ms(Stage::Select)
            - ms(Stage::Cluster)
            - ms(Stage::Regions)
            - ms(Stage::Fit)
            - ms(Stage::Occluders),
        total.as_secs_f64() * 1e3,
        cpu,
        rate(level.triangles.len(), total),
    );
}

fn main() -> anyhow::Result<()> {
    let runs: usize = std::env::args().nth(1).map(|s| s.parse()).transpose()?.unwrap_or(3).max(1);
    let threads = std::env::var("PPR_THREADS").ok().and_then(|t| t.parse().ok()).unwrap_or(0);
    let params = ExtractParams { threads, ..ExtractParams::all_planar() };
    println!(
        "preset all_planar, {} threads, minimum of {runs} runs; times in ms (`other`: ids, groups, set building)",
        if threads == 0 { "all".to_owned() } else { threads.to_string() }
    );
    println!();
    println!(
        "| level | triangles | rectangles | per copy | select | cluster | regions | fit | occluders | other | total | CPU s | triangles/s |"
    );
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    let spec = RoomSpec { cells_per_m: 4.0, ..RoomSpec::default() };
    let room = room_triangles(&spec, glam::DVec3::ZERO);
    row("room", &level_of("room", &room), &params, runs, 1);
    for n in [2usize, 8, 32] {
        let level = copies(&level_of("room", &room), n, 20.0);
        row(&format!("room × {n}, 20 m apart"), &level, &params, runs, n);
    }
    for (nx, nz) in [(4usize, 4usize), (8, 8), (16, 16)] {
        let level = level_of("grid", &room_grid(&spec, nx, nz, 8.0));
        row(&format!("room grid {nx} × {nz}, 8 m apart"), &level, &params, runs, nx * nz);
    }
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let kitchen = root.join("../shared/scenes/kitchen/kitchen.gltf");
    if let Ok(level) = load_level(&kitchen) {
        for n in [1usize, 5] {
            row(&format!("kitchen × {n}, 20 m apart"), &copies(&level, n, 20.0), &params, runs, n);
        }
    }
    Ok(())
}
