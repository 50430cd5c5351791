//! Each reflector's roughness from glTF files built in code: the factor alone, the
//! metallic-roughness texture's mean over the texels the region covers, the area-weighted
//! mean where a region merges materials, and the same bytes every time.

use ppr_extract::{ExtractParams, Extraction, extract, load_level_from_bytes};
use ppr_level::gltf_builder::{GltfBuilder, PositionFormat, quad_xz};

const NO_ROTATION: [f64; 4] = [0.0, 0.0, 0.0, 1.0];
const CLAMP: u32 = 33071;
const REPEAT: u32 = 10497;

fn extract_glb(b: GltfBuilder) -> Extraction {
    let level = load_level_from_bytes(std::path::Path::new("t.glb"), &b.glb(), std::path::Path::new("."))
        .expect("loads");
    extract(&level, &ExtractParams::default(), &|_, _| {})
}

/// A `w × d` floor quad at x0 with its own material of roughness factor `factor`.
fn floor(b: &mut GltfBuilder, name: &str, x0: f32, w: f32, d: f32, factor: f64) -> (usize, usize) {
    let m = b.material(name, factor, 0.0, None);
    let (p, i) = quad_xz(x0, 0.0, x0 + w, d, 0.0);
    let mesh = b.mesh(name, &p, &i, m, PositionFormat::F32);
    b.node(name, mesh, [0.0; 3], NO_ROTATION, [1.0; 3]);
    (m, mesh)
}

fn only_roughness(x: &Extraction) -> f64 {
    assert_eq!(x.set.reflectors.len(), 1, "{:#?}", x.set.reflectors);
    x.set.reflectors[0].roughness
}

#[test]
fn the_roughness_factor_alone() {
    let mut b = GltfBuilder::new();
    floor(&mut b, "Satin", 0.0, 2.0, 1.0, 0.2);
    assert_eq!(only_roughness(&extract_glb(b)), f64::from(0.2f32), "glTF factors are f32");
}

#[test]
fn a_texture_counts_by_the_texels_the_region_covers() {
    // A 4 × 1 texture of roughness 0, 0.2, 0.6 and 1 (green 0, 51, 153, 255), factor 0.25
    // (a candidate by its factor: selection reads factors only; 0.3 in f32 is above 0.3).
    let texture =
        |b: &mut GltfBuilder, m: usize, wrap: u32| b.roughness_texture(m, 4, 1, &[0, 51, 153, 255], wrap);
    // quad_xz's corners are (x0, z0), (x0, z1), (x1, z1), (x1, z0): u follows x.
    let uvs = |u0: f32, u1: f32| [[u0, 0.0], [u0, 1.0], [u1, 1.0], [u1, 0.0]];

    let factor = 0.25;
    // The floor's UVs cover the two middle texels only (an atlas): (0.2 + 0.6) / 2 × 0.25.
    let mut b = GltfBuilder::new();
    let (m, mesh) = floor(&mut b, "Brushed", 0.0, 2.0, 1.0, 0.25);
    texture(&mut b, m, CLAMP);
    b.uvs(mesh, &uvs(0.25, 0.75));
    let r = only_roughness(&extract_glb(b));
    assert!((r - 0.4 * factor).abs() < 1e-3, "{r}");

    // Tiled four times over the whole texture: its mean, (0 + 0.2 + 0.6 + 1) / 4 × 0.25.
    let mut b = GltfBuilder::new();
    let (m, mesh) = floor(&mut b, "Brushed", 0.0, 2.0, 1.0, 0.25);
    texture(&mut b, m, REPEAT);
    b.uvs(mesh, &uvs(0.0, 4.0));
    let r = only_roughness(&extract_glb(b));
    assert!((r - 0.45 * factor).abs() < 1e-3, "{r}");

    // Only the roughest texel: the factor.
    let mut b = GltfBuilder::new();
    let (m, mesh) = floor(&mut b, "Brushed", 0.0, 2.0, 1.0, 0.25);
    texture(&mut b, m, CLAMP);
    b.uvs(mesh, &uvs(0.8, 0.95));
    assert_eq!(only_roughness(&extract_glb(b)), factor);
}

#[test]
fn a_region_of_several_materials_takes_their_area_weighted_mean() {
    // Two coplanar floors sharing an edge make one region: 2 m² at 0.1, 4 m² at 0.25.
    let mut b = GltfBuilder::new();
    floor(&mut b, "Polished", -1.0, 1.0, 2.0, 0.1);
    floor(&mut b, "Satin", 0.0, 2.0, 2.0, 0.25);
    let x = extract_glb(b);
    let r = &x.set.reflectors[0];
    assert_eq!(x.set.reflectors.len(), 1, "one region");
    assert_eq!(r.source.materials, ["Polished", "Satin"]);
    let expected = (2.0 * f64::from(0.1f32) + 4.0 * f64::from(0.25f32)) / 6.0;
    assert!((r.roughness - expected).abs() < 1e-12, "{} vs {expected}", r.roughness);
}

#[test]
fn roughness_is_deterministic_to_the_byte() {
    let build = || {
        let mut b = GltfBuilder::new();
        let (m, mesh) = floor(&mut b, "Brushed", 0.0, 3.0, 1.0, 0.25);
        b.roughness_texture(m, 3, 2, &[10, 200, 30, 90, 250, 0], REPEAT);
        b.uvs(mesh, &[[0.1, 0.2], [0.3, 1.7], [2.9, 1.1], [1.4, -0.6]]);
        floor(&mut b, "Polished", 3.0, 1.0, 1.0, 0.05);
        b
    };
    let text = |b| extract_glb(b).set.to_json_string().unwrap();
    let first = text(build());
    assert_eq!(text(build()), first);
    let set = ppr_format::ReflectorSet::from_json_str(&first).unwrap();
    assert_eq!(set.reflectors.len(), 1, "the floors touch: one region; {first}");
    assert!(set.reflectors[0].roughness > 0.05, "{first}");
}

#[test]
fn all_planar_reflectors_are_mirrors_whatever_the_material() {
    // `--all-planar` is for levels whose one material says nothing: a rough floor becomes a
    // mirror (roughness 0) rather than a reflector the runtime leaves to its rough fallback
    // (it renders none rougher than `PlanParams::max_roughness`, 0.5).
    let mut b = GltfBuilder::new();
    floor(&mut b, "Concrete", 0.0, 2.0, 1.0, 0.9);
    let level = load_level_from_bytes(std::path::Path::new("t.glb"), &b.glb(), std::path::Path::new("."))
        .expect("loads");
    let by_material = extract(&level, &ExtractParams::default(), &|_, _| {});
    assert!(by_material.set.reflectors.is_empty(), "a rough floor is no candidate by material");
    let all = extract(&level, &ExtractParams::all_planar(), &|_, _| {});
    assert_eq!(only_roughness(&all), 0.0);
}
