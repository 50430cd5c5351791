//! Techniques by name on the command line (`ppr`, `ppr-raw`, `exact`, `ssr-low:stride=32`),
//! and the factory that builds them.

use std::fmt;
use std::str::FromStr;

use ppr_baselines::{
    HiZSettings, HiZSsrTechnique, PlanarReflectionTechnique, SsprSettings, SsprTechnique, SsrGlossySettings,
    SsrGlossyTechnique, SsrSettings, SsrTechnique,
};
use ppr_format::ReflectorSet;
use ppr_runtime::{Choice, PlanParams, ReflectionSettings, ResolutionTier, UpsampleProbe};
use ppr_testbed::{Level, ReflectionTechnique, RenderSettings};

use crate::error::BenchError;
use crate::exact_reference::ExactReference;
use crate::ppr_runner::PprRunner;
use crate::technique::{BenchTechnique, Family};
use crate::trait_runner::TraitRunner;

/// A technique name and its settings: `name` or `name:key=value,key=value`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TechniqueSpec {
    /// Technique name (see [`KNOWN_TECHNIQUES`]).
    pub name: String,
    /// Settings as written.
    pub params: Vec<(String, String)>,
}

/// Every technique the bench can build, with what it is.
pub const KNOWN_TECHNIQUES: [(&str, &str); 12] = [
    ("ppr-raw", "PPR, raw decoded intermediate buffer (no hole filling, no filtering)"),
    ("ppr-holes", "PPR with hole filling"),
    ("ppr-filter", "PPR with hole filling and bilinear filtering"),
    ("ppr", "PPR with hole filling, filtering and anti-bleeding (the seed's final image)"),
    (
        "exact",
        "the exact planar reflection (the testbed's reference: mirrored re-render per plane); bounces=",
    ),
    ("ssr-brute", "brute-force SSR, one-pixel steps [McGuire14]; thickness=metres"),
    ("ssr-low", "low-quality SSR, 64-pixel steps + bisection; stride=, refine=, thickness="),
    (
        "ssr-glossy",
        "glossy SSR (Bevy/Godot kind): ssr-low's march + blur of radius spread x roughness^2 x hit distance; \
         stride=, refine=, thickness=, spread=, max-radius= (px), taps=",
    ),
    ("ssr-hiz", "Hi-Z SSR with its pyramid build [Uludag14]; iterations=, thickness= (none: seed)"),
    ("sspr", "screen-space planar reflections, projection hash (Wildlands)"),
    ("sspr-stretch", "SSPR with the edge stretch"),
    ("planar", "planar reflection baseline: mirrored re-render per plane + copy to the output"),
];

/// The comparison's default list: every PPR setting, the exact reference, and the baselines
/// with SSR step counts and thicknesses (`planar` is `exact` plus a copy: on request only).
pub const DEFAULT_TECHNIQUES: [&str; 15] = [
    "ppr-raw",
    "ppr-holes",
    "ppr-filter",
    "ppr",
    "ppr:glossy=off",
    "exact",
    "ssr-brute",
    "ssr-low",
    "ssr-low:stride=16,refine=4",
    "ssr-low:stride=8,refine=3",
    "ssr-low:thickness=1",
    "ssr-glossy",
    "ssr-hiz",
    "sspr",
    "sspr-stretch",
];

