//! The floor of a full-screen image write, measured: an `Rgba16Float` image written by
//! compute (storage texture, several thread layouts), by a fragment pass and as a packed
//! storage buffer, so the reflection and upsample passes' write is compared with what the
//! device does with the same bytes.

use crate::stats::Summary;
use crate::timing::read_u64s;

/// One way of writing the image, and its median GPU time.
#[derive(Clone, Debug, PartialEq)]
pub struct WriteProbeRow {
    pub variant: &'static str,
    /// Bytes written.
    pub bytes: u64,
    pub median_ms: f64,
}

/// How a variant writes.
#[derive(Clone, Copy)]
enum Writer {
    /// Compute `textureStore`, workgroup `wg`, `per` × `per` pixels per thread.
    Compute { wg: [u32; 2], per: u32, format: wgpu::TextureFormat, render_usage: bool },
    /// Compute, one pixel per thread, into a storage buffer of packed halves (8 B/px).
    Buffer,
    /// A full-screen triangle into a colour attachment.
    Fragment,
    /// As the reflection pass finding no data: `reads` neighbours of an intermediate-like
    /// `u32` buffer (all empty), then the `Rgba16Float` store; `per` × `per` px/thread.
    ReadWrite { per: u32, reads: u32 },
}

const VARIANTS: [(&str, Writer); 12] = [
    (
        "compute 16x16, rgba16float",
        Writer::Compute { wg: [16, 16], per: 1, format: F16, render_usage: false },
    ),
    ("compute 8x8, rgba16float", Writer::Compute { wg: [8, 8], per: 1, format: F16, render_usage: false }),
    ("compute 32x8, rgba16float", Writer::Compute { wg: [32, 8], per: 1, format: F16, render_usage: false }),
    (
        "compute 16x16, 2x2 px/thread",
        Writer::Compute { wg: [16, 16], per: 2, format: F16, render_usage: false },
    ),
    (
        "compute 16x16, rgba16float + render usage",
        Writer::Compute { wg: [16, 16], per: 1, format: F16, render_usage: true },
    ),
    (
        "compute 16x16, rgba8unorm",
        Writer::Compute {
            wg: [16, 16],
            per: 1,
            format: wgpu::TextureFormat::Rgba8Unorm,
            render_usage: false,
        },
    ),
    (
        "compute 16x16, r32uint",
        Writer::Compute { wg: [16, 16], per: 1, format: wgpu::TextureFormat::R32Uint, render_usage: false },
    ),
    ("compute 256, storage buffer 8 B/px", Writer::Buffer),
    ("fragment, full-screen triangle", Writer::Fragment),
    ("compute 16x16, 5 u32 reads + store", Writer::ReadWrite { per: 1, reads: 5 }),
    ("compute 16x16, 9 u32 reads + store", Writer::ReadWrite { per: 1, reads: 9 }),
    ("compute 16x16, 2x2 px/thread, 5 reads + store", Writer::ReadWrite { per: 2, reads: 5 }),
];

/// Records one timed pass of a variant.
type RecordPass = dyn Fn(&mut wgpu::CommandEncoder, wgpu::ComputePassTimestampWrites);

const F16: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

fn compute_wgsl(wg: [u32; 2], per: u32, format: wgpu::TextureFormat) -> String {
    let (fmt, value) = match format {
        wgpu::TextureFormat::R32Uint => ("r32uint", "vec4<u32>(p.x ^ p.y, 0u, 0u, 0u)"),
        wgpu::TextureFormat::Rgba8Unorm => {
            ("rgba8unorm", "vec4<f32>(vec2<f32>(p & vec2<u32>(255u)) / 255.0, 0.5, 1.0)")
        }
        _ => ("rgba16float", "vec4<f32>(vec2<f32>(p) * 1e-3, 0.5, 1.0)"),
    };
    format!(
        "@group(0) @binding(0) var out: texture_storage_2d<{fmt}, write>;
@compute @workgroup_size({x}, {y})
fn main(@builtin(local_invocation_id) l: vec3<u32>, @builtin(workgroup_id) w: vec3<u32>) {{
    let size = textureDimensions(out);
    let base = w.xy * vec2<u32>({x}u, {y}u) * {per}u + l.xy;
    for (var j = 0u; j < {per}u * {per}u; j++) {{
        let p = base + vec2<u32>(j % {per}u, j / {per}u) * vec2<u32>({x}u, {y}u);
        if (all(p < size)) {{
            textureStore(out, p, {value});
        }}
    }}
}}",
        x = wg[0],
        y = wg[1],
    )
}

