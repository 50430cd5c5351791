//! Image I/O, readback alignment and metrics.

use image::{Rgba, Rgba32FImage};
use ppr_testbed::PixelMask;
use ppr_testbed::image_io::{self, ToneMap, difference_image, error_ramp, write_exr, write_png};
use ppr_testbed::metrics::{compare, flip_mean, mean_abs_error, psnr};
use ppr_testbed::readback::{read_rgba_f32, read_u32};

use crate::common::gpu;

fn gradient(w: u32, h: u32) -> Rgba32FImage {
    Rgba32FImage::from_fn(w, h, |x, y| {
        Rgba([x as f32 / w as f32, y as f32 / h as f32, ((x + y) % 7) as f32 / 7.0, 1.0])
    })
}

#[test]
fn png_round_trip_is_within_srgb_quantisation() {
    let dir = tempfile::tempdir().expect("tempdir");
    let img = gradient(37, 21);
    let path = dir.path().join("g.png");
    write_png(&path, &img, ToneMap::Clamp).expect("write");
    let back = image_io::read_linear(&path).expect("read");
    assert_eq!(back.dimensions(), img.dimensions());
    for (a, b) in img.pixels().zip(back.pixels()) {
        for c in 0..3 {
            let (ea, eb) = (image_io::linear_to_srgb(a.0[c]), image_io::linear_to_srgb(b.0[c]));
            assert!((ea - eb).abs() <= 0.5 / 255.0 + 1e-6, "{a:?} vs {b:?}");
        }
    }
}

#[test]
fn exr_round_trip_is_exact() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut img = gradient(19, 13);
    img.put_pixel(3, 4, Rgba([12.5, -0.25, 1e-3, 0.5])); // HDR and negative values survive
    let path = dir.path().join("g.exr");
    write_exr(&path, &img).expect("write");
    let back = image_io::read_linear(&path).expect("read");
    assert_eq!(back, img);
}

#[test]
fn reinhard_and_clamp_tonemaps() {
    assert_eq!(ToneMap::Clamp.apply(3.0), 1.0);
    assert_eq!(ToneMap::Clamp.apply(-1.0), 0.0);
    assert_eq!(ToneMap::Clamp.apply(f32::NAN), 0.0);
    assert!((ToneMap::Reinhard.apply(1.0) - 0.5).abs() < 1e-7);
    assert_eq!(error_ramp(0.0), [0, 0, 0]);
    assert_eq!(error_ramp(1.0), [255, 0, 0]);
}

#[test]
fn metrics_of_identical_images_are_perfect() {
    let img = gradient(64, 48);
    let mask = PixelMask::all(64, 48);
    let c = compare(&img, &img, &mask, ToneMap::Clamp).expect("compare");
    assert_eq!(c.psnr_db, f64::INFINITY);
    assert_eq!(c.mean_abs_error, 0.0);
    assert_eq!(c.flip_mean, 0.0);
    assert_eq!(c.pixels, 64 * 48);
}

#[test]
fn psnr_has_peak_one_on_tonemapped_values() {
    let a = Rgba32FImage::from_pixel(8, 8, Rgba([0.5, 0.5, 0.5, 1.0]));
    let b = Rgba32FImage::from_pixel(8, 8, Rgba([0.6, 0.6, 0.6, 1.0]));
    let mask = PixelMask::all(8, 8);
    // MSE = 0.01 -> 20 dB with peak 1.
    let p = psnr(&a, &b, &mask, ToneMap::Clamp).expect("psnr");
    assert!((p - 20.0).abs() < 1e-4, "{p}");
    // Values above 1 are clamped first: 2.0 vs 3.0 is no error.
    let hi = Rgba32FImage::from_pixel(8, 8, Rgba([2.0, 2.0, 2.0, 1.0]));
    let hi2 = Rgba32FImage::from_pixel(8, 8, Rgba([3.0, 3.0, 3.0, 1.0]));
    assert_eq!(psnr(&hi, &hi2, &mask, ToneMap::Clamp).expect("psnr"), f64::INFINITY);
}

