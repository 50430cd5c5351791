//! The level's two procedurally generated base-colour textures: floor tiles and bricks.

use image::{Rgb, RgbImage};

/// Side of both textures, pixels.
pub const TEXTURE_SIZE: u32 = 128;

/// Floor tiles: a 2 × 2 checker of light and mid grey tiles with dark grout lines. One
/// texture repeat is meant to cover 2 m × 2 m (1 m tiles).
pub fn floor_tiles() -> RgbImage {
    let tile = TEXTURE_SIZE / 2;
    RgbImage::from_fn(TEXTURE_SIZE, TEXTURE_SIZE, |x, y| {
        let (tx, ty) = (x % tile, y % tile);
        if tx < 2 || ty < 2 {
            return Rgb([70, 70, 72]);
        }
        let light = (x / tile + y / tile).is_multiple_of(2);
        let base: [u8; 3] = if light { [206, 204, 198] } else { [128, 130, 134] };
        Rgb(shade(base, speckle(x, y, 1), 6))
    })
}

/// Bricks in running bond: 8 courses of 2 bricks, odd courses offset by half a brick, with
/// light mortar; each brick gets its own shade. One repeat is meant to cover 1 m × 1 m.
pub fn bricks() -> RgbImage {
    let course = TEXTURE_SIZE / 8;
    let brick = TEXTURE_SIZE / 2;
    RgbImage::from_fn(TEXTURE_SIZE, TEXTURE_SIZE, |x, y| {
        let row = y / course;
        let shifted_x = (x + (row % 2) * brick / 2) % TEXTURE_SIZE;
        if y % course < 2 || shifted_x % brick < 2 {
            return Rgb(shade([196, 190, 178], speckle(x, y, 2), 4));
        }
        let brick_id = row * 2 + shifted_x / brick;
        let per_brick = speckle(brick_id, 97, 3);
        Rgb(shade(shade([150, 68, 48], per_brick, 18), speckle(x, y, 4), 5))
    })
}

/// A deterministic pseudo-random byte for a pixel (integer hash, no state).
fn speckle(x: u32, y: u32, salt: u32) -> u8 {
    let mut h = x.wrapping_mul(0x27d4_eb2d) ^ y.wrapping_mul(0x1656_67b1) ^ salt.wrapping_mul(0x9e37_79b9);
    h ^= h >> 15;
    h = h.wrapping_mul(0x85eb_ca6b);
    h ^= h >> 13;
    h.to_le_bytes()[0]
}

/// `colour` brightened or darkened by up to `amplitude` according to `noise` (0..=255).
fn shade(colour: [u8; 3], noise: u8, amplitude: i32) -> [u8; 3] {
    let offset = (i32::from(noise) - 128) * amplitude / 128;
    colour.map(|c| u8::try_from((i32::from(c) + offset).clamp(0, 255)).expect("clamped to a byte"))
}