fn read_write_wgsl(per: u32, reads: u32) -> String {
    format!(
        "@group(0) @binding(0) var out: texture_storage_2d<rgba16float, write>;
@group(0) @binding(1) var<storage, read> values: array<u32>;
const OFFSETS = array<vec2<i32>, 9>(vec2<i32>(0, 0), vec2<i32>(1, 0), vec2<i32>(0, 1), vec2<i32>(-1, 0),
    vec2<i32>(0, -1), vec2<i32>(2, 0), vec2<i32>(0, 2), vec2<i32>(-2, 0), vec2<i32>(0, -2));
@compute @workgroup_size(16, 16)
fn main(@builtin(local_invocation_id) l: vec3<u32>, @builtin(workgroup_id) w: vec3<u32>) {{
    let size = vec2<i32>(textureDimensions(out));
    let base = vec2<i32>(w.xy * 16u * {per}u + l.xy);
    for (var j = 0; j < {per} * {per}; j++) {{
        let p = base + vec2<i32>(j % {per}, j / {per}) * 16;
        if (any(p >= size)) {{
            continue;
        }}
        var best = 0xffffffffu;
        for (var k = 0; k < {reads}; k++) {{
            let q = clamp(p + OFFSETS[k], vec2<i32>(0), size - 1);
            best = min(best, values[u32(q.x + q.y * size.x)]);
        }}
        textureStore(out, p, vec4<f32>(f32(best & 1u), 0.0, 0.0, 0.0));
    }}
}}"
    )
}

const BUFFER_WGSL: &str = "
struct Size { w: u32, h: u32 }
@group(0) @binding(0) var<storage, read_write> out: array<vec2<u32>>;
@group(0) @binding(1) var<uniform> size: Size;
@compute @workgroup_size(256)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) n: vec3<u32>) {
    let i = id.x + id.y * n.x * 256u;
    if (i < size.w * size.h) {
        let p = vec2<f32>(f32(i % size.w), f32(i / size.w));
        out[i] = vec2<u32>(pack2x16float(p * 1e-3), pack2x16float(vec2<f32>(0.5, 1.0)));
    }
}";

const FRAGMENT_WGSL: &str = "
@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}
@fragment
fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(p.xy * 1e-3, 0.5, 1.0);
}";

