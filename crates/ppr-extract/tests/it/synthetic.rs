//! Hard synthetic inputs built in code: noise, slivers, duplicated vertices, L and ring
//! regions, rotations, far planes, tiny and huge scales, T-junctions, determinism.

use glam::{DQuat, DVec3};
use ppr_extract::{ExtractParams, Extraction, Level, MaterialInfo, extract};

use crate::checks::assert_encloses_regions;

fn glossy() -> MaterialInfo {
    MaterialInfo { name: "polished".into(), roughness: 0.05, ..MaterialInfo::gltf_default() }
}

/// Deterministic noise in [-1, 1].
struct Noise(u64);
impl Noise {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// A `w × h` rectangle of `nx × ny` cells (two triangles each) in the plane spanned by
/// `u` and `v` around `center`, facing `u × v`; cells for which `keep(i, j)` is false are
/// left out; every corner moves along the normal by up to `noise`.
#[allow(clippy::too_many_arguments)]
fn grid(
    center: DVec3,
    rot: DQuat,
    w: f64,
    h: f64,
    nx: usize,
    ny: usize,
    noise: f64,
    keep: impl Fn(usize, usize) -> bool,
) -> Vec<[DVec3; 3]> {
    let (u, v) = (rot * DVec3::X, rot * DVec3::NEG_Z);
    let n = u.cross(v);
    let mut rng = Noise(42);
    let corners: Vec<Vec<DVec3>> = (0..=nx)
        .map(|i| {
            (0..=ny)
                .map(|j| {
                    center
                        + u * (w * (i as f64 / nx as f64 - 0.5))
                        + v * (h * (j as f64 / ny as f64 - 0.5))
                        + n * (noise * rng.next())
                })
                .collect()
        })
        .collect();
    let mut out = Vec::new();
    for i in 0..nx {
        for j in 0..ny {
            if keep(i, j) {
                let (a, b, c, d) =
                    (corners[i][j], corners[i + 1][j], corners[i + 1][j + 1], corners[i][j + 1]);
                out.push([a, b, c]);
                out.push([a, c, d]);
            }
        }
    }
    out
}

fn run(tris: &[[DVec3; 3]], params: &ExtractParams) -> Extraction {
    let level = Level::from_triangles("synthetic", tris, glossy());
    let x = extract(&level, params, &|_, _| {});
    assert_encloses_regions(&x, 3.0 * params.distance_tolerance_m, "synthetic");
    x
}

fn assert_single(x: &Extraction, w: f64, h: f64, normal: DVec3, tol: f64) {
    assert_eq!(x.set.reflectors.len(), 1, "{:#?}", x.set.reflectors);
    let r = &x.set.reflectors[0];
    let (long, short) = (w.max(h), w.min(h));
    assert!(
        (2.0 * r.half_extents.x - long).abs() <= tol * long,
        "long side {} vs {long}",
        2.0 * r.half_extents.x
    );
    assert!(
        (2.0 * r.half_extents.y - short).abs() <= tol * long,
        "short side {} vs {short}",
        2.0 * r.half_extents.y
    );
    assert!(r.normal.dot(normal) > 1.0 - 1e-6, "normal {:?} vs {normal:?}", r.normal);
}

#[test]
fn noisy_coplanar_triangles_make_one_rectangle() {
    // ±1.1 mm noise on a 10 × 5 m plane of 3200 triangles.
    let rot = DQuat::from_euler(glam::EulerRot::XYZ, 0.4, 0.2, -0.3);
    let tris = grid(DVec3::new(3.0, 1.0, -2.0), rot, 10.0, 5.0, 40, 40, 1.1e-3, |_, _| true);
    // The noise tilts the 12.5 cm wide triangles by up to 1.0°: the angle tolerance must
    // allow that (with relative parameters the few refused triangles were dropped as smaller
    // than the minimum area; 0.01 m² keeps them).
    let x = run(&tris, &ExtractParams { angle_tolerance_deg: 1.5, ..ExtractParams::default() });
    assert_single(&x, 10.0, 5.0, rot * DVec3::Y, 1e-3);
    assert!(x.set.reflectors[0].coverage > 0.99);
}

#[test]
fn slivers_and_duplicated_vertices() {
    // A 4 × 1 rectangle triangulated as a fan of 200 slivers from one corner, plus a second
    // copy of every triangle with the opposite winding (double-sided export).
    let (a, b, c, d) =
        (DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(4.0, 0.0, -1.0), DVec3::new(0.0, 0.0, -1.0));
    let mut tris = Vec::new();
    let steps = 200;
    for k in 0..steps {
        let p = |t: f64| if t <= 0.5 { b.lerp(c, t * 2.0) } else { c.lerp(d, t * 2.0 - 1.0) };
        tris.push([a, p(k as f64 / steps as f64), p((k + 1) as f64 / steps as f64)]);
    }
    let front = tris.clone();
    tris.extend(front.iter().map(|t| [t[0], t[2], t[1]]));
    tris.extend(front.iter().take(50)); // and exact duplicates, which decide the side
    let x = run(&tris, &ExtractParams::default());
    assert_single(&x, 4.0, 1.0, DVec3::Y, 1e-9);
    assert!(x.warnings.iter().any(|w| w.to_string().contains("duplicate triangles")), "{:?}", x.warnings);
}

#[test]
fn degenerate_triangles_are_skipped_and_counted() {
    let mut tris = grid(DVec3::ZERO, DQuat::IDENTITY, 2.0, 2.0, 2, 2, 0.0, |_, _| true);
    tris.push([DVec3::ONE, DVec3::ONE, DVec3::ONE]);
    tris.push([DVec3::ZERO, DVec3::X, DVec3::X * 2.0]);
    let x = run(&tris, &ExtractParams::default());
    assert_eq!(x.set.reflectors.len(), 1);
    assert!(x.warnings.contains(&ppr_extract::Warning::DegenerateTriangles(2)), "{:?}", x.warnings);
}

#[test]
fn l_and_ring_regions_split_into_tight_rectangles() {
    for angle in [0.0, 0.7, 2.0] {
        let rot = DQuat::from_rotation_y(angle);
        let l = grid(DVec3::ZERO, rot, 8.0, 8.0, 8, 8, 0.0, |i, j| i < 2 || j < 2);
        let x = run(&l, &ExtractParams::default());
        assert_eq!(x.set.reflectors.len(), 2, "L at {angle}");
        let total: f64 = x.set.reflectors.iter().map(|r| r.area()).sum();
        assert!((total - 28.0).abs() < 1e-6, "L rectangles {total}");
        let ring =
            grid(DVec3::ZERO, rot, 8.0, 8.0, 8, 8, 0.0, |i, j| !(1..7).contains(&i) || !(1..7).contains(&j));
        let x = run(&ring, &ExtractParams::default());
        assert_eq!(x.set.reflectors.len(), 4, "ring at {angle}");
        let total: f64 = x.set.reflectors.iter().map(|r| r.area()).sum();
        assert!((total - 28.0).abs() < 1e-6, "ring rectangles {total}");
        // Without splitting: one rectangle with the coverage recorded.
        let x = run(&ring, &ExtractParams::no_split());
        assert_eq!(x.set.reflectors.len(), 1);
        assert!((x.set.reflectors[0].coverage - 28.0 / 64.0).abs() < 1e-9);
    }
}

#[test]
fn rotated_rectangles_at_many_angles() {
    for k in 0..48 {
        let a = k as f64 * 0.37;
        let rot = DQuat::from_euler(glam::EulerRot::YXZ, a, a * 0.3, -a * 0.7);
        let tris = grid(DVec3::new(1.0, 2.0, 3.0), rot, 3.0, 1.2, 3, 2, 0.0, |_, _| true);
        let x = run(&tris, &ExtractParams::default());
        assert_single(&x, 3.0, 1.2, rot * DVec3::Y, 1e-9);
    }
}

#[test]
fn far_from_the_origin_and_at_extreme_scales() {
    for (center, size) in [
        (DVec3::new(1e4, 0.0, -1e4), 10.0),
        (DVec3::new(1e5, 50.0, 1e5), 10.0),
        (DVec3::new(0.0, 0.0, 0.0), 1e-3),
        (DVec3::new(1e4, 0.0, 0.0), 1e-3),
        (DVec3::new(0.0, 0.0, 0.0), 1e5),
    ] {
        let rot = DQuat::from_euler(glam::EulerRot::XYZ, 0.1, 0.5, 0.2);
        // Two parallel planes a tenth of the size apart, so the scene is not one plane only.
        let mut tris = grid(center, rot, size, size * 0.5, 4, 4, 0.0, |_, _| true);
        tris.extend(grid(
            center + rot * DVec3::Y * (0.1 * size),
            rot,
            size * 0.5,
            size * 0.25,
            2,
            2,
            0.0,
            |_, _| true,
        ));
        // A 10 m scene modelled at another scale: one level unit is 10 / size metres.
        let x = run(&tris, &ExtractParams::default().in_level_units(10.0 / size));
        assert_eq!(x.set.reflectors.len(), 2, "at {center:?} size {size}");
        let r = &x.set.reflectors[0];
        assert!(
            (2.0 * r.half_extents.x - size).abs() < 1e-9 * size.max(center.length()),
            "size {size}: {r:?}"
        );
        assert!(r.normal.dot(rot * DVec3::Y) > 1.0 - 1e-9);
        // The upper one occludes the lower one, not the other way round.
        assert_eq!(x.set.reflectors[0].occluders, vec![1], "at {center:?} size {size}");
        assert!(x.set.reflectors[1].occluders.is_empty());
    }
}

#[test]
fn t_junctions_connect_regions() {
    // A 2 × 1 quad and, beside it, two 1 × 0.5 quads whose shared corner sits on the
    // middle of the big quad's edge (a T-junction, no shared vertex there).
    let q = |x0: f64, z0: f64, x1: f64, z1: f64| {
        let (a, b, c, d) = (
            DVec3::new(x0, 0.0, z0),
            DVec3::new(x0, 0.0, z1),
            DVec3::new(x1, 0.0, z1),
            DVec3::new(x1, 0.0, z0),
        );
        vec![[a, b, c], [a, c, d]]
    };
    let mut tris = q(0.0, 0.0, 2.0, 1.0);
    tris.extend(q(2.0, 0.0, 3.0, 0.5));
    tris.extend(q(2.0, 0.5, 3.0, 1.0));
    let x = run(&tris, &ExtractParams::default());
    assert_single(&x, 3.0, 1.0, DVec3::Y, 1e-9);
}

#[test]
fn coplanar_pieces_apart_are_separate_regions() {
    let mut tris = grid(DVec3::ZERO, DQuat::IDENTITY, 2.0, 2.0, 2, 2, 0.0, |_, _| true);
    tris.extend(grid(DVec3::new(5.0, 0.0, 0.0), DQuat::IDENTITY, 2.0, 2.0, 2, 2, 0.0, |_, _| true));
    let x = run(&tris, &ExtractParams::default());
    assert_eq!(x.set.reflectors.len(), 2);
    assert_eq!(x.set.reflectors[0].parallel_group, x.set.reflectors[1].parallel_group);
    assert!(x.set.reflectors[0].occluders.is_empty(), "coplanar shapes do not occlude each other");
}

#[test]
fn extraction_is_deterministic_and_ids_are_stable() {
    let mut tris =
        grid(DVec3::ZERO, DQuat::from_rotation_y(0.3), 8.0, 8.0, 8, 8, 1e-4, |i, j| i < 2 || j < 2);
    tris.extend(grid(DVec3::new(0.0, 1.0, 0.0), DQuat::IDENTITY, 2.0, 2.0, 3, 3, 0.0, |_, _| true));
    let a = run(&tris, &ExtractParams::default()).set.to_json_string().unwrap();
    let b = run(&tris, &ExtractParams::default()).set.to_json_string().unwrap();
    assert_eq!(a, b, "same input, same bytes");
    let ids = |p: &ExtractParams| {
        let mut v: Vec<u32> = run(&tris, p).set.reflectors.iter().map(|r| r.id).collect();
        v.sort_unstable();
        v
    };
    let base = ids(&ExtractParams::default());
    assert_eq!(
        base,
        ids(&ExtractParams { reach_m: Some(5.0), ..ExtractParams::default() }),
        "ids survive a parameter change"
    );
    let mut unique = base.clone();
    unique.dedup();
    assert_eq!(unique, base, "ids are unique");
}

#[test]
fn one_plane_of_many_triangles() {
    // 20 000 triangles in one plane (the 100 000-triangle case scales linearly).
    let tris = grid(DVec3::ZERO, DQuat::from_rotation_x(0.2), 50.0, 30.0, 100, 100, 0.0, |_, _| true);
    let x = run(&tris, &ExtractParams::default());
    assert_single(&x, 50.0, 30.0, DQuat::from_rotation_x(0.2) * DVec3::Y, 1e-9);
}
