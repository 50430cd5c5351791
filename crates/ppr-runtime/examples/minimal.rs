//! The smallest game that renders pixel-projected reflections: its own wgpu scene (a grey
//! floor before a red wall), a floor reflector built in code, its own view and projection
//! matrices, and the runtime's two calls per frame. `docs/integration.md` quotes it and
//! `tests/minimal_example.rs` runs it, so the quoted code compiles and works.
//!
//! `cargo run -p ppr-runtime --example minimal` renders one 160 × 90 frame on the first
//! adapter wgpu finds and prints how many pixels got a reflection.

use glam::{DVec2, DVec3};
use ppr_format::{Reflector, ReflectorKind, ReflectorSet, ValidatedSet};
use ppr_runtime::{Camera, DepthMode, FrameInputs, OUTPUT_FORMAT, ReflectionRenderer, RendererDesc};
use wgpu::util::DeviceExt;

/// The frame's size in pixels.
pub const SIZE: [u32; 2] = [160, 90];

/// What one frame gave: the reflection output, row by row, as RGBA in `f32`.
pub struct Frame {
    pub pixels: Vec<[f32; 4]>,
}

#[allow(dead_code)] // the test calls `render`, not `main`
fn main() -> Result<(), Box<dyn std::error::Error>> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))?;
    // The runtime's passes bind more storage buffers than WebGPU's defaults allow.
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        required_limits: adapter.limits(),
        ..Default::default()
    }))?;
    let frame = render(&device, &queue)?;
    let reflected = frame.pixels.iter().filter(|p| p[3] > 0.0).count();
    println!("{reflected} of {} pixels show a reflection", frame.pixels.len());
    Ok(())
}