/// Times each way of writing a `size` image `reps` times (after two warm-up frames) with
/// pass timestamps; empty without timestamp queries.
pub fn run_write_probe(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    size: [u32; 2],
    reps: usize,
) -> Vec<WriteProbeRow> {
    if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
        return Vec::new();
    }
    let query_set = device.create_query_set(&wgpu::QuerySetDescriptor {
        label: Some("write probe timestamps"),
        ty: wgpu::QueryType::Timestamp,
        count: 2,
    });
    let buffer = |label: &str, size: u64, usage| {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage,
            mapped_at_creation: false,
        })
    };
    let resolve =
        buffer("write probe resolve", 16, wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC);
    let readback =
        buffer("write probe readback", 16, wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST);
    let period = f64::from(queue.get_timestamp_period());
    let pixels = u64::from(size[0]) * u64::from(size[1]);
    let texture = |format: wgpu::TextureFormat, usage| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some("write probe target"),
            size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    };
    let mut rows = Vec::new();
    for (variant, writer) in VARIANTS {
        let record: Box<RecordPass>;
        let bytes;
        match writer {
            Writer::Compute { wg, per, format, render_usage } => {
                let mut usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
                if render_usage {
                    usage |= wgpu::TextureUsages::RENDER_ATTACHMENT;
                }
                let view = texture(format, usage).create_view(&Default::default());
                bytes = pixels * u64::from(format.block_copy_size(None).unwrap_or(8));
                let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(variant),
                    source: wgpu::ShaderSource::Wgsl(compute_wgsl(wg, per, format).into()),
                });
                let pipeline = compute_pipeline(device, &module, variant);
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(variant),
                    layout: &pipeline.get_bind_group_layout(0),
                    entries: &[wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(&view),
                    }],
                });
                let groups = [size[0].div_ceil(wg[0] * per), size[1].div_ceil(wg[1] * per)];
                record = Box::new(move |encoder, writes| {
                    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                        label: Some(variant),
                        timestamp_writes: Some(writes),
                    });
                    pass.set_pipeline(&pipeline);
                    pass.set_bind_group(0, &bind_group, &[]);
                    pass.dispatch_workgroups(groups[0], groups[1], 1);
                });
            }
            Writer::Buffer => {
                bytes = pixels * 8;
                let out = buffer("write probe buffer", bytes, wgpu::BufferUsages::STORAGE);
                let uniform =
                    buffer("write probe size", 8, wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST);
                queue.write_buffer(&uniform, 0, bytemuck::cast_slice(&size));
                let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(variant),
                    source: wgpu::ShaderSource::Wgsl(BUFFER_WGSL.into()),
                });
                let pipeline = compute_pipeline(device, &module, variant);
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(variant),
                    layout: &pipeline.get_bind_group_layout(0),
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: out.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 1, resource: uniform.as_entire_binding() },
                    ],
                });
                let groups = pixels.div_ceil(256) as u32;
                let x = groups.min(65535);
                record = Box::new(move |encoder, writes| {
                    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                        label: Some(variant),
                        timestamp_writes: Some(writes),
                    });
                    pass.set_pipeline(&pipeline);
                    pass.set_bind_group(0, &bind_group, &[]);
                    pass.dispatch_workgroups(x, groups.div_ceil(x), 1);
                });
            }
            Writer::ReadWrite { per, reads } => {
                bytes = pixels * (8 + 4);
                let view =
                    texture(F16, wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING)
                        .create_view(&Default::default());
                let values = buffer(
                    "write probe values",
                    pixels * 4,
                    wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                );
                let mut encoder =
                    device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(variant) });
                encoder.clear_buffer(&values, 0, None);
                queue.submit([encoder.finish()]);
                let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(variant),
                    source: wgpu::ShaderSource::Wgsl(read_write_wgsl(per, reads).into()),
                });
                let pipeline = compute_pipeline(device, &module, variant);
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(variant),
                    layout: &pipeline.get_bind_group_layout(0),
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: wgpu::BindingResource::TextureView(&view),
                        },
                        wgpu::BindGroupEntry { binding: 1, resource: values.as_entire_binding() },
                    ],
                });
                let groups = [size[0].div_ceil(16 * per), size[1].div_ceil(16 * per)];
                record = Box::new(move |encoder, writes| {
                    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                        label: Some(variant),
                        timestamp_writes: Some(writes),
                    });
                    pass.set_pipeline(&pipeline);
                    pass.set_bind_group(0, &bind_group, &[]);
                    pass.dispatch_workgroups(groups[0], groups[1], 1);
                });
            }
            Writer::Fragment => {
                bytes = pixels * 8;
                let view = texture(
                    F16,
                    wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
                )
                .create_view(&Default::default());
                let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(variant),
                    source: wgpu::ShaderSource::Wgsl(FRAGMENT_WGSL.into()),
                });
                let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some(variant),
                    layout: None,
                    vertex: wgpu::VertexState {
                        module: &module,
                        entry_point: Some("vs"),
                        compilation_options: Default::default(),
                        buffers: &[],
                    },
                    primitive: wgpu::PrimitiveState::default(),
                    depth_stencil: None,
                    multisample: wgpu::MultisampleState::default(),
                    fragment: Some(wgpu::FragmentState {
                        module: &module,
                        entry_point: Some("fs"),
                        compilation_options: Default::default(),
                        targets: &[Some(F16.into())],
                    }),
                    multiview_mask: None,
                    cache: None,
                });
                record = Box::new(move |encoder, writes| {
                    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                        label: Some(variant),
                        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                            view: &view,
                            depth_slice: None,
                            resolve_target: None,
                            ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
                        })],
                        depth_stencil_attachment: None,
                        timestamp_writes: Some(wgpu::RenderPassTimestampWrites {
                            query_set: writes.query_set,
                            beginning_of_pass_write_index: writes.beginning_of_pass_write_index,
                            end_of_pass_write_index: writes.end_of_pass_write_index,
                        }),
                        occlusion_query_set: None,
                        multiview_mask: None,
                    });
                    pass.set_pipeline(&pipeline);
                    pass.draw(0..3, 0..1);
                });
            }
        }
        let mut samples = Vec::new();
        for rep in 0..reps + 2 {
            let mut encoder =
                device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("write probe") });
            record(
                &mut encoder,
                wgpu::ComputePassTimestampWrites {
                    query_set: &query_set,
                    beginning_of_pass_write_index: Some(0),
                    end_of_pass_write_index: Some(1),
                },
            );
            encoder.resolve_query_set(&query_set, 0..2, &resolve, 0);
            encoder.copy_buffer_to_buffer(&resolve, 0, &readback, 0, 16);
            queue.submit([encoder.finish()]);
            let Some(ticks) = read_u64s(device, &readback) else { continue };
            if rep >= 2 && ticks[1] > ticks[0] {
                samples.push((ticks[1] - ticks[0]) as f64 * period * 1e-6);
            }
        }
        if let Some(s) = Summary::of(&samples) {
            rows.push(WriteProbeRow { variant, bytes, median_ms: s.median });
        }
    }
    rows
}

fn compute_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    label: &str,
) -> wgpu::ComputePipeline {
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: None,
        module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    })
}