/// PPR settings accept `culling=on|off|auto`, `indirect=on|off|auto`, `groups=on|off|auto`
/// (coplanar reflectors merged into plane groups), `trees=on|off|auto` (parallel reflectors
/// at many plane offsets walked as a tree), `tree-index=on|off|auto` (the trees' offset
/// index: `PlanParams::tree_index`), `blockers=on|off|auto` (a write into a parallel
/// reflector first tests the one in front of it: `PlanParams::path_blockers`), `subgroups=on|off|auto` (the projection's
/// subgroup culling), `fused-lists=on|off|auto` (tile lists built in the projection or by
/// their own pass), `fade=`, `replace-far=`,
/// `tier=`, `glossy=on|off` (reflectors with roughness blurred, the default, or all mirrors:
/// the exact reference is a mirror's), `glossy-taps=N` (the glossy blur's most taps a pixel,
/// 2 to 64, instead of 12: `DebugOptions::glossy_taps`), `timing=passes|frame` (GPU time as the sum of the
/// passes' own timestamps, the default, or the whole frame between two encoder timestamps,
/// the barriers between passes included; the SSR and SSPR baselines take it too),
/// `upsample=per-pixel|shared` (the reduced tiers' upsample reads each pixel's reduced
/// samples itself, the default, or each workgroup's once into workgroup memory: the same
/// image; `DebugOptions::shared_upsample`; or a probe of its time, not its image:
/// `store-only`, `depth-only`, `no-own-depth`, `DebugOptions::upsample_probe`) and
/// `bounces=N` (N frames of the same camera, each fed the previous one's composited image
/// as its colour input; scored against the N-bounce reference).
/// Every technique but `exact` and `planar` also accepts `reference-bounces=N`: scored
/// against the N-bounce reference (default: its `bounces`, else 1).
const PPR_KEYS: [&str; 17] = [
    "culling",
    "indirect",
    "groups",
    "trees",
    "tree-index",
    "blockers",
    "subgroups",
    "fused-lists",
    "fade",
    "replace-far",
    "tier",
    "glossy",
    "glossy-taps",
    "timing",
    "upsample",
    "bounces",
    "reference-bounces",
];

/// Largest `bounces=` (each bounce is a frame of PPR and, in the reference, a level of
/// mirrored views).
pub const MAX_BOUNCES: u32 = 4;

/// Settings each baseline accepts.
fn keys_of(name: &str) -> &'static [&'static str] {
    match name {
        n if n.starts_with("ppr") => &PPR_KEYS,
        "ssr-brute" => &["thickness", "timing", "reference-bounces"],
        "ssr-low" => &["stride", "refine", "thickness", "timing", "reference-bounces"],
        "ssr-glossy" => {
            &["stride", "refine", "thickness", "spread", "max-radius", "taps", "timing", "reference-bounces"]
        }
        "ssr-hiz" => &["iterations", "thickness", "timing", "reference-bounces"],
        "sspr" | "sspr-stretch" => &["timing", "reference-bounces"],
        "exact" => &["bounces"],
        _ => &[],
    }
}

impl TechniqueSpec {
    /// A spec without settings.
    pub fn named(name: &str) -> Self {
        Self { name: name.into(), params: Vec::new() }
    }

    /// The label used in reports: the name and its settings (`ssr-low stride=32`).
    pub fn label(&self) -> String {
        let mut s = self.name.clone();
        for (k, v) in &self.params {
            s.push_str(&format!(" {k}={v}"));
        }
        s
    }

    fn param(&self, key: &str) -> Option<&str> {
        self.params.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
    }

    /// The comparison's default list ([`DEFAULT_TECHNIQUES`]).
    pub fn defaults() -> Vec<Self> {
        DEFAULT_TECHNIQUES.iter().filter_map(|t| t.parse().ok()).collect()
    }
}

impl fmt::Display for TechniqueSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name)?;
        for (i, (k, v)) in self.params.iter().enumerate() {
            write!(f, "{}{k}={v}", if i == 0 { ":" } else { "," })?;
        }
        Ok(())
    }
}

impl FromStr for TechniqueSpec {
    type Err = BenchError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let (name, rest) = text.split_once(':').unwrap_or((text, ""));
        let name = name.trim();
        if !KNOWN_TECHNIQUES.iter().any(|(n, _)| *n == name) {
            let known: Vec<&str> = KNOWN_TECHNIQUES.iter().map(|(n, _)| *n).collect();
            return Err(BenchError::Spec(format!(
                "unknown technique `{name}` (known: {})",
                known.join(", ")
            )));
        }
        let mut params = Vec::new();
        for part in rest.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            let (k, v) = part
                .split_once('=')
                .ok_or_else(|| BenchError::Spec(format!("technique `{text}`: `{part}` is not key=value")))?;
            params.push((k.trim().to_owned(), v.trim().to_owned()));
        }
        let spec = Self { name: name.to_owned(), params };
        spec.check_keys()?;
        Ok(spec)
    }
}

