//! `ppr-render`: renders a glTF level with pixel-projected reflections and with the exact
//! mirrored reference, writes the images and prints PSNR / FLIP against the reference.
//!
//! ```text
//! ppr-render level.glb --set level.ppr.json [--camera NAME | --camera "eye=x,y,z;target=x,y,z;fov=60"]
//!            [--size 960x540] [--reversed-z] [--infinite-far] [--no-holes] [--no-filter]
//!            [--no-anti-bleed] -o frame.png
//! ```

use std::path::PathBuf;

use anyhow::{Context, bail};
use clap::Parser;
use ppr_format::ReflectorSet;
use ppr_runtime::{DepthMode, ReflectionSettings};
use ppr_testbed::camera_spec::ProjectionChoice;
use ppr_testbed::render_job::{RenderJob, run};
use ppr_testbed::{CompositeParams, GpuContext, PprTechnique, RenderSettings, ToneMap};

/// Render a level with PPR and with the exact reference; write frame, reflection,
/// reference and difference images; print PSNR and FLIP over on-screen reflector pixels.
#[derive(Parser, Debug)]
#[command(name = "ppr-render", version)]
struct Args {
    /// The glTF level (.glb or .gltf).
    level: PathBuf,
    /// The level's reflector set (*.ppr.json).
    #[arg(long = "set")]
    set: PathBuf,
    /// A camera of the level by name, or "eye=x,y,z;target=x,y,z;fov=60" (degrees; up=,
    /// near=, far= optional). Default: the level's first camera.
    #[arg(long)]
    camera: Option<String>,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "960x540", value_parser = parse_size)]
    size: [u32; 2],
    /// Reversed Z (near plane at depth 1, cleared to 0).
    #[arg(long)]
    reversed_z: bool,
    /// Infinite far plane.
    #[arg(long)]
    infinite_far: bool,
    /// Turn off hole filling in the reflection pass.
    #[arg(long)]
    no_holes: bool,
    /// Turn off filtered (bilinear) sampling in the reflection pass.
    #[arg(long)]
    no_filter: bool,
    /// Turn off the anti-bleeding step in the reflection pass.
    #[arg(long)]
    no_anti_bleed: bool,
    /// Weight of the reflection in the composited frames, in [0, 1].
    #[arg(long, default_value_t = CompositeParams::default().reflectivity)]
    reflectivity: f32,
    /// Tone map the PNG files and the metrics with Reinhard instead of clamping.
    #[arg(long)]
    reinhard: bool,
    /// Any surface on a reflector's plane inside its rectangle is a reflector pixel, not
    /// only reflective materials (use with sets extracted with `--all-planar`).
    #[arg(long)]
    mask_any_surface: bool,
    /// Render even when the set was extracted from other bytes than the level's (its
    /// `source.hash` differs): a warning instead of an error.
    #[arg(long)]
    accept_level_mismatch: bool,
    /// Output frame (PNG); the other files are named after it (frame.reflection.png, ...).
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
}

fn parse_size(text: &str) -> Result<[u32; 2], String> {
    let (w, h) = text.split_once('x').ok_or_else(|| format!("{text:?} is not WIDTHxHEIGHT"))?;
    let parse = |v: &str| v.trim().parse::<u32>().map_err(|e| format!("{v:?}: {e}"));
    let size = [parse(w)?, parse(h)?];
    if size.contains(&0) || size.iter().any(|&v| v > 16384) {
        return Err(format!("{text:?}: each side must be in 1..=16384"));
    }
    Ok(size)
}

fn main() -> anyhow::Result<()> {
    let args = Args::parse();
    if !(0.0..=1.0).contains(&args.reflectivity) {
        bail!("--reflectivity must be in [0, 1], got {}", args.reflectivity);
    }
    let mut job = RenderJob {
        level: args.level.clone(),
        reflectors: args.set.clone(),
        camera: args.camera.clone(),
        size: args.size,
        projection: ProjectionChoice {
            depth: if args.reversed_z { DepthMode::Reversed } else { DepthMode::Standard },
            infinite_far: args.infinite_far,
        },
        output: args.output.clone(),
        composite: CompositeParams { reflectivity: args.reflectivity },
        tone_map: if args.reinhard { ToneMap::Reinhard } else { ToneMap::Clamp },
        render: RenderSettings::default(),
        accept_level_mismatch: args.accept_level_mismatch,
    };
    job.render.mask.require_reflective_material = !args.mask_any_surface;
    let gpu = GpuContext::new_headless().context("creating the GPU context")?;
    let reflectors = ReflectorSet::load(&args.set)?;
    let settings = ReflectionSettings {
        holes: !args.no_holes,
        filtering: !args.no_filter,
        anti_bleeding: !args.no_anti_bleed,
        ..ReflectionSettings::ALL
    };
    let mut ppr = PprTechnique::new(&gpu.device, &gpu.queue, &reflectors, settings)?;
    let report =
        run(&job, &gpu, Some(&mut ppr)).with_context(|| format!("rendering {}", args.level.display()))?;
    println!("{report}");
    Ok(())
}
