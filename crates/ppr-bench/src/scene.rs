//! The scenes a bench runs on: a level for the testbed, its reflector set from the
//! extractor, and the cameras that look at it.

use std::path::{Path, PathBuf};

use ppr_extract::{ExtractParams, extract};
use ppr_format::{ReflectorKind, ReflectorSet};
use ppr_runtime::Projection;
use ppr_testbed::Level;

pub use crate::cameras::NamedCamera;
use crate::cameras::derive_cameras;
use crate::error::BenchError;

/// How a scene's reflector set is made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExtractPreset {
    /// Material-driven candidates (`ExtractParams::default()`).
    Materials,
    /// Every planar surface (`ExtractParams::all_planar()`), for levels with one material.
    AllPlanar,
}

impl ExtractPreset {
    pub fn params(self) -> ExtractParams {
        match self {
            Self::Materials => ExtractParams::default(),
            Self::AllPlanar => ExtractParams::all_planar(),
        }
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Self::Materials => "materials",
            Self::AllPlanar => "all-planar",
        }
    }
}

/// Where a scene comes from.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneSpec {
    /// Short name for reports.
    pub name: String,
    /// The glTF file.
    pub path: PathBuf,
    /// Extraction preset.
    pub preset: ExtractPreset,
}

/// Known scene names: `demo` (the shipped demo room) and the shared scenes.
pub const KNOWN_SCENES: [(&str, &str, ExtractPreset); 6] = [
    ("demo", "assets/demo_room.glb", ExtractPreset::Materials),
    ("kitchen", "kitchen/kitchen.gltf", ExtractPreset::Materials),
    ("small", "small.glb", ExtractPreset::Materials),
    ("collision-world", "collision-world.glb", ExtractPreset::AllPlanar),
    ("pool", "pool_day_baked.glb", ExtractPreset::AllPlanar),
    ("mine", "fps_mine_sketch_compressed.glb", ExtractPreset::Materials),
];

impl SceneSpec {
    /// The scene `text` names: a known name (`demo`, `kitchen`, ...; shared scenes are
    /// looked up in `scenes_dir`, the demo level in `assets_dir`'s parent layout), a
    /// generated mirror room (`mirror-room`, `mirror-room-<n>`, `mirror-corridor`), or a
    /// path to a `.glb`/`.gltf` (material-driven extraction, `:all-planar` suffix for
    /// every planar surface).
    ///
    /// # Errors
    /// [`BenchError::Spec`] for an unknown name that is not a path either.
    pub fn parse(text: &str, repo_root: &Path, scenes_dir: &Path) -> Result<Self, BenchError> {
        // Generated scenes have no file: their path is their name (see `BenchScene::load`).
        if crate::mirror_room::MirrorRoom::from_name(text).is_some()
            || crate::scaling::level_family::LevelFamily::from_scene_name(text).is_some()
        {
            return Ok(Self { name: text.into(), path: text.into(), preset: ExtractPreset::AllPlanar });
        }
        if let Some((name, rel, preset)) = KNOWN_SCENES.iter().find(|(n, _, _)| *n == text) {
            let path = if *name == "demo" { repo_root.join(rel) } else { scenes_dir.join(rel) };
            return Ok(Self { name: (*name).into(), path, preset: *preset });
        }
        let (path, preset) = match text.strip_suffix(":all-planar") {
            Some(p) => (p, ExtractPreset::AllPlanar),
            None => (text, ExtractPreset::Materials),
        };
        let path = PathBuf::from(path);
        let is_gltf = path.extension().is_some_and(|e| e == "glb" || e == "gltf");
        if !is_gltf {
            let known: Vec<&str> = KNOWN_SCENES.iter().map(|(n, _, _)| *n).collect();
            return Err(BenchError::Spec(format!(
                "unknown scene `{text}`: use one of {} or a path to a .glb/.gltf file",
                known.join(", ")
            )));
        }
        let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| text.into());
        Ok(Self { name, path, preset })
    }
}

/// A scene ready to render: the level, its reflectors and its cameras.
#[derive(Clone, Debug)]
pub struct BenchScene {
    /// Short name.
    pub name: String,
    /// The testbed's level.
    pub level: Level,
    /// Reflectors from `ppr-extract` (glass panels turned opaque, see [`SceneOptions`]).
    pub reflectors: ReflectorSet,
    /// The cameras: the file's own, or derived from the bounds and the largest reflectors.
    pub cameras: Vec<NamedCamera>,
    /// What was changed or noticed while loading, for the report.
    pub notes: Vec<String>,
    /// The cameras are candidates derived by [`derive_cameras`], still to be ranked
    /// ([`crate::camera_ranking::rank_cameras`]).
    pub cameras_derived: bool,
    /// Every planar surface is a reflector (all-planar extraction): the testbed's reflector
    /// mask takes any surface on a reflector, whatever its material.
    pub any_surface: bool,
}

/// How scenes are prepared for a bench.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SceneOptions {
    /// Turn transparent reflectors (glass) into opaque ones: the runtime has no
    /// transparent atlas yet and would skip them, so every technique is compared on the
    /// same reflectors.
    pub glass_as_opaque: bool,
    /// At most this many cameras per scene.
    pub max_cameras: usize,
}

