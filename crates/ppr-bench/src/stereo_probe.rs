//! A stereo frame against two mono frames: both eyes of a headset (64 mm apart) at a
//! per-eye size, PPR from one renderer as `prepare_stereo` + `encode_stereo`, and as two
//! mono frames (`prepare`, `encode`, `prepare`, `encode`) into one encoder. Each is timed
//! by encoder timestamps around its PPR commands (uploads included), the L2 evicted before.

use glam::Vec3;
use ppr_format::{ReflectorSet, ValidatedSet};
use ppr_runtime::{Camera, FrameInputs, ReflectionRenderer, RendererDesc};
use ppr_testbed::encoder_timer::EncoderTimer;
use ppr_testbed::gbuffer_targets::Target;
use ppr_testbed::technique::REFLECTION_FORMAT;
use ppr_testbed::{Level, LevelRenderer, ReflectionInputs};

use crate::frame_loop::CacheFlush;
use crate::stats::Summary;

/// Half the distance between the eyes, metres.
const HALF_IPD: f64 = 0.032;

/// One scene, camera and per-eye size.
#[derive(Clone, Debug, PartialEq)]
pub struct StereoRow {
    pub scene: String,
    pub camera: String,
    /// Per eye.
    pub size: [u32; 2],
    /// Median ms of a stereo frame (both eyes).
    pub stereo_ms: f64,
    /// Median ms of the two mono frames.
    pub mono_pair_ms: f64,
    pub frames: usize,
}

/// The two eyes of `head`: offset along its right vector.
pub fn eyes(head: &Camera) -> [Camera; 2] {
    let right = (head.rotation * Vec3::X).as_dvec3();
    [-HALF_IPD, HALF_IPD].map(|d| Camera { position: head.position + right * d, ..*head })
}

/// Times both ways on one scene and camera; `None` without encoder timestamps.
#[allow(clippy::too_many_arguments)] // one probe's inputs, each used once
pub fn run_stereo_probe(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    (scene, level, reflectors): (&str, &Level, &ReflectorSet),
    (camera_name, head): (&str, &Camera),
    size: [u32; 2],
    reps: usize,
    flush: &CacheFlush,
) -> Option<StereoRow> {
    let timer = EncoderTimer::new(device, queue)?;
    let set = ValidatedSet::new(reflectors.clone()).ok()?;
    let eyes = eyes(head);
    // Each eye's scene, drawn once.
    let levels: Vec<LevelRenderer> = eyes
        .iter()
        .map(|eye| {
            let mut l = LevelRenderer::new(device, queue, level, reflectors);
            l.prepare(device, queue, eye, size);
            let mut encoder = device.create_command_encoder(&Default::default());
            l.encode_gbuffer(&mut encoder);
            queue.submit([encoder.finish()]);
            l
        })
        .collect();
    let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
    let outputs: Vec<Target> =
        (0..2).map(|_| Target::new(device, "stereo output", size, REFLECTION_FORMAT, usage)).collect();
    let inputs: Vec<ReflectionInputs> = levels
        .iter()
        .zip(&outputs)
        .map(|(l, o)| ReflectionInputs::from_gbuffer(l.gbuffer(), &o.view))
        .collect();
    let frame = |k: usize| FrameInputs::new(inputs[k].color, inputs[k].depth, inputs[k].output);
    let mut ppr = ReflectionRenderer::new(device, queue, &RendererDesc { timestamps: false });
    ppr.set_reflectors(&set);

    let mut time = |stereo: bool| -> Vec<f64> {
        let mut ms = Vec::new();
        for rep in 0..reps + 5 {
            let mut encoder = device.create_command_encoder(&Default::default());
            flush.encode(&mut encoder);
            timer.begin(&mut encoder);
            if stereo {
                ppr.prepare_stereo([&eyes[0], &eyes[1]], size);
                ppr.encode_stereo(&mut encoder, [&frame(0), &frame(1)]);
            } else {
                for (k, eye) in eyes.iter().enumerate() {
                    ppr.prepare(eye, size);
                    ppr.encode(&mut encoder, &frame(k));
                }
            }
            timer.end(&mut encoder);
            queue.submit([encoder.finish()]);
            // The first five are warm-up.
            if let Some(t) = timer.read_ms(device).filter(|_| rep >= 5) {
                ms.push(t);
            }
        }
        ms
    };
    let mono = time(false);
    let stereo = time(true);
    Some(StereoRow {
        scene: scene.to_owned(),
        camera: camera_name.to_owned(),
        size,
        stereo_ms: Summary::of(&stereo)?.median,
        mono_pair_ms: Summary::of(&mono)?.median,
        frames: stereo.len().min(mono.len()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn the_eyes_are_64_mm_apart_across_the_view() {
        let head = Camera::look_at(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), Vec3::Y, Default::default());
        let [l, r] = eyes(&head);
        assert!((r.position - l.position - DVec3::new(0.064, 0.0, 0.0)).length() < 1e-9, "{l:?} {r:?}");
        assert_eq!(l.rotation, head.rotation);
    }
}
