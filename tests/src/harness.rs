//! Runs the runtime on a CPU-made frame: uploads colour and depth, encodes, reads back.

use glam::{Vec3, Vec4};
use ppr_runtime::{Camera, FrameInputs, FramePlan, ReflectionRenderer, RendererDesc};

use crate::gpu::{gpu, read_buffer};
use crate::scene::Frame;

/// What one run of the runtime produced.
pub struct Output {
    pub plan: std::sync::Arc<FramePlan>,
    /// Reflection colour + confidence alpha per pixel (0: no reflection found).
    pub pixels: Vec<Vec4>,
    /// The intermediate buffer after the projection pass.
    pub intermediate: Vec<u32>,
    /// The layer output (glass and water reflections), colour + confidence alpha.
    pub layer_pixels: Vec<Vec4>,
}

impl Output {
    /// Asserts that `other` holds this run's frame bit for bit: intermediate buffer, output
    /// and layer output (`what` names the frame in the message).
    pub fn assert_same_frame(&self, other: &Output, what: &str) {
        let bits = |p: &[Vec4]| p.iter().flat_map(|v| v.to_array().map(f32::to_bits)).collect::<Vec<_>>();
        assert!(self.intermediate == other.intermediate, "{what}: intermediate buffer");
        assert!(bits(&self.pixels) == bits(&other.pixels), "{what}: output");
        assert!(bits(&self.layer_pixels) == bits(&other.layer_pixels), "{what}: layer output");
    }
}

/// GPU textures of a CPU frame.
pub struct GpuFrame {
    pub color: wgpu::Texture,
    pub depth: wgpu::Texture,
    pub output: wgpu::Texture,
    /// Reflections of glass and water layers.
    pub layer_output: wgpu::Texture,
    /// Shading normals; `None` to run without them.
    pub normals: Option<wgpu::Texture>,
    pub size: [u32; 2],
}

const DEPTH_WRITE: &str = r#"
@group(0) @binding(0) var depth_in: texture_2d<f32>;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) pos: vec4<f32>) -> @builtin(frag_depth) f32 {
    return textureLoad(depth_in, vec2<i32>(pos.xy), 0).r;
}
"#;

impl GpuFrame {
    /// Uploads colour as `Rgba16Float` and depth as `Depth32Float` (drawn with `frag_depth`).
    pub fn upload(frame: &Frame) -> Self {
        Self::upload_with(frame, false)
    }

    /// Like [`Self::upload`], but the depth the runtime reads is the raw `R32Float`
    /// texture, so that values a depth buffer cannot hold (NaN, infinities, outside
    /// [0, 1]) reach the passes.
    pub fn upload_raw_depth(frame: &Frame) -> Self {
        Self::upload_with(frame, true)
    }

    fn upload_with(frame: &Frame, raw_depth: bool) -> Self {
        let g = gpu();
        let d = &g.device;
        let [w, h] = frame.size;
        let extent = wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 };
        let texture = |label, format, usage, data: Option<&[u8]>, bpp: u32| {
            let desc = wgpu::TextureDescriptor {
                label: Some(label),
                size: extent,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            };
            match data {
                Some(bytes) => {
                    let t = d.create_texture(&desc);
                    g.queue.write_texture(
                        t.as_image_copy(),
                        bytes,
                        wgpu::TexelCopyBufferLayout {
                            offset: 0,
                            bytes_per_row: Some(w * bpp),
                            rows_per_image: None,
                        },
                        extent,
                    );
                    t
                }
                None => d.create_texture(&desc),
            }
        };
        let color_f16: Vec<half::f16> =
            frame.color.iter().flat_map(|c| [c.x, c.y, c.z, 1.0]).map(half::f16::from_f32).collect();
        let color = texture(
            "test colour",
            wgpu::TextureFormat::Rgba16Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            Some(bytemuck::cast_slice(&color_f16)),
            8,
        );
        let depth_src = texture(
            "test depth source",
            wgpu::TextureFormat::R32Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            Some(bytemuck::cast_slice(&frame.depth)),
            4,
        );
        let depth = texture(
            "test depth",
            wgpu::TextureFormat::Depth32Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
            None,
            4,
        );
        let output = texture(
            "test output",
            ppr_runtime::OUTPUT_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
            None,
            8,
        );
        let layer_output = texture(
            "test layer output",
            ppr_runtime::OUTPUT_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
            None,
            8,
        );
        let normals_f16: Vec<half::f16> =
            frame.normals.iter().flat_map(|n| [n.x, n.y, n.z, 0.0]).map(half::f16::from_f32).collect();
        let normals = Some(texture(
            "test normals",
            wgpu::TextureFormat::Rgba16Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            Some(bytemuck::cast_slice(&normals_f16)),
            8,
        ));
        if raw_depth {
            return Self { color, depth: depth_src, output, layer_output, normals, size: frame.size };
        }
        write_depth(&depth_src, &depth);
        Self { color, depth, output, layer_output, normals, size: frame.size }
    }
}

