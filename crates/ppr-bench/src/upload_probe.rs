//! What a frame's upload costs before its first pass, measured: small copies from a staging
//! buffer (host memory, as `ppr-runtime`'s upload ring) into device buffers, then one
//! compute dispatch that reads them all, between two encoder timestamps. The variants
//! change how many copies there are and how many buffers they land in, so the per-copy
//! cost (each copy's own barrier in wgpu) is told from the fixed one.

use ppr_testbed::encoder_timer::EncoderTimer;

use crate::stats::Summary;

/// Bytes of each part (a few of the runtime's small parts are this size).
const PART_BYTES: u64 = 256;

/// Most buffers a variant reads (wgpu's default limit of storage buffers per stage is 8).
const MAX_PARTS: usize = 8;

/// One way of uploading, and its median GPU time.
#[derive(Clone, Debug, PartialEq)]
pub struct UploadProbeRow {
    pub variant: String,
    /// Copies recorded.
    pub copies: usize,
    pub median_ms: f64,
}

/// How a variant uploads `parts` parts of [`PART_BYTES`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Upload {
    /// No copy: the dispatch alone.
    None,
    /// One copy per part, each into its own buffer (as the runtime's upload).
    CopyEach(usize),
    /// One copy per part into one buffer at the parts' offsets.
    CopyEachIntoOne(usize),
    /// One copy of all the parts into one buffer.
    CopyOnce(usize),
}

impl Upload {
    /// Every variant the probe times.
    pub const ALL: [Self; 8] = [
        Self::None,
        Self::CopyEach(1),
        Self::CopyEach(4),
        Self::CopyEach(8),
        Self::CopyEachIntoOne(4),
        Self::CopyEachIntoOne(8),
        Self::CopyOnce(4),
        Self::CopyOnce(8),
    ];

    /// Parts the dispatch reads.
    pub fn parts(self) -> usize {
        match self {
            Self::None => 1,
            Self::CopyEach(n) | Self::CopyEachIntoOne(n) | Self::CopyOnce(n) => n,
        }
    }

    /// Copies the variant records.
    pub fn copies(self) -> usize {
        match self {
            Self::None => 0,
            Self::CopyEach(n) | Self::CopyEachIntoOne(n) => n,
            Self::CopyOnce(_) => 1,
        }
    }

    /// Buffers the parts land in (and the dispatch binds).
    pub fn buffers(self) -> usize {
        match self {
            Self::CopyEach(n) => n,
            _ => 1,
        }
    }

    pub fn label(self) -> String {
        match self {
            Self::None => "dispatch only".to_owned(),
            Self::CopyEach(1) => "1 copy into 1 buffer".to_owned(),
            Self::CopyEach(n) => format!("{n} copies into {n} buffers"),
            Self::CopyEachIntoOne(n) => format!("{n} copies into 1 buffer"),
            Self::CopyOnce(n) => format!("1 copy of {n} parts"),
        }
    }
}

/// The probe's kernel: reads word 0 of each part (`buffers` bindings, `parts` parts in all)
/// and stores their sum.
fn kernel_wgsl(buffers: usize, parts: usize) -> String {
    let words = PART_BYTES / 4;
    let mut s = String::new();
    for b in 0..buffers {
        s.push_str(&format!("@group(0) @binding({b}) var<storage, read> part{b}: array<u32>;\n"));
    }
    s.push_str(&format!("@group(0) @binding({buffers}) var<storage, read_write> sum: array<u32>;\n"));
    s.push_str("@compute @workgroup_size(64)\nfn main(@builtin(global_invocation_id) id: vec3<u32>) {\n");
    s.push_str("    var total = 0u;\n");
    for p in 0..parts {
        if buffers == 1 {
            s.push_str(&format!("    total += part0[{}u + id.x % {words}u];\n", p as u64 * words));
        } else {
            s.push_str(&format!("    total += part{p}[id.x % {words}u];\n"));
        }
    }
    s.push_str("    sum[id.x] = total;\n}\n");
    s
}

