//! Issue 13's goals judged from the bench's rows: whole frames at 4K, the projection
//! against its floor, PPR against the cheapest low-quality SSR, the generated levels' cost
//! against shape count, and collision-world. One [`Check`] per scene, camera or family
//! measured; a goal with no rows in the files has no check (the report says so).

use std::collections::{BTreeMap, BTreeSet};

use crate::goals::bench_rows::{CompareRow, RuntimeRow};
use crate::scaling::level_family::LevelFamily;

/// Most ms of a whole PPR frame at 4K.
pub const FRAME_4K_MS: f64 = 0.15;
/// Most times its bandwidth floor for the projection pass.
pub const FLOOR_RATIO: f64 = 4.0;
/// Most ms a generated family's 1 000-shape frame may cost above its 1-shape frame.
pub const SCALING_1000_OVER_MS: f64 = 0.25;
/// Most ms of a generated family's 10 000-shape frame.
pub const SCALING_10000_MS: f64 = 2.0;
/// Most ms of a 4K frame of collision-world.
pub const COLLISION_4K_MS: f64 = 1.5;
/// The scenes of the compare goal.
pub const COMPARE_SCENES: [&str; 2] = ["demo", "kitchen"];

/// One goal of the issue.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Goal {
    Frame4k,
    ProjectionFloor,
    CompareCost,
    ComparePsnr,
    Scaling1000,
    Scaling10000,
    SubLinear,
    CollisionWorld,
}

impl Goal {
    pub const ALL: [Self; 8] = [
        Self::Frame4k,
        Self::ProjectionFloor,
        Self::CompareCost,
        Self::ComparePsnr,
        Self::Scaling1000,
        Self::Scaling10000,
        Self::SubLinear,
        Self::CollisionWorld,
    ];

    /// What the goal asks, in words.
    pub fn title(self) -> String {
        match self {
            Self::Frame4k => format!("A whole PPR frame at 4K ≤ {FRAME_4K_MS} ms (runtime `frame span` rows)"),
            Self::ProjectionFloor => {
                format!("The projection pass ≤ {FLOOR_RATIO}× its floor at 4K (runtime `reflection own pass` rows)")
            }
            Self::CompareCost => {
                "Full PPR no dearer than the cheapest low-quality SSR (compare: camera means of `ppr` against `ssr-low*`)"
                    .into()
            }
            Self::ComparePsnr => "Full PPR's on-screen PSNR no lower than the baseline's (compare, camera means)".into(),
            Self::Scaling1000 => format!(
                "At 1 000 shapes ≤ {SCALING_1000_OVER_MS} ms above the family's 1-shape frame (runtime on `<family>-<count>`, 4K, passes)"
            ),
            Self::Scaling10000 => format!("At 10 000 shapes ≤ {SCALING_10000_MS} ms (runtime on `<family>-<count>`, 4K, passes)"),
            Self::SubLinear => "Cost sub-linear in shape count (growth exponent < 1 between successive counts)".into(),
            Self::CollisionWorld => format!("collision-world ≤ {COLLISION_4K_MS} ms a 4K frame (compare)"),
        }
    }
}

/// One judged measurement.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    pub goal: Goal,
    /// What was measured (`demo cam_mirror 4K`, `stairway`).
    pub subject: String,
    /// The number the goal bounds (ms, a ratio, dB of difference, an exponent).
    pub value: f64,
    pub met: bool,
    /// The numbers behind the value.
    pub detail: String,
}

/// What the checks read.
#[derive(Clone, Copy, Debug)]
pub struct GoalInputs<'a> {
    pub runtime: &'a [RuntimeRow],
    pub compare: &'a [CompareRow],
    /// A compare run of the code the PSNR goal compares with (the "today").
    pub baseline: Option<&'a [CompareRow]>,
    /// How far below the baseline's PSNR still counts as no lower (rounding of the files).
    pub psnr_tolerance_db: f64,
}

/// The checks of a judgement, and what could not be judged and why.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Verdicts {
    pub checks: Vec<Check>,
    /// Lines for the report: comparisons left out (a baseline scored against another
    /// reference, with no camera in common).
    pub notes: Vec<String>,
}