impl TechniqueSpec {
    fn check_keys(&self) -> Result<(), BenchError> {
        let allowed = keys_of(&self.name);
        for (k, v) in &self.params {
            if !allowed.contains(&k.as_str()) {
                return Err(BenchError::Spec(format!(
                    "technique `{}` has no setting `{k}` (settings: {})",
                    self.name,
                    if allowed.is_empty() { "none".to_string() } else { allowed.join(", ") }
                )));
            }
            let bad = |e: String| BenchError::Spec(format!("technique `{self}`: {e}"));
            match k.as_str() {
                "culling" | "indirect" | "groups" | "trees" | "tree-index" | "blockers" | "subgroups"
                | "fused-lists" | "replace-far" | "glossy" => {
                    parse_choice(v).map_err(bad)?;
                }
                "tier" => {
                    parse_tier(v).map_err(bad)?;
                }
                "glossy-taps" => {
                    glossy_taps(v).map_err(bad)?;
                }
                "timing" => {
                    frame_timing(v).map_err(bad)?;
                }
                "upsample" => {
                    upsample_mode(v).map_err(bad)?;
                }
                "bounces" | "reference-bounces" => {
                    parse_bounces(v).map_err(bad)?;
                }
                "fade" => {
                    let f = v.parse::<f32>().map_err(|e| bad(format!("{k}: {e}")))?;
                    if !(0.0..=0.5).contains(&f) {
                        return Err(bad(format!("fade: {f} is outside [0, 0.5]")));
                    }
                }
                "spread" | "max-radius" => {
                    let f = v.parse::<f32>().map_err(|e| bad(format!("{k}: {e}")))?;
                    if !(f.is_finite() && f >= 0.0) {
                        return Err(bad(format!("{k}: {f} is not a finite value ≥ 0")));
                    }
                }
                "stride" | "refine" | "iterations" | "taps" => {
                    v.parse::<u32>().map_err(|e| bad(format!("{k}: {e}")))?;
                }
                "thickness" if v == "none" && self.name == "ssr-hiz" => {}
                "thickness" => {
                    v.parse::<f32>().map_err(|e| bad(format!("{k}: {e}")))?;
                }
                _ => {}
            }
        }
        Ok(())
    }
}

fn parse_bounces(v: &str) -> Result<u32, String> {
    match v.parse::<u32>() {
        Ok(n) if (1..=MAX_BOUNCES).contains(&n) => Ok(n),
        Ok(n) => Err(format!("bounces: {n} is outside [1, {MAX_BOUNCES}]")),
        Err(e) => Err(format!("bounces: {e}")),
    }
}

/// The frames a PPR spec feeds back (`bounces=N`, 1 without the key; 1 for other techniques).
///
/// # Errors
/// [`BenchError::Spec`] when the value does not parse.
pub fn ppr_bounces(spec: &TechniqueSpec) -> Result<u32, BenchError> {
    spec.param("bounces").map_or(Ok(1), |v| parse_bounces(v).map_err(BenchError::Spec))
}

/// The bounces of the reference `spec` is scored against: `reference-bounces=N`, else its
/// `bounces=N`, else 1.
///
/// # Errors
/// [`BenchError::Spec`] when a value does not parse.
pub fn reference_bounces(spec: &TechniqueSpec) -> Result<u32, BenchError> {
    match spec.param("reference-bounces") {
        Some(v) => parse_bounces(v).map_err(BenchError::Spec),
        None => ppr_bounces(spec),
    }
}

fn parse_tier(v: &str) -> Result<ResolutionTier, String> {
    match v {
        "full" => Ok(ResolutionTier::Full),
        "half" => Ok(ResolutionTier::Half),
        "quarter" => Ok(ResolutionTier::Quarter),
        _ => Err(format!("tier `{v}` is not full, half or quarter")),
    }
}