/// Renders the scene and its reflections once and reads the reflection output back.
///
/// # Errors
/// A set that breaks an invariant of the format, or a failed read-back.
pub fn render(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Frame, Box<dyn std::error::Error>> {
    // [integration:begin]
    // Once: the reflectors (here built in code; a game loads `ppr-extract`'s file with
    // `ValidatedSet::load(path)?`). The normal says which side reflects.
    let mut set = ReflectorSet::new("minimal.glb");
    set.reflectors.push(Reflector::new(
        0,
        "floor",
        ReflectorKind::Opaque,
        DVec3::new(0.0, 0.0, -2.0), // centre
        DVec3::Y,                   // the reflecting side: up
        DVec3::X,                   // first in-plane axis
        DVec2::new(4.0, 4.0),       // half extents, metres
    ));
    let set = ValidatedSet::new(set)?;
    let mut ppr = ReflectionRenderer::new(device, queue, &RendererDesc::default());
    ppr.set_reflectors(&set);

    // The game's own matrices: view in f64 (positions stay precise far from the origin).
    let view = glam::dcamera::rh::view::look_at_mat4(
        DVec3::new(0.0, 1.5, 3.0),
        DVec3::new(0.0, 0.5, -2.0),
        DVec3::Y,
    );
    let aspect = SIZE[0] as f32 / SIZE[1] as f32;
    let clip_from_view =
        glam::camera::rh::proj::directx::perspective(60f32.to_radians(), aspect, 0.05, 100.0);
    let camera = Camera::from_matrices(view, clip_from_view, DepthMode::Standard)?;

    // Every frame: the game draws colour and depth with camera-relative positions and
    // `camera.clip_from_relative(aspect)`, which is how the runtime reconstructs them.
    let targets = Targets::new(device);
    let mut encoder = device.create_command_encoder(&Default::default());
    draw_scene(device, &mut encoder, &targets, &camera);

    let plan = ppr.prepare(&camera, SIZE); // CPU: cull, plan, pack this view's upload
    // The passes write only where reflectors may show (nothing for an empty plan, only
    // the active tiles with indirect dispatch): clear the output, or composite only
    // where `plan` says.
    clear(&mut encoder, &targets.output);
    ppr.encode(&mut encoder, &FrameInputs::new(&targets.color, &targets.depth, &targets.output));
    // The game then composites: mix(fallback, output.rgb, output.a) on reflective pixels.
    queue.submit([encoder.finish()]);
    // [integration:end]
    assert_eq!(plan.visible.len(), 1, "the floor is in view");
    Ok(Frame { pixels: read_output(device, queue, &targets.output_texture)? })
}

/// The game's frame textures, with the usages the runtime needs.
struct Targets {
    /// The lit scene, linear HDR; read by the runtime (`TEXTURE_BINDING`).
    color: wgpu::TextureView,
    /// Depth, drawn by the game, read by the runtime as a depth-only view.
    depth: wgpu::TextureView,
    /// The reflection: `STORAGE_BINDING` for the runtime, `RENDER_ATTACHMENT` to clear
    /// it, `COPY_SRC` to read it back (a game: `TEXTURE_BINDING` to composite it).
    output: wgpu::TextureView,
    output_texture: wgpu::Texture,
}

impl Targets {
    fn new(device: &wgpu::Device) -> Self {
        use wgpu::TextureUsages as U;
        let texture = |label, format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width: SIZE[0], height: SIZE[1], depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let color =
            texture("color", wgpu::TextureFormat::Rgba16Float, U::RENDER_ATTACHMENT | U::TEXTURE_BINDING);
        let depth =
            texture("depth", wgpu::TextureFormat::Depth32Float, U::RENDER_ATTACHMENT | U::TEXTURE_BINDING);
        let output =
            texture("ppr output", OUTPUT_FORMAT, U::STORAGE_BINDING | U::RENDER_ATTACHMENT | U::COPY_SRC);
        Self {
            color: color.create_view(&Default::default()),
            depth: depth.create_view(&wgpu::TextureViewDescriptor {
                aspect: wgpu::TextureAspect::DepthOnly,
                ..Default::default()
            }),
            output: output.create_view(&Default::default()),
            output_texture: output,
        }
    }
}

const SCENE_WGSL: &str = r"
@group(0) @binding(0) var<uniform> clip_from_relative: mat4x4<f32>;
struct Out { @builtin(position) position: vec4<f32>, @location(0) colour: vec3<f32> }
@vertex fn vs(@location(0) relative: vec3<f32>, @location(1) colour: vec3<f32>) -> Out {
    return Out(clip_from_relative * vec4(relative, 1.0), colour);
}
@fragment fn fs(in: Out) -> @location(0) vec4<f32> { return vec4(in.colour, 1.0); }
";

/// The game's scene pass: a grey floor and a red wall, unlit.
fn draw_scene(device: &wgpu::Device, encoder: &mut wgpu::CommandEncoder, targets: &Targets, camera: &Camera) {
    let quad = |corners: [DVec3; 4], colour: [f32; 3]| {
        // Camera-relative, subtracted in f64 and rounded once.
        let v = corners.map(|c| {
            let r = camera.relative(c);
            [r.x, r.y, r.z, colour[0], colour[1], colour[2]]
        });
        [v[0], v[1], v[2], v[0], v[2], v[3]]
    };
    let floor = quad(
        [
            DVec3::new(-4.0, 0.0, 2.0),
            DVec3::new(4.0, 0.0, 2.0),
            DVec3::new(4.0, 0.0, -6.0),
            DVec3::new(-4.0, 0.0, -6.0),
        ],
        [0.2, 0.2, 0.2],
    );
    let wall = quad(
        [
            DVec3::new(-4.0, 0.0, -4.0),
            DVec3::new(4.0, 0.0, -4.0),
            DVec3::new(4.0, 3.0, -4.0),
            DVec3::new(-4.0, 3.0, -4.0),
        ],
        [0.9, 0.1, 0.1],
    );
    let vertices: Vec<[f32; 6]> = floor.into_iter().chain(wall).collect();
    let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("scene vertices"),
        contents: bytemuck::cast_slice(&vertices),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let aspect = SIZE[0] as f32 / SIZE[1] as f32;
    let matrix = camera.clip_from_relative(aspect).to_cols_array();
    let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("scene matrix"),
        contents: bytemuck::cast_slice(&matrix),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("scene"),
        source: wgpu::ShaderSource::Wgsl(SCENE_WGSL.into()),
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("scene"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: 24,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3],
            })],
        },
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::TextureFormat::Rgba16Float.into())],
        }),
        primitive: Default::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(camera.projection.depth_compare()),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("scene matrix"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() }],
    });
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("scene"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: &targets.color,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &targets.depth,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(camera.projection.far_depth()),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        ..Default::default()
    });
    pass.set_pipeline(&pipeline);
    pass.set_bind_group(0, &bind_group, &[]);
    pass.set_vertex_buffer(0, vertex_buffer.slice(..));
    pass.draw(0..vertices.len() as u32, 0..1);
}

/// Clears the reflection output to "no reflection" (alpha 0).
fn clear(encoder: &mut wgpu::CommandEncoder, output: &wgpu::TextureView) {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("clear ppr output"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: output,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                store: wgpu::StoreOp::Store,
            },
        })],
        ..Default::default()
    });
}

/// Reads an `Rgba16Float` texture of [`SIZE`] back as `f32` RGBA.
fn read_output(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<[f32; 4]>, Box<dyn std::error::Error>> {
    let row = (SIZE[0] * 8).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read back"),
        size: u64::from(row * SIZE[1]),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: None },
        },
        texture.size(),
    );
    queue.submit([encoder.finish()]);
    buffer.slice(..).map_async(wgpu::MapMode::Read, |_| {});
    device.poll(wgpu::PollType::wait_indefinitely())?;
    let bytes = buffer.slice(..).get_mapped_range()?;
    let halves: Vec<half::f16> = (0..SIZE[1] as usize)
        .flat_map(|y| {
            bytemuck::pod_collect_to_vec::<u8, half::f16>(&bytes[y * row as usize..][..SIZE[0] as usize * 8])
        })
        .collect();
    Ok(halves.chunks_exact(4).map(|p| [p[0].to_f32(), p[1].to_f32(), p[2].to_f32(), p[3].to_f32()]).collect())
}