#[test]
fn metrics_respect_the_mask() {
    let a = gradient(40, 30);
    let mut b = a.clone();
    for y in 0..30 {
        for x in 20..40 {
            b.put_pixel(x, y, Rgba([1.0, 0.0, 1.0, 1.0]));
        }
    }
    let left = PixelMask::from_fn(40, 30, |x, _| x < 20);
    let right = PixelMask::from_fn(40, 30, |x, _| x >= 20);
    assert_eq!(psnr(&a, &b, &left, ToneMap::Clamp).expect("psnr"), f64::INFINITY);
    assert_eq!(mean_abs_error(&a, &b, &left, ToneMap::Clamp).expect("mae"), 0.0);
    assert!(psnr(&a, &b, &right, ToneMap::Clamp).expect("psnr") < 10.0);
    assert!(mean_abs_error(&a, &b, &right, ToneMap::Clamp).expect("mae") > 0.2);
    let flip_right = flip_mean(&a, &b, &right, ToneMap::Clamp).expect("flip");
    let flip_left = flip_mean(&a, &b, &left, ToneMap::Clamp).expect("flip");
    assert!(flip_right > 0.3, "{flip_right}");
    assert_eq!(flip_left, 0.0, "differences outside the mask must not bleed in");
    // An empty mask has no error.
    let none = PixelMask::from_fn(40, 30, |_, _| false);
    assert_eq!(psnr(&a, &b, &none, ToneMap::Clamp).expect("psnr"), f64::INFINITY);
    // The difference image is dark grey outside the mask, red for a full error inside.
    let diff = difference_image(&a, &b, &right, 4.0, ToneMap::Clamp).expect("diff");
    assert_eq!(diff.get_pixel(30, 10).0, [255, 0, 0]);
    let outside = diff.get_pixel(5, 10).0;
    assert!(outside[0] == outside[1] && outside[1] == outside[2] && outside[0] < 70, "{outside:?}");
    // Sizes are checked.
    assert!(psnr(&a, &gradient(10, 10), &left, ToneMap::Clamp).is_err());
}

/// Readback removes the 256-byte row padding (widths that are not multiples of 64 texels).
#[test]
fn readback_handles_row_padding() {
    let g = gpu();
    let _guard = g.lock();
    let (device, queue) = (&g.ctx.device, &g.ctx.queue);
    for (w, h) in [(37u32, 5u32), (64, 3), (1, 1), (130, 7)] {
        let img = gradient(w, h);
        let halfs: Vec<u16> = img.as_raw().iter().map(|&v| half::f16::from_f32(v).to_bits()).collect();
        let texture = make_texture(device, wgpu::TextureFormat::Rgba16Float, w, h);
        upload(queue, &texture, bytemuck::cast_slice(&halfs), 8 * w, w, h);
        let back = read_rgba_f32(device, queue, &texture).expect("readback");
        for (a, b) in img.pixels().zip(back.pixels()) {
            for c in 0..4 {
                assert!((a.0[c] - b.0[c]).abs() < 1e-3, "{w}x{h}: {a:?} vs {b:?}");
            }
        }
        let ids: Vec<u32> = (0..w * h).map(|i| i.wrapping_mul(2_654_435_761).wrapping_add(i)).collect();
        let texture = make_texture(device, wgpu::TextureFormat::R32Uint, w, h);
        upload(queue, &texture, bytemuck::cast_slice(&ids), 4 * w, w, h);
        assert_eq!(read_u32(device, queue, &texture).expect("readback").data, ids, "{w}x{h}");
    }
}

fn make_texture(device: &wgpu::Device, format: wgpu::TextureFormat, w: u32, h: u32) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("readback test"),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::COPY_DST
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    })
}

fn upload(queue: &wgpu::Queue, texture: &wgpu::Texture, bytes: &[u8], row: u32, w: u32, h: u32) {
    queue.write_texture(
        texture.as_image_copy(),
        bytes,
        wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: Some(h) },
        wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
    );
}
