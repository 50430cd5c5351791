//! The command line.

use std::path::PathBuf;

use clap::Parser;

use crate::camera_spec::ProjectionChoice;
use crate::level_match::LevelMatch;
use crate::view_mode::ViewMode;

/// Walk through a glTF level with pixel-projected reflections (ppr-runtime).
///
/// Keys: WASD move, Q/E down/up, Shift fast, hold the right mouse button to look, wheel
/// for speed; H holes, F filtering, B anti-bleeding, P feed the previous frame to PPR, V
/// view (final, reflection buffer, intermediate buffer, weight), C next camera of the level,
/// F9 lose the device, Esc quit.
/// The reflector set is reloaded when its file changes.
#[derive(Clone, Debug, Parser)]
#[command(name = "ppr-walkthrough", version)]
pub struct Args {
    /// The glTF level (`.glb` or `.gltf`).
    #[arg(default_value = "assets/demo_room.glb")]
    pub level: PathBuf,
    /// Its reflector set [default: `<level stem>.ppr.json` beside the level].
    #[arg(long)]
    pub set: Option<PathBuf>,
    /// A camera of the level by name, or "eye=x,y,z;target=x,y,z;fov=60" [default: the
    /// level's first camera].
    #[arg(long)]
    pub camera: Option<String>,
    /// Window or image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    pub size: [u32; 2],
    /// Reversed Z (near plane at depth 1).
    #[arg(long)]
    pub reversed_z: bool,
    /// Infinite far plane.
    #[arg(long)]
    pub infinite_far: bool,
    /// Render offscreen without a window (needs --frames).
    #[arg(long)]
    pub headless: bool,
    /// Stop after this many frames (with a window too).
    #[arg(long)]
    pub frames: Option<u32>,
    /// Write the last frame to this PNG.
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// What the screen shows first.
    #[arg(long, value_enum, default_value_t = ViewMode::Final)]
    pub view: ViewMode,
    /// Start with hole filling off.
    #[arg(long)]
    pub no_holes: bool,
    /// Start with filtering off.
    #[arg(long)]
    pub no_filter: bool,
    /// Start with anti-bleeding off.
    #[arg(long)]
    pub no_anti_bleed: bool,
    /// Start with glossy reflections off (key G): reflectors with roughness reflect as
    /// mirrors.
    #[arg(long)]
    pub no_glossy: bool,
    /// Render both eyes of a headset side by side (64 mm apart, each half the width), PPR
    /// for both from one renderer (`prepare_stereo` + `encode_stereo`).
    #[arg(long)]
    pub stereo: bool,
    /// Start feeding PPR the previous frame's composite as its colour input (key P): a
    /// mirror seen in a mirror gains one bounce per frame.
    #[arg(long)]
    pub feed_previous_frame: bool,
    /// Resolution the PPR passes run at: full, half or quarter (each side); the reflection
    /// is upsampled to the window, edge-aware. Half costs about a quarter of the pixels.
    #[arg(long, default_value = "full", value_parser = parse_tier)]
    pub tier: ppr_runtime::ResolutionTier,
    /// Use the set even when it was extracted from other bytes than the level's (its
    /// `source.hash` differs): a warning instead of a refusal.
    #[arg(long)]
    pub accept_level_mismatch: bool,
    /// Lose the device on purpose after this frame (tests the recovery).
    #[arg(long)]
    pub lose_device_at: Option<u32>,
}

impl Args {
    /// The reflector-set file: `--set`, or `<stem>.ppr.json` beside the level.
    pub fn set_path(&self) -> PathBuf {
        self.set.clone().unwrap_or_else(|| {
            let stem =
                self.level.file_stem().map_or_else(|| "level".into(), |s| s.to_string_lossy().into_owned());
            self.level.with_file_name(format!("{stem}.ppr.json"))
        })
    }

    /// What a set must match: this level's hash, unless `--accept-level-mismatch`.
    pub fn level_match(&self, level_hash: &str) -> LevelMatch {
        LevelMatch {
            set_path: self.set_path(),
            level_path: self.level.clone(),
            level_hash: level_hash.to_owned(),
            accept_mismatch: self.accept_level_mismatch,
        }
    }

    /// Depth convention and far plane.
    pub fn projection(&self) -> ProjectionChoice {
        ProjectionChoice {
            depth: if self.reversed_z {
                ppr_runtime::DepthMode::Reversed
            } else {
                ppr_runtime::DepthMode::Standard
            },
            infinite_far: self.infinite_far,
        }
    }

    /// The reflection pass's steps as the flags ask.
    pub fn settings(&self) -> ppr_runtime::ReflectionSettings {
        ppr_runtime::ReflectionSettings {
            holes: !self.no_holes,
            filtering: !self.no_filter,
            anti_bleeding: !self.no_anti_bleed,
            glossy: !self.no_glossy,
            resolution: self.tier,
            ..ppr_runtime::ReflectionSettings::ALL
        }
    }
}

/// Parses a resolution tier: `full`, `half` or `quarter`.
fn parse_tier(text: &str) -> Result<ppr_runtime::ResolutionTier, String> {
    match text {
        "full" => Ok(ppr_runtime::ResolutionTier::Full),
        "half" => Ok(ppr_runtime::ResolutionTier::Half),
        "quarter" => Ok(ppr_runtime::ResolutionTier::Quarter),
        _ => Err(format!("{text:?}: expected full, half or quarter")),
    }
}

/// Parses `WIDTHxHEIGHT`.
fn parse_size(text: &str) -> Result<[u32; 2], String> {
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(|| format!("{text:?}: expected WIDTHxHEIGHT"))?;
    let parse = |v: &str| v.trim().parse::<u32>().map_err(|e| format!("{text:?}: {e}"));
    match [parse(w)?, parse(h)?] {
        [0, _] | [_, 0] => Err(format!("{text:?}: sides must be positive")),
        size => Ok(size),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_the_headless_command_line() {
        let args = Args::try_parse_from([
            "ppr-walkthrough",
            "levels/room.glb",
            "--headless",
            "--frames",
            "3",
            "--screenshot",
            "out.png",
            "--camera",
            "cam_mirror",
            "--size",
            "320x180",
        ])
        .expect("parses");
        assert_eq!(args.set_path(), PathBuf::from("levels/room.ppr.json"));
        assert_eq!((args.frames, args.size, args.headless), (Some(3), [320, 180], true));
        assert!(Args::try_parse_from(["ppr-walkthrough", "--size", "0x5"]).is_err());
    }
}