impl Default for SceneOptions {
    fn default() -> Self {
        Self { glass_as_opaque: false, max_cameras: 3 }
    }
}

impl BenchScene {
    /// Loads the level, extracts its reflectors and picks its cameras.
    ///
    /// # Errors
    /// The level cannot be read by the testbed or the extractor.
    pub fn load(spec: &SceneSpec, options: &SceneOptions) -> Result<Self, BenchError> {
        if let Some(room) = crate::mirror_room::MirrorRoom::from_name(&spec.name) {
            return Ok(crate::mirror_room::bench_scene(room, options));
        }
        if let Some((family, count)) = crate::scaling::level_family::LevelFamily::from_scene_name(&spec.name)
        {
            // A scaling family (scaling.md) with its one camera, to profile like a real level.
            let g = crate::scaling::level_family::generate(family, count);
            let mut notes = vec![format!(
                "generated scaling level: {} reflectors from {} triangles",
                g.reflectors.reflectors.len(),
                g.level.triangle_count()
            )];
            let mut scene = Self::from_parts(&spec.name, g.level, g.reflectors, options, &mut notes);
            scene.cameras = vec![NamedCamera { name: "scaling".into(), camera: g.camera }];
            scene.cameras_derived = false;
            return Ok(scene);
        }
        // One read of the file (ppr-level, as every tool): drawn by the testbed, flattened for the extractor.
        let level_error =
            |e: ppr_level::LoadError| BenchError::Level { path: spec.path.clone(), reason: e.to_string() };
        let loaded =
            ppr_level::load_scene(&spec.path, &ppr_level::LoadParams::render()).map_err(level_error)?;
        let level = Level::from_scene(&loaded)?;
        let extracted = ppr_level::Level::from_scene(&loaded).map_err(level_error)?;
        let extraction = extract(&extracted, &spec.preset.params(), &|_, _| {});
        let any_surface = spec.preset == ExtractPreset::AllPlanar;
        let mut notes = vec![format!(
            "{} reflectors extracted ({} preset) from {} triangles",
            extraction.set.reflectors.len(),
            spec.preset.as_str(),
            level.triangle_count()
        )];
        let mut scene = Self::from_parts(&spec.name, level, extraction.set, options, &mut notes);
        scene.any_surface = any_surface;
        Ok(scene)
    }

    /// A scene from a level and a set made in code (cameras as [`Self::load`] picks them).
    pub fn from_parts(
        name: &str,
        level: Level,
        mut reflectors: ReflectorSet,
        options: &SceneOptions,
        notes: &mut Vec<String>,
    ) -> Self {
        if options.glass_as_opaque {
            let glass = reflectors.reflectors.iter().filter(|r| r.kind == ReflectorKind::Transparent).count();
            if glass > 0 {
                for r in &mut reflectors.reflectors {
                    if r.kind == ReflectorKind::Transparent {
                        r.kind = ReflectorKind::Opaque;
                    }
                }
                notes.push(format!(
                    "{glass} glass reflector(s) benchmarked as opaque (no transparent atlas yet)"
                ));
            }
        }
        let mut cameras: Vec<NamedCamera> = level
            .cameras
            .iter()
            .map(|c| NamedCamera { name: c.name.clone(), camera: c.to_camera(default_projection(c.zfar)) })
            .collect();
        let cameras_derived = cameras.is_empty();
        if cameras_derived {
            cameras = derive_cameras(&level, &reflectors, options.max_cameras);
        } else {
            cameras.truncate(options.max_cameras.max(1));
        }
        Self {
            name: name.into(),
            level,
            reflectors,
            cameras,
            notes: std::mem::take(notes),
            cameras_derived,
            any_surface: false,
        }
    }

    /// The testbed's render settings for this scene (the reflector mask takes any surface
    /// on a reflector for all-planar scenes).
    pub fn render_settings(&self) -> ppr_testbed::RenderSettings {
        let mut s = ppr_testbed::RenderSettings::default();
        s.mask.require_reflective_material = !self.any_surface;
        s
    }

    /// Loads the scene and, when its cameras were derived, ranks them on `gpu`.
    ///
    /// # Errors
    /// As [`Self::load`], or a readback fails.
    pub fn load_ranked(
        spec: &SceneSpec,
        options: &SceneOptions,
        gpu: &ppr_testbed::GpuContext,
    ) -> Result<Self, BenchError> {
        let mut scene = Self::load(spec, options)?;
        crate::camera_ranking::rank_cameras(gpu, &mut scene, options.max_cameras)?;
        Ok(scene)
    }

    /// Keeps only the cameras whose names are listed (all when `names` is empty).
    pub fn keep_cameras(&mut self, names: &[String]) {
        if !names.is_empty() {
            self.cameras.retain(|c| names.contains(&c.name));
        }
    }
}

/// The projection the bench uses with a file camera (its fov and near plane replace these).
fn default_projection(zfar: Option<f32>) -> Projection {
    Projection { far: zfar.or(Projection::default().far), ..Projection::default() }
}
