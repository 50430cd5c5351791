//! The WGSL encoding equals the Rust reference bit for bit: millions of random offsets and
//! every edge case, for the seed's layout and the layouts of 1080p, 4K and 8K.

use glam::Vec2;
use ppr_runtime::EncodingLayout;
use ppr_runtime::encoding::{self, CLEAR_VALUE};
use wgpu::util::DeviceExt;

use ppr_tests::gpu::{gpu, read_buffer};

const KERNEL: &str = r#"
@group(0) @binding(0) var<uniform> enc_params: EncodingParams;
@group(0) @binding(1) var<storage, read> offsets: array<vec2<f32>>;
@group(0) @binding(2) var<storage, read_write> encoded: array<u32>;
// whole.x, whole.y, bits(fract.x), bits(fract.y), basis, bits(offset.x), bits(offset.y), bits(whole offset.x)
@group(0) @binding(3) var<storage, read_write> decoded: array<array<u32, 8>>;

@compute @workgroup_size(256)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = gid.x + gid.y * groups.x * 256u;
    if (i >= arrayLength(&offsets)) {
        return;
    }
    let v = ppr_encode(offsets[i], enc_params);
    encoded[i] = v;
    if (v != PPR_CLEAR_VALUE) {
        let d = ppr_decode(v, enc_params);
        let o = ppr_decoded_offset(d);
        let w = ppr_decoded_whole_offset(d);
        decoded[i] = array<u32, 8>(u32(d.whole.x), u32(d.whole.y), bitcast<u32>(d.fract.x),
            bitcast<u32>(d.fract.y), d.basis, bitcast<u32>(o.x), bitcast<u32>(o.y), bitcast<u32>(w.x));
    }
}
"#;

/// Runs encode + decode of `offsets` on the GPU.
fn gpu_encode(offsets: &[Vec2], layout: &EncodingLayout) -> (Vec<u32>, Vec<[u32; 8]>) {
    let g = gpu();
    let d = &g.device;
    let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC;
    let params = d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::bytes_of(&layout.gpu_params()),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let input = d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::cast_slice(offsets),
        usage: storage,
    });
    let n = offsets.len() as u64;
    let encoded = d.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: n * 4,
        usage: storage,
        mapped_at_creation: false,
    });
    let decoded = d.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: n * 32,
        usage: storage,
        mapped_at_creation: false,
    });
    let module = ppr_runtime::shader::module(d, "encoding parity", KERNEL);
    let pipeline = d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("encoding parity"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let bg = d.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: params.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: input.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 2, resource: encoded.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 3, resource: decoded.as_entire_binding() },
        ],
    });
    let mut encoder = d.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bg, &[]);
        let groups = (offsets.len() as u32).div_ceil(256);
        let x = groups.min(65535);
        pass.dispatch_workgroups(x, groups.div_ceil(x), 1);
    }
    g.queue.submit([encoder.finish()]);
    let enc: Vec<u32> = bytemuck::pod_collect_to_vec(&read_buffer(&encoded));
    let dec: Vec<[u32; 8]> = bytemuck::pod_collect_to_vec(&read_buffer(&decoded));
    (enc, dec)
}

/// Compares GPU and CPU for every offset; panics with the first mismatches.
fn check_parity(offsets: &[Vec2], layout: &EncodingLayout) -> usize {
    let (enc, dec) = gpu_encode(offsets, layout);
    let mut mismatches = Vec::new();
    let mut written = 0;
    for (i, &o) in offsets.iter().enumerate() {
        let cpu = encoding::encode(o, layout);
        let cpu_dec = encoding::decode(cpu, layout).map(|d| {
            let off = d.offset();
            let whole = d.whole_offset();
            [
                d.whole.x as u32,
                d.whole.y as u32,
                d.fract.x.to_bits(),
                d.fract.y.to_bits(),
                d.basis,
                off.x.to_bits(),
                off.y.to_bits(),
                whole.x.to_bits(),
            ]
        });
        let same = enc[i] == cpu && cpu_dec.is_none_or(|c| c == dec[i]);
        if !same && mismatches.len() < 8 {
            mismatches.push(format!("{o:?}: gpu {:#010x} {:?} cpu {cpu:#010x} {cpu_dec:?}", enc[i], dec[i]));
        }
        written += usize::from(cpu != CLEAR_VALUE);
    }
    assert!(mismatches.is_empty(), "{layout:?} on {}:\n{}", gpu().info.name, mismatches.join("\n"));
    written
}