/// Copies an R32Float texture into a Depth32Float one by drawing `frag_depth`.
fn write_depth(src: &wgpu::Texture, dst: &wgpu::Texture) {
    let g = gpu();
    let d = &g.device;
    let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("test depth write"),
        source: wgpu::ShaderSource::Wgsl(DEPTH_WRITE.into()),
    });
    let pipeline = d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("test depth write"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Always),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &[],
        }),
        multiview_mask: None,
        cache: None,
    });
    let view = src.create_view(&Default::default());
    let bg = d.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&view) }],
    });
    let dst_view = dst.create_view(&Default::default());
    let mut encoder = d.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("test depth write"),
            color_attachments: &[],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &dst_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bg, &[]);
        pass.draw(0..3, 0..1);
    }
    g.queue.submit([encoder.finish()]);
}

/// Runs the renderer once on an uploaded frame and reads everything back. The outputs are
/// zeroed first, so that what an earlier run wrote cannot pass for this run's result
/// (indirect dispatch leaves pixels outside the active tiles untouched).
pub fn run(renderer: &mut ReflectionRenderer, frame: &GpuFrame, camera: &Camera) -> Output {
    let g = gpu();
    let zeros = vec![0u8; (frame.size[0] * frame.size[1] * 8) as usize];
    for t in [&frame.output, &frame.layer_output] {
        g.queue.write_texture(
            t.as_image_copy(),
            &zeros,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(frame.size[0] * 8),
                rows_per_image: None,
            },
            t.size(),
        );
    }
    let plan = renderer.prepare(camera, frame.size);
    let color = frame.color.create_view(&Default::default());
    let aspect = if frame.depth.format().has_depth_aspect() {
        wgpu::TextureAspect::DepthOnly
    } else {
        wgpu::TextureAspect::All
    };
    let depth = frame.depth.create_view(&wgpu::TextureViewDescriptor { aspect, ..Default::default() });
    let output = frame.output.create_view(&Default::default());
    let mut encoder = g.device.create_command_encoder(&Default::default());
    let layer_output = frame.layer_output.create_view(&Default::default());
    let normals = frame.normals.as_ref().map(|t| t.create_view(&Default::default()));
    renderer.encode(
        &mut encoder,
        &FrameInputs {
            layer_output: Some(&layer_output),
            normals: normals.as_ref(),
            ..FrameInputs::new(&color, &depth, &output)
        },
    );
    g.queue.submit([encoder.finish()]);
    let pixels = read_rgba16f(&frame.output);
    let layer_pixels = read_rgba16f(&frame.layer_output);
    let intermediate = renderer
        .intermediate_buffer()
        .map(|b| bytemuck::pod_collect_to_vec(&read_buffer(b)))
        .unwrap_or_default();
    Output { plan, pixels, intermediate, layer_pixels }
}

/// `set`, validated (panics naming the broken field when it is not).
pub fn validated(set: &ppr_format::ReflectorSet) -> ppr_format::ValidatedSet {
    ppr_format::ValidatedSet::new(set.clone()).unwrap_or_else(|e| panic!("a valid set: {e}"))
}

/// A renderer on the test device.
pub fn renderer() -> ReflectionRenderer {
    let g = gpu();
    ReflectionRenderer::new(&g.device, &g.queue, &RendererDesc::default())
}

/// Reads an `Rgba16Float` texture.
pub fn read_rgba16f(texture: &wgpu::Texture) -> Vec<Vec4> {
    let g = gpu();
    let (w, h) = (texture.width(), texture.height());
    let row = (w * 8).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let buffer = g.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("test texture readback"),
        size: u64::from(row * h),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let mut encoder = g.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: None },
        },
        wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
    );
    g.queue.submit([encoder.finish()]);
    let bytes = read_buffer(&buffer);
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        let line: &[half::f16] = bytemuck::cast_slice(&bytes[(y * row) as usize..(y * row + w * 8) as usize]);
        out.extend(
            line.chunks_exact(4).map(|c| Vec4::new(c[0].into(), c[1].into(), c[2].into(), c[3].into())),
        );
    }
    out
}

