//! Picks among derived candidate cameras by rendering each at a small size and counting the
//! reflector pixels whose reflected point is on screen (what the comparison measures).

use ppr_testbed::{FrameImages, GpuContext, LevelRenderer};

use crate::error::BenchError;
use crate::scene::BenchScene;

/// Size the candidates are rendered at.
const RANK_SIZE: [u32; 2] = [320, 180];

/// Keeps the overview and the `count − 1` candidate views with the most on-screen reflector
/// pixels (at most one view per reflector), when the scene's cameras were derived.
///
/// # Errors
/// A readback fails.
pub fn rank_cameras(gpu: &GpuContext, scene: &mut BenchScene, count: usize) -> Result<(), BenchError> {
    if !scene.cameras_derived || scene.cameras.len() <= count {
        scene.cameras.truncate(count.max(1));
        return Ok(());
    }
    let (device, queue) = (&gpu.device, &gpu.queue);
    let mut level = LevelRenderer::new(device, queue, &scene.level, &scene.reflectors);
    level.settings = scene.render_settings();
    let mut scored = Vec::new();
    for (k, cam) in scene.cameras.iter().enumerate().skip(1) {
        level.render(device, queue, &cam.camera, RANK_SIZE);
        let images = FrameImages::read(device, queue, &level)?;
        let on = images.on_screen_mask().count();
        scored.push((on, k));
    }
    scored.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut keep = vec![0];
    let mut reflectors_used: Vec<String> = Vec::new();
    for (_, k) in scored {
        if keep.len() >= count {
            break;
        }
        // Names are `view-<reflector>-<direction>`: one view per reflector.
        let name = &scene.cameras[k].name;
        let reflector = name.rsplit_once('-').map_or(name.as_str(), |(r, _)| r).to_string();
        if !reflectors_used.contains(&reflector) {
            reflectors_used.push(reflector);
            keep.push(k);
        }
    }
    let cameras = std::mem::take(&mut scene.cameras);
    scene.cameras = keep.into_iter().map(|k| cameras[k].clone()).collect();
    scene.cameras_derived = false;
    scene.notes.push(format!(
        "cameras derived from the bounds and the largest reflectors, ranked by on-screen reflection at {}x{}: {}",
        RANK_SIZE[0],
        RANK_SIZE[1],
        scene.cameras.iter().map(|c| c.name.as_str()).collect::<Vec<_>>().join(", ")
    ));
    Ok(())
}
