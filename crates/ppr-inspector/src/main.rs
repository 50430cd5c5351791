//! `ppr-inspector [level.glb] [--set level.ppr.json] [--screenshot out.png]`: parses the
//! arguments and runs the inspector window.

use std::path::PathBuf;

use anyhow::Context as _;
use clap::Parser;
use ppr_inspector::{InspectorApp, StartupOptions, gpu_setup};

/// Review, fix and preview a level's reflectors.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// The glTF level (.glb or .gltf); extracted in the background unless --set is given.
    level: Option<PathBuf>,
    /// A saved reflector set (.ppr.json) to load instead of extracting.
    #[arg(long)]
    set: Option<PathBuf>,
    /// Once everything is loaded, write a picture of the window here and quit.
    #[arg(long, value_name = "PNG")]
    screenshot: Option<PathBuf>,
    /// Window size in points, e.g. 1400x860.
    #[arg(long, default_value = "1400x860", value_parser = parse_size)]
    size: [f32; 2],
}

fn parse_size(text: &str) -> Result<[f32; 2], String> {
    let (w, h) = text.split_once('x').ok_or("expected WIDTHxHEIGHT")?;
    let parse = |s: &str| s.trim().parse::<f32>().map_err(|e| format!("{s:?}: {e}"));
    Ok([parse(w)?, parse(h)?])
}

fn main() -> anyhow::Result<()> {
    let args = Args::parse();
    let options = StartupOptions { level: args.level, set: args.set, screenshot: args.screenshot };
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default().with_inner_size(args.size).with_title("PPR inspector"),
        wgpu_options: eframe::egui_wgpu::WgpuConfiguration {
            wgpu_setup: gpu_setup::wgpu_setup(),
            ..Default::default()
        },
        ..Default::default()
    };
    eframe::run_native("ppr-inspector", native, Box::new(|cc| Ok(Box::new(InspectorApp::new(cc, options)))))
        .map_err(|e| anyhow::anyhow!("{e}"))
        .context("the inspector window failed")
}
