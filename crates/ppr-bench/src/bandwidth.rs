//! The memory floor: the device's copy bandwidth, measured with a vec4 copy kernel, and the
//! bytes each PPR pass must move given the frame's plan.

use crate::stats::Summary;
use crate::timing::read_u64s;

/// A measured copy: bytes read plus bytes written over the median time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CopyBandwidth {
    /// Bytes read plus bytes written per copy.
    pub bytes: u64,
    /// Median GPU time of one copy, ms.
    pub median_ms: f64,
}

impl CopyBandwidth {
    /// Bytes per second.
    pub fn bytes_per_second(&self) -> f64 {
        self.bytes as f64 / (self.median_ms * 1e-3)
    }

    /// Time to move `bytes` at this bandwidth, ms.
    pub fn floor_ms(&self, bytes: u64) -> f64 {
        bytes as f64 / self.bytes_per_second() * 1e3
    }
}

const COPY_WGSL: &str = "
@group(0) @binding(0) var<storage, read> src: array<vec4<u32>>;
@group(0) @binding(1) var<storage, read_write> dst: array<vec4<u32>>;
@compute @workgroup_size(256)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = id.x + id.y * groups.x * 256u;
    if (i < arrayLength(&src)) {
        dst[i] = src[i];
    }
}";

/// Times a copy of `buffer_bytes` (vec4 per thread, 256-thread workgroups) `reps` times with
/// GPU timestamps; `None` without timestamp queries.
pub fn measure_copy_bandwidth(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    buffer_bytes: u64,
    reps: usize,
) -> Option<CopyBandwidth> {
    if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
        return None;
    }
    let bytes = buffer_bytes.next_multiple_of(16).min(device.limits().max_storage_buffer_binding_size);
    let bytes = bytes - bytes % 16;
    let buffer = |label: &str| {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    };
    let (src, dst) = (buffer("bandwidth copy source"), buffer("bandwidth copy destination"));
    // Non-zero data: never time on zeros.
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("bandwidth init") });
    encoder.clear_buffer(&src, 0, None);
    queue.submit([encoder.finish()]);
    queue.write_buffer(&src, 0, &[0xA5u8; 4096]);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("bandwidth copy"),
        source: wgpu::ShaderSource::Wgsl(COPY_WGSL.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("bandwidth copy"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("bandwidth copy"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: src.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: dst.as_entire_binding() },
        ],
    });
    let query_set = device.create_query_set(&wgpu::QuerySetDescriptor {
        label: Some("bandwidth timestamps"),
        ty: wgpu::QueryType::Timestamp,
        count: 2,
    });
    let resolve = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("bandwidth resolve"),
        size: 16,
        usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("bandwidth readback"),
        size: 16,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let period = f64::from(queue.get_timestamp_period());
    let groups = (bytes / 16).div_ceil(256) as u32;
    let x = groups.min(65535);
    let mut samples = Vec::new();
    for rep in 0..reps + 2 {
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("bandwidth copy") });
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("bandwidth copy"),
                timestamp_writes: Some(wgpu::ComputePassTimestampWrites {
                    query_set: &query_set,
                    beginning_of_pass_write_index: Some(0),
                    end_of_pass_write_index: Some(1),
                }),
            });
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(x, groups.div_ceil(x), 1);
        }
        encoder.resolve_query_set(&query_set, 0..2, &resolve, 0);
        encoder.copy_buffer_to_buffer(&resolve, 0, &readback, 0, 16);
        queue.submit([encoder.finish()]);
        let ticks = read_u64s(device, &readback)?;
        if rep >= 2 && ticks[1] > ticks[0] {
            samples.push((ticks[1] - ticks[0]) as f64 * period * 1e-6);
        }
    }
    let s = Summary::of(&samples)?;
    Some(CopyBandwidth { bytes: 2 * bytes, median_ms: s.median })
}

/// What one PPR frame touched, as the plan and a read-back of its buffers say.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameFacts {
    /// Viewport pixels.
    pub pixels: u64,
    /// 16×16 tiles of the viewport.
    pub tiles: u64,
    /// Tiles the classification found active (all when indirect dispatch is off).
    pub active_tiles: u64,
    /// Whether the clear and reflection passes ran over the active tiles only.
    pub indirect: bool,
    /// Whether a direct-dispatch frame's buffer was cleared by the frame before's
    /// reflection pass (no clear pass; the reflection pass clears the next frame's instead).
    pub cleared_ahead: bool,
    /// Pixels of the intermediate buffer holding an offset after the projection pass (in
    /// active tiles).
    pub written_pixels: u64,
}

/// Bytes one pass must move (reads + writes).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PassBytes {
    pub pass: &'static str,
    pub bytes: u64,
    /// How the bytes were counted.
    pub rule: &'static str,
}

/// Pixels in `tiles` 16×16 tiles, at most the viewport's.
fn tile_pixels(f: &FrameFacts, tiles: u64) -> u64 {
    (tiles * 256).min(f.pixels)
}