fn parse_choice(v: &str) -> Result<Choice, String> {
    match v {
        "on" => Ok(Choice::On),
        "off" => Ok(Choice::Off),
        "auto" => Ok(Choice::Auto),
        _ => Err(format!("`{v}` is not on, off or auto")),
    }
}

/// What building a technique needs.
pub struct TechniqueContext<'a> {
    pub device: &'a wgpu::Device,
    pub queue: &'a wgpu::Queue,
    /// The level (the planar baseline renders it again).
    pub level: &'a Level,
    pub reflectors: &'a ReflectorSet,
    /// How the testbed renders the level (the planar baseline renders it again).
    pub render: RenderSettings,
    /// Plan parameters for PPR (settings in the spec override them).
    pub plan_params: PlanParams,
}

/// The reflection settings and plan parameters of a PPR spec (`ppr-raw`, `ppr-holes`,
/// `ppr-filter`, `ppr` with their settings over `base`); `None` for other techniques.
///
/// # Errors
/// [`BenchError::Spec`] for an unknown setting or a value that does not parse.
pub fn ppr_settings(
    spec: &TechniqueSpec,
    base: PlanParams,
) -> Result<Option<(ReflectionSettings, PlanParams)>, BenchError> {
    spec.check_keys()?;
    let mut settings = match spec.name.as_str() {
        "ppr-raw" => ReflectionSettings::RAW,
        "ppr-holes" => ReflectionSettings { holes: true, ..ReflectionSettings::RAW },
        "ppr-filter" => ReflectionSettings { holes: true, filtering: true, ..ReflectionSettings::RAW },
        "ppr" => ReflectionSettings::ALL,
        _ => return Ok(None),
    };
    if let Some(v) = spec.param("fade") {
        settings.border_fade = v.parse::<f32>().map_err(|e| BenchError::Spec(format!("fade: {e}")))?;
    }
    if let Some(v) = spec.param("replace-far") {
        settings.replace_far_reflections = parse_choice(v).map_err(BenchError::Spec)? == Choice::On;
    }
    if let Some(v) = spec.param("tier") {
        settings.resolution = parse_tier(v).map_err(BenchError::Spec)?;
    }
    if let Some(v) = spec.param("glossy") {
        settings.glossy = parse_choice(v).map_err(BenchError::Spec)? != Choice::Off;
    }
    let mut params = base;
    if let Some(v) = spec.param("culling") {
        params.tile_culling = parse_choice(v).map_err(BenchError::Spec)?;
    }
    if let Some(v) = spec.param("indirect") {
        params.indirect = parse_choice(v).map_err(BenchError::Spec)?;
    }
    if let Some(v) = spec.param("groups") {
        params.plane_groups = parse_choice(v).map_err(BenchError::Spec)?;
    }
    if let Some(v) = spec.param("trees") {
        params.parallel_trees = parse_choice(v).map_err(BenchError::Spec)?;
    }
    if let Some(v) = spec.param("tree-index") {
        params.tree_index = parse_choice(v).map_err(BenchError::Spec)?;
    }
    if let Some(v) = spec.param("blockers") {
        params.path_blockers = parse_choice(v).map_err(BenchError::Spec)?;
    }
    if let Some(v) = spec.param("subgroups") {
        params.subgroup_cull = parse_choice(v).map_err(BenchError::Spec)?;
    }
    if let Some(v) = spec.param("fused-lists") {
        params.fused_lists = parse_choice(v).map_err(BenchError::Spec)?;
    }
    Ok(Some((settings, params)))
}

/// `glossy-taps=`: the glossy blur's most taps a pixel (0 and 1 are the bench's cost
/// probes, not a blur: `--glossy` rows of the runtime suite).
fn glossy_taps(v: &str) -> Result<u32, String> {
    match v.parse::<u32>() {
        Ok(n) if (2..=64).contains(&n) => Ok(n),
        _ => Err(format!("glossy-taps: `{v}` is not a whole number from 2 to 64")),
    }
}