/// Every check the rows allow, goal by goal.
pub fn check_goals(inputs: &GoalInputs<'_>) -> Verdicts {
    let mut v = Verdicts::default();
    v.checks.extend(frame_checks(inputs.runtime));
    v.checks.extend(floor_checks(inputs.runtime));
    compare_checks(inputs, &mut v);
    v.checks.extend(scaling_checks(inputs.runtime));
    v.checks.extend(collision_checks(inputs.compare));
    v.checks.sort_by_key(|c| c.goal);
    v
}

/// `4K`, `1080p` or `WxH`.
pub fn size_name(width: u32, height: u32) -> String {
    match (width, height) {
        (3840, 2160) => "4K".into(),
        (1920, 1080) => "1080p".into(),
        _ => format!("{width}x{height}"),
    }
}

fn is_4k(width: u32, height: u32) -> bool {
    (width, height) == (3840, 2160)
}

/// A scene of the runtime suite's own (demo, kitchen, a level): not a generated family and
/// not a variant row such as `demo (features off)`.
fn is_plain_scene(scene: &str) -> bool {
    LevelFamily::from_scene_name(scene).is_none() && !scene.contains(" (")
}

/// The first row of each key, in file order.
fn first_by_key<'a, K: Ord + Clone>(
    rows: impl Iterator<Item = &'a RuntimeRow>,
    key: impl Fn(&RuntimeRow) -> K,
) -> Vec<(K, &'a RuntimeRow)> {
    let mut seen = BTreeSet::new();
    rows.filter_map(|r| {
        let k = key(r);
        seen.insert(k.clone()).then_some((k, r))
    })
    .collect()
}

fn frame_checks(rows: &[RuntimeRow]) -> Vec<Check> {
    let at_4k = || rows.iter().filter(|r| is_4k(r.width, r.height) && is_plain_scene(r.scene_and_row().0));
    let frames = first_by_key(
        at_4k().filter(|r| r.scene_and_row().1 == Some("frame span") && r.pass == "frame"),
        |r| (r.scene_and_row().0.to_owned(), r.camera.clone()),
    );
    let mut checks: Vec<Check> = frames
        .iter()
        .map(|((scene, camera), r)| Check {
            goal: Goal::Frame4k,
            subject: format!("{scene} {camera} 4K"),
            value: r.median_ms,
            met: r.median_ms <= FRAME_4K_MS,
            detail: "whole frame".into(),
        })
        .collect();
    // A camera without a frame-span row is judged by its passes (a frame costs a few
    // thousandths of a ms more than they do).
    let passes = first_by_key(
        at_4k().filter(|r| r.scene_and_row().1.is_none() && r.pass == "projection + reflection"),
        |r| (r.scene_and_row().0.to_owned(), r.camera.clone()),
    );
    for ((scene, camera), r) in passes {
        if !frames.iter().any(|(k, _)| k.0 == scene && k.1 == camera) {
            checks.push(Check {
                goal: Goal::Frame4k,
                subject: format!("{scene} {camera} 4K"),
                value: r.median_ms,
                met: r.median_ms <= FRAME_4K_MS,
                detail: "passes only (no frame span row)".into(),
            });
        }
    }
    checks
}

fn floor_checks(rows: &[RuntimeRow]) -> Vec<Check> {
    let own = rows.iter().filter(|r| {
        let (scene, row) = r.scene_and_row();
        is_4k(r.width, r.height)
            && is_plain_scene(scene)
            && row == Some("reflection own pass")
            && r.pass == "projection"
    });
    first_by_key(own, |r| (r.scene_and_row().0.to_owned(), r.camera.clone()))
        .into_iter()
        .map(|((scene, camera), r)| Check {
            goal: Goal::ProjectionFloor,
            subject: format!("{scene} {camera} 4K"),
            value: r.ratio_to_floor,
            met: r.ratio_to_floor <= FLOOR_RATIO,
            detail: format!("projection {:.4} ms", r.median_ms),
        })
        .collect()
}