/// Error statistics of the runtime's output against the exact reflection over a mask.
#[derive(Debug, Clone, Copy)]
pub struct Comparison {
    pub pixels: usize,
    /// Mask pixels the runtime left without data (alpha 0).
    pub empty: usize,
    /// PSNR in dB over mask pixels (peak 1.0; empty pixels count as black).
    pub psnr: f64,
    /// Mean absolute error per channel.
    pub mean_abs: f64,
    /// Mask pixels whose colour is off by more than 0.25 in some channel (a wrong surface).
    pub wrong: usize,
}

pub fn compare(frame: &Frame, out: &[Vec4], mask: impl Fn(usize) -> bool) -> Comparison {
    let (mut n, mut empty, mut se, mut ae, mut wrong) = (0usize, 0usize, 0f64, 0f64, 0usize);
    for (i, o) in out.iter().enumerate() {
        if !mask(i) {
            continue;
        }
        n += 1;
        if o.w <= 0.0 {
            empty += 1;
        }
        let d: Vec3 =
            o.truncate().clamp(Vec3::ZERO, Vec3::ONE) - frame.reference[i].clamp(Vec3::ZERO, Vec3::ONE);
        wrong += usize::from(d.abs().max_element() > 0.25);
        se += f64::from(d.length_squared()) / 3.0;
        ae += f64::from(d.abs().element_sum()) / 3.0;
    }
    let mse = se / n.max(1) as f64;
    Comparison {
        pixels: n,
        empty,
        psnr: 10.0 * (1.0 / mse.max(1e-12)).log10(),
        mean_abs: ae / n.max(1) as f64,
        wrong,
    }
}

/// Writes `dir/ppr/name.png`: the runtime's output, the exact reflection and their
/// difference ×4 (blue: not compared), side by side. Tests pass their
/// `env!("CARGO_TARGET_TMPDIR")`.
pub fn save_comparison(dir: &str, name: &str, frame: &Frame, out: &[Vec4], mask: impl Fn(usize) -> bool) {
    let ppr: Vec<Vec3> = out.iter().map(|p| p.truncate()).collect();
    let reference: Vec<Vec3> = (0..ppr.len())
        .map(|i| if frame.mirror[i].is_some() { frame.reference[i] } else { Vec3::ZERO })
        .collect();
    let diff: Vec<Vec3> = (0..ppr.len())
        .map(|i| {
            if mask(i) {
                ((ppr[i] - reference[i]).abs() * 4.0).min(Vec3::ONE)
            } else {
                Vec3::new(0.0, 0.0, 0.3)
            }
        })
        .collect();
    let dir = std::path::Path::new(dir).join("ppr");
    std::fs::create_dir_all(&dir).expect("create test output folder");
    save_png(&dir.join(format!("{name}.png")), frame.size, &[ppr, reference, diff]);
}

/// Writes linear RGB images side by side as an sRGB PNG.
pub fn save_png(path: &std::path::Path, size: [u32; 2], images: &[Vec<Vec3>]) {
    let [w, h] = size;
    let mut img = image::RgbImage::new(w * images.len() as u32, h);
    for (k, im) in images.iter().enumerate() {
        for (i, c) in im.iter().enumerate() {
            let (x, y) = (i as u32 % w, i as u32 / w);
            let srgb =
                c.clamp(Vec3::ZERO, Vec3::ONE).to_array().map(|v| (v.powf(1.0 / 2.2) * 255.0).round() as u8);
            img.put_pixel(k as u32 * w + x, y, image::Rgb(srgb));
        }
    }
    img.save(path).expect("write debug png");
}