/// Deterministic pseudo-random offsets: a mix of short, long, axis-near and diagonal ones.
fn random_offsets(count: usize, max: f32, seed: u64) -> Vec<Vec2> {
    let mut state = seed;
    let mut next = move || {
        // xorshift64*
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..count)
        .map(|i| {
            let r = match i % 4 {
                0 => max * next(),
                1 => 8.0 * next(),
                2 => max * next() * next(),
                _ => (max * next()).round() + 0.5,
            };
            let a = std::f32::consts::TAU * next();
            let v = Vec2::new(a.cos(), a.sin()) * r;
            if i % 7 == 0 { Vec2::new(v.x, v.x * (1.0 - 2.0 * (i % 2) as f32)) } else { v }
        })
        .collect()
}

/// Offsets on and around every boundary: zero, axis-aligned, exact diagonals, half-pixel
/// ties, the largest that fit and the smallest that do not, NaN and infinities.
fn edge_offsets(layout: &EncodingLayout) -> Vec<Vec2> {
    let max_major = layout.max_major() as f32;
    let bias = layout.minor_bias() as f32;
    let mut v = vec![
        Vec2::ZERO,
        Vec2::new(-0.0, 0.0),
        Vec2::new(f32::NAN, 0.0),
        Vec2::new(f32::INFINITY, 1.0),
        Vec2::new(1.0, f32::NEG_INFINITY),
        Vec2::splat(1e9),
    ];
    for m in [
        0.0,
        0.25,
        0.5,
        0.5 + 1.0 / 64.0,
        1.0,
        1.5,
        2.0,
        100.5,
        bias - 1.0,
        bias - 0.5,
        bias,
        max_major - 0.5,
        max_major,
        max_major + 0.5,
        max_major + 1.0,
    ] {
        for d in [-0.5f32, -1.0 / 32.0, 0.0, 1.0 / 64.0, 0.5] {
            for s in [1.0f32, -1.0] {
                let a = m * s + d;
                v.extend([
                    Vec2::new(a, 0.0),
                    Vec2::new(0.0, a),
                    Vec2::new(a, a),
                    Vec2::new(a, -a),
                    Vec2::new(a, 0.5 * a),
                ]);
                v.extend([Vec2::new(a, bias - 1.0), Vec2::new(bias - 0.5, a), Vec2::new(a, -bias)]);
            }
        }
    }
    v
}

#[test]
fn gpu_encoding_equals_cpu_reference_bit_for_bit() {
    let layouts = [
        EncodingLayout::SEED,
        EncodingLayout::for_resolution(1920, 1080),
        EncodingLayout::for_resolution(3840, 2160),
        EncodingLayout::for_resolution(7680, 4320),
        EncodingLayout { mirror_fractions: false, ..EncodingLayout::for_resolution(1920, 1080) },
    ];
    let mut total = 0;
    for (k, layout) in layouts.iter().enumerate() {
        let max = layout.max_major() as f32 * 1.05;
        let mut offsets =
            random_offsets(if k == 2 { 4_000_000 } else { 1_000_000 }, max, 0x9e37_79b9 + k as u64);
        offsets.extend(edge_offsets(layout));
        let written = check_parity(&offsets, layout);
        assert!(written > offsets.len() / 2, "most offsets fit: {written}/{}", offsets.len());
        total += offsets.len();
    }
    eprintln!("{total} offsets encoded and decoded identically on {}", gpu().info.name);
}