/// Times every [`Upload`] variant `reps` times (after a few untimed runs); empty without
/// encoder timestamps.
pub fn run_upload_probe(device: &wgpu::Device, queue: &wgpu::Queue, reps: usize) -> Vec<UploadProbeRow> {
    let Some(timer) = EncoderTimer::new(device, queue) else {
        return Vec::new();
    };
    let buffer = |label: &str, size: u64, usage| {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage,
            mapped_at_creation: false,
        })
    };
    let all_parts = PART_BYTES * MAX_PARTS as u64;
    // Host memory, as the runtime's staging buffers: written once, copied from every rep.
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("upload probe staging"),
        size: all_parts,
        usage: wgpu::BufferUsages::MAP_WRITE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: true,
    });
    let ones = vec![1u8; all_parts as usize];
    staging.slice(..).get_mapped_range_mut().expect("mapped at creation").copy_from_slice(&ones);
    staging.unmap();
    let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
    let targets: Vec<wgpu::Buffer> =
        (0..MAX_PARTS).map(|i| buffer(&format!("upload probe part {i}"), PART_BYTES, storage)).collect();
    let packed = buffer("upload probe parts", all_parts, storage);
    let sum = buffer("upload probe sum", 64 * 4, wgpu::BufferUsages::STORAGE);
    let mut rows = Vec::new();
    for upload in Upload::ALL {
        let (buffers, parts) = (upload.buffers(), upload.parts());
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("upload probe"),
            source: wgpu::ShaderSource::Wgsl(kernel_wgsl(buffers, parts).into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("upload probe"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let read: Vec<&wgpu::Buffer> =
            if buffers == 1 { vec![&packed] } else { targets.iter().take(buffers).collect() };
        let mut entries: Vec<wgpu::BindGroupEntry<'_>> = read
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry { binding: i as u32, resource: b.as_entire_binding() })
            .collect();
        entries.push(wgpu::BindGroupEntry { binding: buffers as u32, resource: sum.as_entire_binding() });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("upload probe"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let mut times = Vec::with_capacity(reps);
        for rep in 0..reps + 3 {
            let mut encoder = device.create_command_encoder(&Default::default());
            timer.begin(&mut encoder);
            match upload {
                Upload::None => {}
                Upload::CopyEach(n) => {
                    for (i, t) in targets.iter().take(n).enumerate() {
                        encoder.copy_buffer_to_buffer(&staging, i as u64 * PART_BYTES, t, 0, PART_BYTES);
                    }
                }
                Upload::CopyEachIntoOne(n) => {
                    for i in 0..n as u64 {
                        encoder.copy_buffer_to_buffer(
                            &staging,
                            i * PART_BYTES,
                            &packed,
                            i * PART_BYTES,
                            PART_BYTES,
                        );
                    }
                }
                Upload::CopyOnce(n) => {
                    encoder.copy_buffer_to_buffer(&staging, 0, &packed, 0, n as u64 * PART_BYTES);
                }
            }
            {
                let mut pass = encoder.begin_compute_pass(&Default::default());
                pass.set_pipeline(&pipeline);
                pass.set_bind_group(0, &bind_group, &[]);
                pass.dispatch_workgroups(1, 1, 1);
            }
            timer.end(&mut encoder);
            queue.submit([encoder.finish()]);
            if let (Some(ms), true) = (timer.read_ms(device), rep >= 3) {
                times.push(ms);
            }
        }
        if let Some(s) = Summary::of(&times) {
            rows.push(UploadProbeRow {
                variant: upload.label(),
                copies: upload.copies(),
                median_ms: s.median,
            });
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kernel_reads_every_part_and_is_valid_wgsl() {
        for upload in Upload::ALL {
            let source = kernel_wgsl(upload.buffers(), upload.parts());
            let module = naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{upload:?}: {e}"));
            let bindings = module.global_variables.iter().count();
            assert_eq!(bindings, upload.buffers() + 1, "{upload:?}");
            assert_eq!(source.matches("total += ").count(), upload.parts(), "{upload:?}");
        }
        assert_eq!(Upload::CopyOnce(8).copies(), 1);
        assert_eq!(Upload::CopyEachIntoOne(8).copies(), 8);
        assert!(Upload::ALL.iter().all(|u| u.buffers() <= MAX_PARTS && u.parts() <= MAX_PARTS));
    }
}