/// CPU reference of the projection pass (occluder lists and depth occlusion included): the
/// intermediate buffer it writes.
pub fn cpu_projection(frame: &Frame, camera: &Camera, set: &ppr_format::ReflectorSet) -> Vec<u32> {
    let [w, h] = frame.size;
    let layout = ppr_runtime::EncodingLayout::for_resolution(w, h);
    let clip_from_rel = camera.clip_from_relative(w as f32 / h as f32).as_dmat4();
    let rel_from_clip = clip_from_rel.inverse();
    let mut buf = vec![ppr_runtime::CLEAR_VALUE; (w * h) as usize];
    let far = f64::from(camera.projection.far_depth());
    // Each shape's path blocker (`PlanParams::path_blockers`, on by default).
    let blockers = ppr_runtime::shapes::ShapeTable::from_set(set).path_blockers;
    // `ppr_unproject_homogeneous` of view.wgsl: the pixel centre's homogeneous point.
    let homogeneous = |x: u32, y: u32, d: f64| {
        let ndc = glam::DVec4::new(
            (x as f64 + 0.5) / w as f64 * 2.0 - 1.0,
            1.0 - (y as f64 + 0.5) / h as f64 * 2.0,
            d,
            1.0,
        );
        rel_from_clip * ndc
    };
    let unproject = |x: u32, y: u32, d: f64| {
        let hp = homogeneous(x, y, d);
        hp.truncate() / hp.w
    };
    // `ppr_on_plane_tolerance` of view.wgsl: the f32 unprojection error or four depth ulps
    // along the view ray (the unprojection's derivative in depth times them), whichever is
    // larger.
    let on_plane_tolerance = |x: u32, y: u32, d: f64, p: glam::DVec3| {
        let ulps = 4.0 * f64::from(f32::EPSILON) * d.abs().max(1e-30);
        let hw = homogeneous(x, y, d).w;
        let c = rel_from_clip.z_axis;
        let along = (c.truncate() - p * c.w).length() * ulps / hw.abs();
        (f64::from(ppr_runtime::renderer::PLANE_EPSILON) * p.length()).max(if along.is_finite() {
            along
        } else {
            0.0
        })
    };
    for y in 0..h {
        for x in 0..w {
            let d = f64::from(frame.depth[(y * w + x) as usize]);
            if d == far {
                continue;
            }
            let p = unproject(x, y, d);
            let tolerance = on_plane_tolerance(x, y, d, p);
            for (r, &blocker) in set.reflectors.iter().zip(&blockers) {
                let c = r.center - camera.position;
                let pd = c.dot(r.normal);
                // The plan culls shapes whose reflecting side faces away from the camera.
                if pd >= 0.0 {
                    continue;
                }
                let dist = p.dot(r.normal) - pd;
                if dist <= tolerance {
                    continue;
                }
                let m = p - 2.0 * dist * r.normal;
                let hit = m * (pd / m.dot(r.normal));
                let l = hit - c;
                if l.dot(r.axis_u).abs() > r.half_extents.x || l.dot(r.axis_v).abs() > r.half_extents.y {
                    continue;
                }
                // Occluder lists: not where one of the shape's occluders (not glass) crosses
                // the ray from the camera to the reflection point strictly before it.
                let occluded = r.occluders.iter().any(|&o| {
                    let o = &set.reflectors[o as usize];
                    if !o.enabled || o.kind == ppr_format::ReflectorKind::Transparent {
                        return false;
                    }
                    let (on, oc) = (o.normal, o.center - camera.position);
                    let t = oc.dot(on) / hit.dot(on);
                    let l = hit * t - oc;
                    t > 0.0
                        && t < 0.9999
                        && l.dot(o.axis_u).abs() <= o.half_extents.x
                        && l.dot(o.axis_v).abs() <= o.half_extents.y
                });
                if occluded {
                    continue;
                }
                // Path blockers: not where the path from `p` down to the reflection point
                // crosses the shape's blocker (a parallel reflector in front of it) inside.
                if let Some(b) = set.reflectors.get(blocker as usize) {
                    let rise = (b.center - camera.position).dot(r.normal) - pd;
                    let x = hit + (p - hit) * (rise / dist);
                    let l = x - (b.center - camera.position);
                    if rise > 0.0
                        && rise < dist
                        && l.dot(b.axis_u).abs() < b.half_extents.x
                        && l.dot(b.axis_v).abs() < b.half_extents.y
                    {
                        continue;
                    }
                }
                let cl = clip_from_rel * m.extend(1.0);
                if cl.w <= 0.0 {
                    continue;
                }
                let n = cl.truncate().truncate() / cl.w;
                if n.x.abs() >= 1.0 || n.y.abs() >= 1.0 {
                    continue;
                }
                let t = (n * glam::DVec2::new(0.5, -0.5) + 0.5) * glam::DVec2::new(w as f64, h as f64);
                let px = glam::UVec2::new((t.x as u32).min(w - 1), (t.y as u32).min(h - 1));
                let whole = px.as_ivec2() - glam::IVec2::new(x as i32, y as i32);
                let fract = (t - px.as_dvec2() - 0.5).as_vec2();
                let v = ppr_runtime::encoding::encode_parts(whole, fract, &layout);
                let i = px.y * w + px.x;
                // Depth occlusion: not where the surface seen at the target lies in front of
                // the plane.
                let td = f64::from(frame.depth[i as usize]);
                if td != far {
                    let q = unproject(px.x, px.y, td);
                    if q.dot(r.normal) - pd > on_plane_tolerance(px.x, px.y, td, q) {
                        continue;
                    }
                }
                buf[i as usize] = buf[i as usize].min(v);
            }
        }
    }
    buf
}