/// The mean of a technique's `f` over `cameras` of one scene and size, if it has them all.
fn camera_mean(
    rows: &[CompareRow],
    scene: &str,
    size: (u32, u32),
    technique: &str,
    cameras: &[String],
    f: impl Fn(&CompareRow) -> f64,
) -> Option<f64> {
    let values: Vec<f64> = cameras
        .iter()
        .map(|c| {
            rows.iter()
                .find(|r| {
                    r.scene == scene
                        && (r.width, r.height) == size
                        && r.technique == technique
                        && r.camera == *c
                })
                .map(&f)
        })
        .collect::<Option<_>>()?;
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

/// The cheapest low-quality SSR setting's mean time over `cameras`: its name and ms.
fn cheapest_ssr_low(
    rows: &[CompareRow],
    scene: &str,
    size: (u32, u32),
    cameras: &[String],
    whole_frame: bool,
) -> Option<(String, f64)> {
    let mut names: Vec<&str> = rows
        .iter()
        .filter(|r| {
            r.scene == scene
                && (r.width, r.height) == size
                && r.technique.starts_with("ssr-low")
                && r.technique.contains("timing=frame") == whole_frame
        })
        .map(|r| r.technique.as_str())
        .collect();
    names.sort_unstable();
    names.dedup();
    names
        .into_iter()
        .filter_map(|t| {
            camera_mean(rows, scene, size, t, cameras, |r| r.gpu_total_median_ms).map(|ms| (t.to_owned(), ms))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

fn compare_checks(inputs: &GoalInputs<'_>, v: &mut Verdicts) {
    let rows = inputs.compare;
    for scene in COMPARE_SCENES {
        let mut sizes: Vec<(u32, u32)> = rows
            .iter()
            .filter(|r| r.scene == scene && r.technique == "ppr")
            .map(|r| (r.width, r.height))
            .collect();
        sizes.sort_unstable();
        sizes.dedup();
        for size in sizes {
            let name = size_name(size.0, size.1);
            let mut cameras: Vec<String> = rows
                .iter()
                .filter(|r| r.scene == scene && (r.width, r.height) == size && r.technique == "ppr")
                .map(|r| r.camera.clone())
                .collect();
            cameras.sort_unstable();
            cameras.dedup();
            for (ppr, whole_frame, what) in
                [("ppr", false, "passes"), ("ppr timing=frame", true, "whole frames")]
            {
                let Some(ppr_ms) = camera_mean(rows, scene, size, ppr, &cameras, |r| r.gpu_total_median_ms)
                else {
                    continue;
                };
                let Some((ssr, ssr_ms)) = cheapest_ssr_low(rows, scene, size, &cameras, whole_frame) else {
                    continue;
                };
                let ratio = ppr_ms / ssr_ms;
                v.checks.push(Check {
                    goal: Goal::CompareCost,
                    subject: format!("{scene} {name}, {what}"),
                    value: ratio,
                    met: ratio <= 1.0,
                    detail: format!(
                        "`{ppr}` {ppr_ms:.4} ms, `{ssr}` {ssr_ms:.4} ms ({} cameras)",
                        cameras.len()
                    ),
                });
            }
            let Some(baseline) = inputs.baseline else { continue };
            psnr_check(rows, baseline, scene, size, &cameras, inputs.psnr_tolerance_db, v);
        }
    }
}

/// Full PPR's on-screen PSNR against the baseline's, over the cameras both runs have, where
/// both scored against the same reference.
fn psnr_check(
    rows: &[CompareRow],
    baseline: &[CompareRow],
    scene: &str,
    size: (u32, u32),
    cameras: &[String],
    tolerance_db: f64,
    v: &mut Verdicts,
) {
    let name = size_name(size.0, size.1);
    let ppr_of = |rows: &'_ [CompareRow]| -> Vec<CompareRow> {
        rows.iter()
            .filter(|r| r.scene == scene && (r.width, r.height) == size && r.technique == "ppr")
            .cloned()
            .collect()
    };
    let (now, then) = (ppr_of(rows), ppr_of(baseline));
    if then.is_empty() {
        return;
    }
    let common: Vec<String> =
        cameras.iter().filter(|c| then.iter().any(|r| r.camera == **c)).cloned().collect();
    if common.is_empty() {
        v.notes
            .push(format!("PSNR of {scene} {name} not judged: the baseline has none of this run's cameras."));
        return;
    }
    let (reference_now, reference_then) = (&now[0].reference, &then[0].reference);
    if reference_now != reference_then {
        v.notes.push(format!(
            "PSNR of {scene} {name} not judged: this run scored against the `{reference_now}` reference, \
             the baseline against the `{reference_then}` one."
        ));
        return;
    }
    let psnr = |r: &CompareRow| r.psnr_on_screen_db;
    if let (Some(a), Some(b)) = (
        camera_mean(rows, scene, size, "ppr", &common, psnr),
        camera_mean(baseline, scene, size, "ppr", &common, psnr),
    ) {
        v.checks.push(Check {
            goal: Goal::ComparePsnr,
            subject: format!("{scene} {name}"),
            value: a - b,
            met: a >= b - tolerance_db,
            detail: format!(
                "{a:.2} dB against the baseline's {b:.2} dB ({} cameras, `{reference_now}` reference)",
                common.len()
            ),
        });
    }
}

fn scaling_checks(rows: &[RuntimeRow]) -> Vec<Check> {
    let mut families: BTreeMap<&str, BTreeMap<usize, f64>> = BTreeMap::new();
    for r in rows {
        let (scene, row) = r.scene_and_row();
        let Some((family, count)) = LevelFamily::from_scene_name(scene) else { continue };
        if row.is_none() && r.pass == "projection + reflection" && is_4k(r.width, r.height) {
            families.entry(family.as_str()).or_default().entry(count).or_insert(r.median_ms);
        }
    }
    let mut checks = Vec::new();
    for (family, counts) in families {
        let one = counts.get(&1).copied();
        if let (Some(one), Some(&at)) = (one, counts.get(&1000)) {
            checks.push(Check {
                goal: Goal::Scaling1000,
                subject: family.to_owned(),
                value: at - one,
                met: at - one <= SCALING_1000_OVER_MS,
                detail: format!("1 000 shapes {at:.4} ms, 1 shape {one:.4} ms"),
            });
        }
        if let Some(&at) = counts.get(&10_000) {
            checks.push(Check {
                goal: Goal::Scaling10000,
                subject: family.to_owned(),
                value: at,
                met: at <= SCALING_10000_MS,
                detail: "10 000 shapes".into(),
            });
        }
        let points: Vec<(usize, f64)> = counts.into_iter().collect();
        let exponents: Vec<(usize, usize, f64)> = points
            .windows(2)
            .map(|w| (w[0].0, w[1].0, (w[1].1 / w[0].1).ln() / (w[1].0 as f64 / w[0].0 as f64).ln()))
            .collect();
        if let Some(worst) = exponents.iter().map(|e| e.2).max_by(f64::total_cmp) {
            let list: Vec<String> = exponents.iter().map(|(a, b, e)| format!("{a}→{b}: {e:.2}")).collect();
            checks.push(Check {
                goal: Goal::SubLinear,
                subject: family.to_owned(),
                value: worst,
                met: worst < 1.0,
                detail: list.join(", "),
            });
        }
    }
    checks
}

fn collision_checks(rows: &[CompareRow]) -> Vec<Check> {
    let at_4k = |t: &str| -> Vec<&CompareRow> {
        rows.iter()
            .filter(|r| r.scene == "collision-world" && is_4k(r.width, r.height) && r.technique == t)
            .collect()
    };
    let frames = at_4k("ppr timing=frame");
    let (rows, what) = if frames.is_empty() { (at_4k("ppr"), "passes") } else { (frames, "whole frame") };
    rows.into_iter()
        .map(|r| Check {
            goal: Goal::CollisionWorld,
            subject: format!("collision-world {} 4K", r.camera),
            value: r.gpu_total_median_ms,
            met: r.gpu_total_median_ms <= COLLISION_4K_MS,
            detail: format!("{what}, on-screen PSNR {:.2} dB", r.psnr_on_screen_db),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn runtime(scene: &str, camera: &str, size: (u32, u32), pass: &str, ms: f64, ratio: f64) -> RuntimeRow {
        RuntimeRow {
            scene: scene.into(),
            camera: camera.into(),
            width: size.0,
            height: size.1,
            pass: pass.into(),
            median_ms: ms,
            ratio_to_floor: ratio,
        }
    }

    fn compare(
        scene: &str,
        camera: &str,
        size: (u32, u32),
        technique: &str,
        ms: f64,
        psnr: f64,
    ) -> CompareRow {
        CompareRow {
            scene: scene.into(),
            camera: camera.into(),
            width: size.0,
            height: size.1,
            technique: technique.into(),
            gpu_total_median_ms: ms,
            psnr_on_screen_db: psnr,
            reference: "mirror".into(),
        }
    }

    const UHD: (u32, u32) = (3840, 2160);
    const HD: (u32, u32) = (1920, 1080);

    fn judge(runtime: &[RuntimeRow], compare: &[CompareRow], baseline: Option<&[CompareRow]>) -> Vec<Check> {
        check_goals(&GoalInputs { runtime, compare, baseline, psnr_tolerance_db: 0.02 }).checks
    }

    fn of(checks: &[Check], goal: Goal) -> Vec<&Check> {
        checks.iter().filter(|c| c.goal == goal).collect()
    }

    #[test]
    fn frames_are_judged_by_their_span_and_by_their_passes_only_without_one() {
        let rows = [
            runtime("demo", "a", UHD, "projection + reflection", 0.140, 9.0),
            runtime("demo [frame span]", "a", UHD, "frame", 0.155, f64::NAN),
            runtime("demo", "b", UHD, "projection + reflection", 0.120, 9.0),
            // Not the goal's: another size, a variant row, a generated level.
            runtime("demo [frame span]", "a", HD, "frame", 0.05, f64::NAN),
            runtime("demo (features off)", "a", UHD, "projection + reflection", 0.01, 9.0),
            runtime("stairway-1", "scaling", UHD, "projection + reflection", 0.07, 9.0),
            runtime("demo [reflection own pass]", "a", UHD, "projection", 0.05, 3.5),
            runtime("demo [reflection own pass]", "b", UHD, "projection", 0.09, 8.0),
        ];
        let checks = judge(&rows, &[], None);
        let frames = of(&checks, Goal::Frame4k);
        assert_eq!(frames.len(), 2, "{frames:?}");
        // The span decides camera a (missed by 0.005 though its passes fit).
        assert_eq!((frames[0].subject.as_str(), frames[0].value, frames[0].met), ("demo a 4K", 0.155, false));
        assert_eq!((frames[1].subject.as_str(), frames[1].met), ("demo b 4K", true));
        assert!(frames[1].detail.contains("passes only"));
        let floors = of(&checks, Goal::ProjectionFloor);
        assert_eq!(floors.iter().map(|c| c.met).collect::<Vec<_>>(), [true, false]);
    }

    #[test]
    fn ppr_is_compared_with_the_cheapest_ssr_low_setting_over_the_same_cameras() {
        let rows = [
            compare("demo", "a", UHD, "ppr", 0.20, 25.0),
            compare("demo", "b", UHD, "ppr", 0.30, 27.0),
            compare("demo", "a", UHD, "ssr-low", 0.30, 20.0),
            compare("demo", "b", UHD, "ssr-low", 0.20, 20.0),
            compare("demo", "a", UHD, "ssr-low stride=16 refine=4", 0.20, 24.0),
            compare("demo", "b", UHD, "ssr-low stride=16 refine=4", 0.21, 24.0),
            // Missing camera b: not a candidate.
            compare("demo", "a", UHD, "ssr-low stride=128", 0.01, 10.0),
            compare("demo", "a", UHD, "ppr timing=frame", 0.22, 25.0),
            compare("demo", "b", UHD, "ppr timing=frame", 0.32, 27.0),
            compare("demo", "a", UHD, "ssr-low timing=frame", 0.31, 20.0),
            compare("demo", "b", UHD, "ssr-low timing=frame", 0.21, 20.0),
            // The kitchen at 1080p: cheaper than SSR.
            compare("kitchen", "k", HD, "ppr", 0.05, 30.0),
            compare("kitchen", "k", HD, "ssr-low", 0.06, 28.0),
        ];
        let baseline =
            [compare("demo", "a", UHD, "ppr", 0.5, 25.5), compare("demo", "b", UHD, "ppr", 0.5, 26.5)];
        let checks = judge(&[], &rows, Some(&baseline));
        let cost = of(&checks, Goal::CompareCost);
        assert_eq!(cost.len(), 3, "{cost:?}");
        // Means 0.25 against the stride-16 setting's 0.205 (ssr-low's mean is 0.25).
        assert!((cost[0].value - 0.25 / 0.205).abs() < 1e-9 && !cost[0].met, "{:?}", cost[0]);
        assert!(cost[0].detail.contains("`ssr-low stride=16 refine=4`"), "{}", cost[0].detail);
        assert!((cost[1].value - 0.27 / 0.26).abs() < 1e-9 && cost[1].subject == "demo 4K, whole frames");
        assert!(cost[2].met && cost[2].subject == "kitchen 1080p, passes");
        // PSNR: mean 26.0 against 26.0 (met); the kitchen has no baseline rows.
        let psnr = of(&checks, Goal::ComparePsnr);
        assert_eq!(psnr.len(), 1);
        assert!(psnr[0].met && psnr[0].value.abs() < 1e-9);
        let lower =
            [compare("demo", "a", UHD, "ppr", 0.5, 25.5), compare("demo", "b", UHD, "ppr", 0.5, 26.6)];
        let psnr = of(&judge(&[], &rows, Some(&lower)), Goal::ComparePsnr)[0].clone();
        assert!(!psnr.met && (psnr.value + 0.05).abs() < 1e-9, "{psnr:?}");
        // Over the cameras both runs have: camera b alone, 27.0 against 26.6.
        let one = [compare("demo", "b", UHD, "ppr", 0.5, 26.6), compare("demo", "z", UHD, "ppr", 0.5, 40.0)];
        let psnr = of(&judge(&[], &rows, Some(&one)), Goal::ComparePsnr)[0].clone();
        assert!(
            psnr.met && (psnr.value - 0.4).abs() < 1e-9 && psnr.detail.contains("(1 cameras"),
            "{psnr:?}"
        );
        // Another reference: not judged, and the notes say why.
        let mut glossy = baseline.to_vec();
        for r in &mut glossy {
            r.reference = "default".into();
        }
        let v = check_goals(&GoalInputs {
            runtime: &[],
            compare: &rows,
            baseline: Some(&glossy),
            psnr_tolerance_db: 0.02,
        });
        assert!(v.checks.iter().all(|c| c.goal != Goal::ComparePsnr));
        assert!(v.notes.iter().any(|n| n.contains("demo 4K") && n.contains("`default`")), "{:?}", v.notes);
    }

    #[test]
    fn families_are_judged_against_their_own_one_shape_frame() {
        let pass = "projection + reflection";
        let rows = [
            runtime("stairway-1", "scaling", UHD, pass, 0.07, 9.0),
            runtime("stairway-1000", "scaling", UHD, pass, 0.53, 9.0),
            runtime("stairway-10000", "scaling", UHD, pass, 1.46, 9.0),
            runtime("stairway-1000 [path blockers off]", "scaling", UHD, pass, 0.67, 9.0),
            runtime("rooms-1", "scaling", UHD, pass, 0.07, 9.0),
            runtime("rooms-10", "scaling", UHD, pass, 1.00, 9.0),
            runtime("rooms-1000", "scaling", UHD, pass, 0.30, 9.0),
        ];
        let checks = judge(&rows, &[], None);
        let at_1000 = of(&checks, Goal::Scaling1000);
        assert_eq!(
            at_1000.iter().map(|c| (c.subject.as_str(), c.met)).collect::<Vec<_>>(),
            [("rooms", true), ("stairway", false)]
        );
        assert!((at_1000[1].value - 0.46).abs() < 1e-9);
        assert_eq!(of(&checks, Goal::Scaling10000).len(), 1);
        // rooms: 1 → 10 grows with exponent log(1/0.07)/log(10) = 1.15: not sub-linear.
        let growth = of(&checks, Goal::SubLinear);
        assert!(
            !growth[0].met && (growth[0].value - (1.0f64 / 0.07).log10()).abs() < 1e-9,
            "{:?}",
            growth[0]
        );
        assert!(growth[1].met);
    }

    #[test]
    fn collision_world_is_judged_by_whole_frames_where_it_has_them() {
        let rows = [
            compare("collision-world", "a", UHD, "ppr", 0.4, 30.0),
            compare("collision-world", "a", UHD, "ppr timing=frame", 1.6, 30.0),
            compare("collision-world", "a", HD, "ppr timing=frame", 0.1, 30.0),
        ];
        let checks = judge(&[], &rows, None);
        let c = of(&checks, Goal::CollisionWorld);
        assert_eq!(c.len(), 1);
        assert!(!c[0].met && (c[0].value - 1.6).abs() < 1e-12);
        let passes_only = judge(&[], &rows[..1], None);
        assert!(passes_only[0].met && passes_only[0].detail.starts_with("passes"));
    }
}