/// The bytes each pass must move at least, given the frame:
/// - classify (indirect only): depth 4 B/px read over the viewport, one tile flag written
///   per tile and one list entry per active tile (4 B each), and the clear of the active
///   tiles, 4 B/px;
/// - clear (direct dispatch only): 4 B/px written over the whole buffer, by the clear pass
///   or, where the frame before cleared this frame's buffer (`cleared_ahead`), by the
///   reflection pass for the next frame;
/// - projection: depth 4 B/px read over the viewport, plus 4 B per written pixel (the
///   `atomicMin` result that must reach memory);
/// - reflection: over the dispatched pixels, the intermediate value 4 B/px read (its
///   neighbours come from the cache) and the output 8 B/px written, plus the colour 8 B per
///   pixel that found data.
pub fn pass_bytes(f: &FrameFacts) -> Vec<PassBytes> {
    let mut out = Vec::new();
    let active = if f.indirect { f.active_tiles } else { f.tiles };
    let dispatched = tile_pixels(f, active);
    if f.indirect {
        // The classification clears the active tiles itself.
        out.push(PassBytes {
            pass: "classify",
            bytes: 4 * f.pixels + 4 * f.tiles + 4 * f.active_tiles + 4 * dispatched,
            rule: "depth 4 B/px + 4 B/tile flag + 4 B/active tile + 4 B/px cleared over active tiles",
        });
    } else if !f.cleared_ahead {
        out.push(PassBytes {
            pass: "clear",
            bytes: 4 * dispatched,
            rule: "4 B/px written over cleared pixels",
        });
    }
    out.push(PassBytes {
        pass: "projection",
        bytes: 4 * f.pixels + 4 * f.written_pixels,
        rule: "depth 4 B/px + 4 B per written pixel",
    });
    let clear_next = !f.indirect && f.cleared_ahead;
    out.push(PassBytes {
        pass: "reflection",
        bytes: (4 + 8 + if clear_next { 4 } else { 0 }) * dispatched + 8 * f.written_pixels.min(dispatched),
        rule: if clear_next {
            "intermediate 4 B/px + output 8 B/px + next frame's clear 4 B/px over dispatched pixels + colour 8 B per pixel with data"
        } else {
            "intermediate 4 B/px + output 8 B/px over dispatched pixels + colour 8 B per pixel with data"
        },
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_of_a_full_screen_4k_frame_match_the_gpu_readme() {
        // 4K, no indirect dispatch, every pixel written: the floor of shared/gpu/README.md
        // (clear 33 MB; projection 33 + 33 MB; reflection 33 + 66 + 66 MB).
        let pixels = 3840 * 2160;
        let f = FrameFacts {
            pixels,
            tiles: 240 * 135,
            active_tiles: 0,
            indirect: false,
            cleared_ahead: false,
            written_pixels: pixels,
        };
        let b = pass_bytes(&f);
        let get = |name: &str| b.iter().find(|p| p.pass == name).expect(name).bytes;
        assert_eq!(get("clear"), 4 * pixels);
        assert_eq!(get("projection"), 8 * pixels);
        assert_eq!(get("reflection"), 20 * pixels);
        let total: u64 = b.iter().map(|p| p.bytes).sum();
        assert_eq!(total, 32 * pixels); // 265 MB
        // At the README's 2.45 TB/s: 0.108 ms.
        let bw =
            CopyBandwidth { bytes: (2 * 512) << 20, median_ms: ((2 * 512u64) << 20) as f64 / 2.45e12 * 1e3 };
        let floor: f64 = b.iter().map(|p| bw.floor_ms(p.bytes)).sum();
        assert!((floor - 0.1083).abs() < 1e-3, "{floor}");
        // Cleared by the frame before: the same bytes, the clear's moved to the reflection.
        let ahead = pass_bytes(&FrameFacts { cleared_ahead: true, ..f });
        assert!(ahead.iter().all(|p| p.pass != "clear"));
        let reflection = ahead.iter().find(|p| p.pass == "reflection").expect("reflection").bytes;
        assert_eq!(reflection, 24 * pixels);
        assert_eq!(ahead.iter().map(|p| p.bytes).sum::<u64>(), total);
    }

    #[test]
    fn indirect_frames_count_only_active_tiles() {
        let f = FrameFacts {
            pixels: 64 * 32,
            tiles: 8,
            active_tiles: 2,
            indirect: true,
            cleared_ahead: false,
            written_pixels: 100,
        };
        let b = pass_bytes(&f);
        let get = |name: &str| b.iter().find(|p| p.pass == name).expect(name).bytes;
        assert_eq!(get("classify"), 4 * 2048 + 4 * 8 + 4 * 2 + 4 * 512);
        assert!(b.iter().all(|p| p.pass != "clear"), "the classification clears the active tiles");
        assert_eq!(get("projection"), 4 * 2048 + 400);
        assert_eq!(get("reflection"), 12 * 512 + 800);
    }
}
