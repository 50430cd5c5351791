//! Accuracy of a camera case against the f64 CPU projection and the exact reflection, and
//! the bounds the camera cases assert on it (docs/stability.md, "Cameras"). Each bound is
//! also checked against an output that holds nothing, so that a runtime that wrote
//! nothing fails every case whose CPU reference writes something.

use glam::Vec4;
use ppr_runtime::{CLEAR_VALUE, EncodingLayout};
use ppr_tests::harness::compare;
use ppr_tests::scene::Frame;

/// How far a GPU offset may be from the CPU reference's and still count as the same
/// source: a pixel (f32 positions on the GPU, f64 here; the fraction's quantisation).
pub const SAME_SOURCE_PX: f32 = 1.0;

/// What a case's output holds, measured against the f64 CPU projection
/// (`ppr_tests::harness::cpu_projection`) and the exact reflection.
#[derive(Debug, Clone, Copy, Default)]
pub struct Accuracy {
    /// Target pixels the CPU reference writes.
    pub cpu_written: usize,
    /// Of those, the ones where the GPU stores an offset within [`SAME_SOURCE_PX`] of the
    /// CPU's (the same source pixel).
    pub matched: usize,
    /// Target pixels the GPU writes and the CPU reference does not.
    pub extra: usize,
    /// Mirror pixels whose reflected point is on screen (the exact reflection's mask).
    pub on_screen: usize,
    /// Of those, the ones with a reflection in the output (alpha > 0).
    pub covered: usize,
    /// PSNR over the on-screen mask against the exact reflection (empty pixels count as
    /// black); infinite without on-screen pixels.
    pub psnr: f64,
}

impl Accuracy {
    /// Share of the CPU reference's writes the GPU stores with the same source (1 when the
    /// reference writes nothing).
    pub fn matched_share(&self) -> f64 {
        share(self.matched, self.cpu_written)
    }

    /// Share of the on-screen mirror pixels the output reflects (1 when there are none).
    pub fn covered_share(&self) -> f64 {
        share(self.covered, self.on_screen)
    }
}

fn share(part: usize, whole: usize) -> f64 {
    if whole == 0 { 1.0 } else { part as f64 / whole as f64 }
}

/// Measures an output (`pixels`: the reflection; `intermediate`: the projection's buffer
/// in `layout`) against the CPU reference's buffer `cpu`
/// (`ppr_tests::harness::cpu_projection`) and the exact reflection.
pub fn measure(
    frame: &Frame,
    cpu: &[u32],
    layout: &EncodingLayout,
    pixels: &[Vec4],
    intermediate: &[u32],
) -> Accuracy {
    let cpu_layout = EncodingLayout::for_resolution(frame.size[0], frame.size[1]);
    let mut a = Accuracy::default();
    for (i, &c) in cpu.iter().enumerate() {
        let g = intermediate.get(i).copied().unwrap_or(CLEAR_VALUE);
        let gpu = ppr_runtime::encoding::decode(g, layout);
        match ppr_runtime::encoding::decode(c, &cpu_layout) {
            None => a.extra += usize::from(gpu.is_some()),
            Some(c) => {
                a.cpu_written += 1;
                a.matched +=
                    usize::from(gpu.is_some_and(|g| (g.offset() - c.offset()).length() <= SAME_SOURCE_PX));
            }
        }
    }
    let quality = compare(frame, pixels, |i| frame.on_screen[i]);
    a.on_screen = quality.pixels;
    a.covered = quality.pixels - quality.empty;
    a.psnr = if quality.pixels > 0 { quality.psnr } else { f64::INFINITY };
    a
}

/// The least a case must reach: shares in [0, 1], PSNR in dB.
#[derive(Debug, Clone, Copy)]
pub struct Bounds {
    /// Least share of the CPU reference's writes stored with the same source.
    pub matched: f64,
    /// Most GPU writes where the CPU reference has none, as a share of its writes.
    pub extra: f64,
    /// Least share of the on-screen mirror pixels reflected.
    pub covered: f64,
    /// Least PSNR over the on-screen mask.
    pub psnr: f64,
}

impl Bounds {
    /// What `a` breaks, one line per bound: (matched, extra, covered, PSNR).
    fn violations(&self, a: &Accuracy) -> [Option<String>; 4] {
        [
            (a.matched_share() < self.matched).then(|| {
                format!(
                    "{} of {} CPU writes matched ({:.1}% < {:.1}%)",
                    a.matched,
                    a.cpu_written,
                    100.0 * a.matched_share(),
                    100.0 * self.matched
                )
            }),
            (a.extra as f64 > self.extra * a.cpu_written as f64).then(|| {
                format!(
                    "{} GPU writes where the CPU has none (> {:.1}% of {})",
                    a.extra,
                    100.0 * self.extra,
                    a.cpu_written
                )
            }),
            (a.covered_share() < self.covered).then(|| {
                format!(
                    "{} of {} on-screen pixels reflected ({:.1}% < {:.1}%)",
                    a.covered,
                    a.on_screen,
                    100.0 * a.covered_share(),
                    100.0 * self.covered
                )
            }),
            (a.psnr < self.psnr).then(|| format!("PSNR {:.1} dB < {:.1} dB", a.psnr, self.psnr)),
        ]
    }

    /// Asserts that `a` holds the bounds, and that an output holding nothing breaks each
    /// of them that can see it whenever the CPU reference writes something: the matched
    /// share, and the covered share and the PSNR if the exact reflection has on-screen
    /// pixels (the bound on extra writes guards against false writes instead). Returns
    /// what the output holding nothing measures.
    pub fn check(&self, name: &str, frame: &Frame, cpu: &[u32], a: &Accuracy) -> Accuracy {
        let broken: Vec<String> = self.violations(a).into_iter().flatten().collect();
        assert!(broken.is_empty(), "{name}: {}", broken.join("; "));
        let n = (frame.size[0] * frame.size[1]) as usize;
        let layout = EncodingLayout::for_resolution(frame.size[0], frame.size[1]);
        let empty = measure(frame, cpu, &layout, &vec![Vec4::ZERO; n], &vec![CLEAR_VALUE; n]);
        let [matched, _, covered, psnr] = self.violations(&empty).map(|v| v.is_some());
        let sees = |seen: bool, there: bool, what: &str| {
            assert!(
                seen || !there,
                "{name}: the {what} bound must reject an output that holds nothing: {empty:?}"
            )
        };
        sees(matched, a.cpu_written > 0, "matched");
        sees(covered, a.cpu_written > 0 && a.on_screen > 0, "covered");
        sees(psnr, a.cpu_written > 0 && a.on_screen > 0, "PSNR");
        empty
    }
}
