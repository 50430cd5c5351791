//! The CPU side of a frame's `prepare` on a generated level, without a device: the plan
//! (culling, screen rectangles, source boxes, plane groups, parallel trees), the
//! camera-relative shapes and the shape tests with the trees' words, each timed alone
//! (medians), and a parallel tree's source-box union (how many boxes it computed). A
//! profiler's harness: `perf record target/release/examples/prepare_cpu stairway-10000`.
//!
//! ```text
//! cargo run --release -p ppr-bench --example prepare_cpu -- stairway-10000 [frames] [WxH]
//! ```
//!
//! Scenes: the scaling suite's generated families (`stairway-N`, `rooms-N`,
//! `tiled-floor-N`, `facade-N`, ...). The renderer's own `prepare` (with its upload) is
//! timed by `ppr-bench runtime` as `cpu_ms`.

use std::time::Instant;

use anyhow::{Context, bail};
use ppr_bench::scaling::level_family::{LevelFamily, generate};
use ppr_runtime::shape_tests::FrameTests;
use ppr_runtime::shapes::ShapeTable;
use ppr_runtime::source_box::SourceBoxes;
use ppr_runtime::{FramePlan, PlanParams};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map_or("stairway-10000", String::as_str);
    let frames: usize = args.get(1).map_or(Ok(50), |s| s.parse()).context("frames: a count")?;
    let size: [u32; 2] = match args.get(2) {
        None => [3840, 2160],
        Some(s) => {
            let (w, h) = s.split_once('x').context("size: WxH, e.g. 3840x2160")?;
            [w.parse()?, h.parse()?]
        }
    };
    let Some((family, count)) = LevelFamily::from_scene_name(name) else {
        bail!("unknown scene {name:?}: a generated family, e.g. stairway-10000 or rooms-1000");
    };
    let level = generate(family, count);
    let table = ShapeTable::from_set(&level.reflectors);
    let camera = &level.camera;
    let params = PlanParams::default();

    let plan = FramePlan::build(&table, camera, size, &params);
    let clip = camera.clip_from_relative(size[0] as f32 / size[1] as f32);
    let boxes = SourceBoxes::new(camera.position, &clip, size);
    for tree in &plan.trees {
        let shape = |k: usize| &table.shapes[tree.members[k] as usize];
        let (rect, computed) = boxes.union(tree.members.len(), shape);
        let ms = median((0..frames).map(|_| {
            let start = Instant::now();
            std::hint::black_box(boxes.union(tree.members.len(), shape));
            start.elapsed()
        }));
        println!(
            "{name}: tree of {} members: union {rect:?}, {computed} boxes computed, {ms:.3} ms",
            tree.members.len()
        );
    }

    let (mut shapes, mut tests) = (Vec::new(), FrameTests::default());
    let mut times = [Vec::new(), Vec::new(), Vec::new()];
    for _ in 0..frames {
        let start = Instant::now();
        let plan = FramePlan::build(&table, camera, size, &params);
        let planned = Instant::now();
        table.gpu_shapes_into(camera.position, &mut shapes);
        let shaped = Instant::now();
        tests.fill(&table, &plan, camera.position);
        let tested = Instant::now();
        std::hint::black_box((&plan, &shapes, &tests.tests));
        times[0].push(planned - start);
        times[1].push(shaped - planned);
        times[2].push(tested - shaped);
    }
    let [plan_ms, shapes_ms, tests_ms] = times.map(|t| median(t.into_iter()));
    println!(
        "{name}: {} visible, plan {plan_ms:.3} ms, shapes {shapes_ms:.3} ms, tests {tests_ms:.3} ms (medians of {frames})",
        plan.visible.len()
    );
    Ok(())
}

/// The median of some durations, in milliseconds.
fn median(times: impl Iterator<Item = std::time::Duration>) -> f64 {
    let ms: Vec<f64> = times.map(|t| t.as_secs_f64() * 1e3).collect();
    ppr_bench::stats::median(&ms).unwrap_or(f64::NAN)
}