/// `timing=`: whether PPR is timed as a whole frame (`frame`) or pass by pass (`passes`).
fn frame_timing(v: &str) -> Result<bool, String> {
    match v {
        "frame" => Ok(true),
        "passes" => Ok(false),
        _ => Err(format!("timing: `{v}` is neither `passes` nor `frame`")),
    }
}

/// `upsample=`: whether the reduced tiers' upsample reads each workgroup's reduced samples
/// once into workgroup memory (`shared`) or each pixel its own (`per-pixel`), and which
/// probe of its time replaces it, if any (`store-only`, `depth-only`, `no-own-depth`).
fn upsample_mode(v: &str) -> Result<(bool, UpsampleProbe), String> {
    match v {
        "shared" => Ok((true, UpsampleProbe::None)),
        "per-pixel" => Ok((false, UpsampleProbe::None)),
        "store-only" => Ok((false, UpsampleProbe::StoreOnly)),
        "depth-only" => Ok((false, UpsampleProbe::DepthOnly)),
        "no-own-depth" => Ok((false, UpsampleProbe::NoOwnDepth)),
        _ => Err(format!(
            "upsample: `{v}` is none of `per-pixel`, `shared`, `store-only`, `depth-only`, `no-own-depth`"
        )),
    }
}

/// Builds the technique `spec` names.
///
/// # Errors
/// [`BenchError::Spec`] for an unknown name or setting.
pub fn build_technique(
    spec: &TechniqueSpec,
    ctx: &TechniqueContext<'_>,
) -> Result<Box<dyn BenchTechnique>, BenchError> {
    if let Some((settings, params)) = ppr_settings(spec, ctx.plan_params)? {
        let mut runner =
            PprRunner::new(ctx.device, ctx.queue, ctx.reflectors, spec.label(), settings, params)?;
        runner.set_bounces(ppr_bounces(spec)?);
        runner.set_reference_bounces(reference_bounces(spec)?);
        if let Some(v) = spec.param("timing") {
            runner.renderer().debug.frame_span = frame_timing(v).map_err(BenchError::Spec)?;
        }
        if let Some(v) = spec.param("glossy-taps") {
            runner.renderer().debug.glossy_taps = Some(glossy_taps(v).map_err(BenchError::Spec)?);
        }
        if let Some(v) = spec.param("upsample") {
            let (shared, probe) = upsample_mode(v).map_err(BenchError::Spec)?;
            runner.renderer().debug.shared_upsample = shared;
            runner.renderer().debug.upsample_probe = probe;
        }
        return Ok(Box::new(runner));
    }
    let (device, queue, set) = (ctx.device, ctx.queue, ctx.reflectors);
    let num = |key: &str| spec.param(key).and_then(|v| v.parse::<f32>().ok());
    let int = |key: &str| spec.param(key).and_then(|v| v.parse::<u32>().ok());
    let runner =
        |family, inner: Box<dyn ReflectionTechnique>| -> Result<Box<dyn BenchTechnique>, BenchError> {
            let mut runner = TraitRunner::new(spec.label(), family, inner);
            if let Some(v) = spec.param("timing")
                && frame_timing(v).map_err(BenchError::Spec)?
            {
                runner = runner.with_frame_timing(device, queue);
            }
            Ok(Box::new(runner.with_reference_bounces(reference_bounces(spec)?)))
        };
    match spec.name.as_str() {
        "exact" => Ok(Box::new(ExactReference::with_bounces(
            device,
            queue,
            (ctx.level, set),
            ctx.render,
            spec.param("bounces").and_then(|v| v.parse().ok()).unwrap_or(1),
        ))),
        "ssr-brute" | "ssr-low" => {
            let mut s = if spec.name == "ssr-brute" {
                SsrSettings::brute_force()
            } else {
                SsrSettings::low_quality()
            };
            s.stride = int("stride").unwrap_or(s.stride);
            s.refine_steps = int("refine").unwrap_or(s.refine_steps);
            s.thickness = num("thickness").unwrap_or(s.thickness);
            runner(Family::Ssr, Box::new(SsrTechnique::new(device, queue, set, s)))
        }
        "ssr-glossy" => {
            let mut s = SsrGlossySettings::low_quality();
            s.march.stride = int("stride").unwrap_or(s.march.stride);
            s.march.refine_steps = int("refine").unwrap_or(s.march.refine_steps);
            s.march.thickness = num("thickness").unwrap_or(s.march.thickness);
            s.spread = num("spread").unwrap_or(s.spread);
            s.max_radius = num("max-radius").unwrap_or(s.max_radius);
            s.samples = int("taps").unwrap_or(s.samples);
            runner(Family::Ssr, Box::new(SsrGlossyTechnique::new(device, queue, set, s)))
        }
        "ssr-hiz" => {
            let mut s = HiZSettings::seed();
            s.max_iterations = int("iterations").unwrap_or(s.max_iterations);
            if let Some(t) = num("thickness") {
                s.thickness = Some(t);
            }
            runner(Family::Ssr, Box::new(HiZSsrTechnique::new(device, queue, set, s)))
        }
        "sspr" => {
            runner(Family::Sspr, Box::new(SsprTechnique::new(device, queue, set, SsprSettings::seed())))
        }
        "sspr-stretch" => runner(
            Family::Sspr,
            Box::new(SsprTechnique::new(device, queue, set, SsprSettings::with_edge_stretch())),
        ),
        "planar" => runner(
            Family::Exact,
            Box::new(PlanarReflectionTechnique::new(
                device,
                queue,
                ctx.level,
                set,
                RenderSettings::default(),
            )),
        ),
        other => Err(BenchError::Spec(format!("technique `{other}` cannot be built"))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_parse_and_print() {
        let s: TechniqueSpec = "ppr:culling=off,indirect=on".parse().expect("spec");
        assert_eq!(s.name, "ppr");
        assert_eq!(s.label(), "ppr culling=off indirect=on");
        assert_eq!(s.to_string(), "ppr:culling=off,indirect=on");
        let framed: TechniqueSpec = "ppr:timing=frame".parse().expect("frame timing");
        assert_eq!(framed.param("timing"), Some("frame"));
        assert!("ppr:timing=fast".parse::<TechniqueSpec>().is_err());
        assert!("ssr-low:timing=frame".parse::<TechniqueSpec>().is_ok());
        assert!("exact:timing=frame".parse::<TechniqueSpec>().is_err());
        let shared: TechniqueSpec = "ppr:tier=half,upsample=shared".parse().expect("shared upsample");
        assert_eq!(shared.label(), "ppr tier=half upsample=shared");
        assert_eq!(upsample_mode(shared.param("upsample").expect("set")), Ok((true, UpsampleProbe::None)));
        let own: TechniqueSpec = "ppr-filter:upsample=per-pixel".parse().expect("per-pixel upsample");
        assert_eq!(upsample_mode(own.param("upsample").expect("set")), Ok((false, UpsampleProbe::None)));
        let probe: TechniqueSpec = "ppr:tier=quarter,upsample=depth-only".parse().expect("a probe");
        assert_eq!(
            upsample_mode(probe.param("upsample").expect("set")),
            Ok((false, UpsampleProbe::DepthOnly))
        );
        let wrong = "ppr:tier=half,upsample=tiled".parse::<TechniqueSpec>().expect_err("not a mode");
        let message = wrong.to_string();
        assert!(
            message.contains("ppr:tier=half,upsample=tiled") && message.contains("per-pixel"),
            "{message}"
        );
        assert!("ssr-low:upsample=shared".parse::<TechniqueSpec>().is_err());
        let sharp: TechniqueSpec = "ppr:glossy=off".parse().expect("glossy");
        let (settings, _) = ppr_settings(&sharp, PlanParams::default()).expect("valid").expect("ppr");
        assert!(!settings.glossy);
        let separate: TechniqueSpec = "ppr:fused-lists=off".parse().expect("fused lists");
        let (_, params) = ppr_settings(&separate, PlanParams::default()).expect("valid").expect("ppr");
        assert_eq!(params.fused_lists, Choice::Off);
        assert!("ppr:fused-lists=sometimes".parse::<TechniqueSpec>().is_err());
        let open: TechniqueSpec = "ppr:blockers=off".parse().expect("path blockers");
        let (_, params) = ppr_settings(&open, PlanParams::default()).expect("valid").expect("ppr");
        assert_eq!(params.path_blockers, Choice::Off);
        assert!("ppr:blockers=maybe".parse::<TechniqueSpec>().is_err());
        let walked: TechniqueSpec = "ppr:tree-index=off".parse().expect("tree index");
        let (_, params) = ppr_settings(&walked, PlanParams::default()).expect("valid").expect("ppr");
        assert_eq!(params.tree_index, Choice::Off);
        assert!("ppr:tree-index=fast".parse::<TechniqueSpec>().is_err());
        assert!("ssr-low:tree-index=off".parse::<TechniqueSpec>().is_err());
        assert!("ssr-low:blockers=off".parse::<TechniqueSpec>().is_err());
        assert!("ppr:glossy=blurry".parse::<TechniqueSpec>().is_err());
        let eight: TechniqueSpec = "ppr:glossy-taps=8".parse().expect("glossy taps");
        assert_eq!(eight.label(), "ppr glossy-taps=8");
        for bad in
            ["ppr:glossy-taps=1", "ppr:glossy-taps=65", "ppr:glossy-taps=many", "ssr-low:glossy-taps=8"]
        {
            assert!(bad.parse::<TechniqueSpec>().is_err(), "{bad}");
        }
        assert!("nope".parse::<TechniqueSpec>().is_err());
        assert!("ppr:culling=maybe".parse::<TechniqueSpec>().is_err());
        assert!("exact:steps=3".parse::<TechniqueSpec>().is_err());
        assert!("ssr-low:stride=x".parse::<TechniqueSpec>().is_err());
        let glossy: TechniqueSpec =
            "ssr-glossy:spread=3,max-radius=16,taps=12,stride=8".parse().expect("glossy");
        assert_eq!(glossy.label(), "ssr-glossy spread=3 max-radius=16 taps=12 stride=8");
        assert!("ssr-glossy:spread=-1".parse::<TechniqueSpec>().is_err());
        assert!("ssr-glossy:taps=many".parse::<TechniqueSpec>().is_err());
        assert!("ssr-low:spread=2".parse::<TechniqueSpec>().is_err());
        assert_eq!(
            "ssr-low:stride=16,refine=4".parse::<TechniqueSpec>().expect("ssr").label(),
            "ssr-low stride=16 refine=4"
        );
        assert_eq!(TechniqueSpec::defaults().len(), DEFAULT_TECHNIQUES.len());
        assert!("ppr:culling".parse::<TechniqueSpec>().is_err());
        let fed: TechniqueSpec = "ppr:bounces=2".parse().expect("bounces");
        assert_eq!((fed.label().as_str(), ppr_bounces(&fed).ok()), ("ppr bounces=2", Some(2)));
        assert_eq!(ppr_bounces(&TechniqueSpec::named("ppr")).ok(), Some(1));
        assert!("ppr:bounces=0".parse::<TechniqueSpec>().is_err());
        assert!("ppr:bounces=9".parse::<TechniqueSpec>().is_err());
        assert!("ssr-low:bounces=2".parse::<TechniqueSpec>().is_err());
        let rescored: TechniqueSpec = "ssr-brute:reference-bounces=2".parse().expect("rescored");
        assert_eq!(reference_bounces(&rescored).ok(), Some(2));
        assert_eq!(reference_bounces(&fed).ok(), Some(2));
        assert!("exact:reference-bounces=2".parse::<TechniqueSpec>().is_err());
        assert!("exact:bounces=2".parse::<TechniqueSpec>().is_ok());
        for (name, _) in KNOWN_TECHNIQUES {
            assert_eq!(name.parse::<TechniqueSpec>().expect("known").label(), name);
        }
    }
}
