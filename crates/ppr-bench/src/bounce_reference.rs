//! The exact reference with more than one bounce, for rows that feed PPR its previous
//! frame (`ppr:bounces=N` is scored against the N-bounce reference; every other row
//! against the one-bounce reference, as before).

use std::collections::BTreeSet;
use std::sync::Arc;

use ppr_runtime::Camera;
use ppr_testbed::{FrameImages, LevelRenderer};

use crate::error::BenchError;
use crate::quality::ReferenceFrame;

/// The deeper references of one camera and size.
#[derive(Default)]
pub struct DeeperReferences {
    frames: Vec<(u32, Arc<ReferenceFrame>)>,
}

impl DeeperReferences {
    /// Renders the reference at each of `depths` (those above 1) for `camera` at `size` and
    /// reads it back, then leaves `level` prepared and rendered at one bounce again (the
    /// `exact` row times the one-bounce reference). Notes name views the cost cap skipped
    /// (`what` names the frame: scene, camera, size).
    ///
    /// # Errors
    /// A readback fails.
    pub fn render(
        gpu: (&wgpu::Device, &wgpu::Queue),
        level: &mut LevelRenderer,
        camera: &Camera,
        size: [u32; 2],
        depths: &BTreeSet<u32>,
        what: &str,
        notes: &mut Vec<String>,
    ) -> Result<Self, BenchError> {
        let (device, queue) = gpu;
        let mut frames = Vec::new();
        let deeper: Vec<u32> = depths.iter().copied().filter(|&d| d > 1).collect();
        if deeper.is_empty() {
            return Ok(Self { frames });
        }
        for d in deeper {
            level.settings.reference_bounces = d;
            let summary = level.render(device, queue, camera, size);
            if summary.bounce_views_skipped > 0 {
                notes.push(format!(
                    "{what}: {d}-bounce reference not exact: {} views beyond the first bounce \
                     rendered, {} more over the cap of {} skipped (those mirrors show their own \
                     colour at that bounce)",
                    summary.bounce_views, summary.bounce_views_skipped, level.settings.max_bounce_views
                ));
            }
            frames.push((d, Arc::new(ReferenceFrame::new(FrameImages::read(device, queue, level)?))));
        }
        level.settings.reference_bounces = 1;
        level.render(device, queue, camera, size);
        Ok(Self { frames })
    }

    /// The reference of `depth` bounces: `one` for 1, else the deeper one rendered (or
    /// `None` when it was not).
    pub fn pick(&self, depth: u32, one: Option<&Arc<ReferenceFrame>>) -> Option<Arc<ReferenceFrame>> {
        if depth <= 1 {
            return one.cloned();
        }
        self.frames.iter().find(|(d, _)| *d == depth).map(|(_, f)| Arc::clone(f))
    }
}
