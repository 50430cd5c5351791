//! Extractor: rectangle fits at every angle, huge and tiny scales, noise, slivers,
//! duplicates, T-junctions, one plane of 100 000 triangles, degenerate hulls.

use glam::{DVec2, DVec3};
use ppr_extract::rect_fit::min_area_rect;
use ppr_extract::{ExtractParams, Extraction, Level, MaterialInfo, extract};

fn glossy() -> MaterialInfo {
    MaterialInfo { roughness: 0.05, ..MaterialInfo::gltf_default() }
}

/// A `w × h` rectangle in the plane through `origin` spanned by `u`, `v`, cut into an
/// `n × m` grid of triangle pairs.
fn grid(origin: DVec3, u: DVec3, v: DVec3, [w, h]: [f64; 2], [n, m]: [usize; 2]) -> Vec<[DVec3; 3]> {
    let p = |i: usize, j: usize| origin + u * (w * i as f64 / n as f64) + v * (h * j as f64 / m as f64);
    let mut t = Vec::with_capacity(2 * n * m);
    for i in 0..n {
        for j in 0..m {
            t.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            t.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    t
}

fn run(tris: &[[DVec3; 3]]) -> Extraction {
    run_with(tris, &ExtractParams::default())
}

fn run_with(tris: &[[DVec3; 3]], params: &ExtractParams) -> Extraction {
    extract(&Level::from_triangles("stability", tris, glossy()), params, &|_, _| {})
}

/// One rectangle of `w × h` (relative tolerance `tol`) with the given normal.
fn assert_one(x: &Extraction, [w, h]: [f64; 2], normal: DVec3, tol: f64, what: &str) {
    assert_eq!(x.set.reflectors.len(), 1, "{what}: {:?}", x.set.reflectors.len());
    let r = &x.set.reflectors[0];
    let (a, b) = (2.0 * r.half_extents.x, 2.0 * r.half_extents.y);
    let (a, b) = (a.max(b), a.min(b));
    let (w, h) = (w.max(h), w.min(h));
    assert!(((a - w) / w).abs() <= tol && ((b - h) / h).abs() <= tol, "{what}: {a}×{b} vs {w}×{h}");
    assert!(r.normal.dot(normal) > 1.0 - 1e-9, "{what}: normal {}", r.normal);
}

#[test]
fn fit_stays_at_the_minimum_area_for_every_tenth_of_a_degree() {
    let (w, h) = (3.7, 1.3);
    let mut worst = 0.0f64;
    for k in 0..3600 {
        let a = (k as f64 * 0.1).to_radians();
        let (u, v) = (DVec2::from_angle(a), DVec2::from_angle(a).perp());
        let c = DVec2::new(12.5, -3.25);
        // Corners, edge midpoints, interior points, a duplicate and collinear points.
        let mut pts = Vec::new();
        for (s, t) in [
            (-1.0, -1.0),
            (1.0, -1.0),
            (1.0, 1.0),
            (-1.0, 1.0),
            (0.0, -1.0),
            (1.0, 0.3),
            (0.2, 0.1),
            (-1.0, 1.0),
        ] {
            pts.push(c + u * (s * w / 2.0) + v * (t * h / 2.0));
        }
        let r = min_area_rect(&pts).expect("a rectangle");
        worst = worst.max((r.area() - w * h).abs() / (w * h));
        for &p in &pts {
            assert!(r.contains(p, 1e-9), "angle {}: {p} outside", k as f64 * 0.1);
        }
    }
    eprintln!("3600 angles: worst relative area excess {worst:.2e}");
    assert!(worst <= 1e-6, "{worst}");
}

#[test]
fn degenerate_hulls_collinear_and_duplicate_points() {
    // Collinear points: a zero-width rectangle must not be a reflector and must not panic.
    let line: Vec<DVec2> = (0..50).map(|i| DVec2::new(i as f64 * 0.1, i as f64 * 0.05)).collect();
    let r = min_area_rect(&line);
    assert!(r.is_none_or(|r| r.half.y.abs() < 1e-9), "{r:?}");
    // All points identical.
    let same = vec![DVec2::new(1.0, 2.0); 10];
    assert!(min_area_rect(&same).is_none_or(|r| r.area() < 1e-12));
    // Many duplicates of a square's corners.
    let mut sq = Vec::new();
    for _ in 0..100 {
        sq.extend([DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y]);
    }
    let r = min_area_rect(&sq).expect("square");
    assert!((r.area() - 1.0).abs() < 1e-12);
}

#[test]
fn one_plane_of_100_000_triangles() {
    let tris = grid(DVec3::new(-50.0, 0.0, 50.0), DVec3::X, DVec3::NEG_Z, [100.0, 60.0], [250, 200]);
    assert_eq!(tris.len(), 100_000);
    let t = std::time::Instant::now();
    let x = run(&tris);
    eprintln!("100 000 triangles: one rectangle in {:.2} s", t.elapsed().as_secs_f64());
    assert_one(&x, [100.0, 60.0], DVec3::Y, 1e-9, "100k");
}

#[test]
fn near_coplanar_noise_slivers_duplicates_and_t_junctions() {
    // Noise of 1e-4 of the size across the plane.
    let mut rng = 0x1234_5678_u64;
    let mut noise = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng % 2001) as f64 / 1000.0 - 1.0
    };
    let mut tris = grid(DVec3::ZERO, DVec3::X, DVec3::NEG_Z, [8.0, 4.0], [16, 8]);
    for t in &mut tris {
        for p in t.iter_mut() {
            p.y += 8e-4 * noise();
        }
    }
    assert_one(&run(&tris), [8.0, 4.0], DVec3::Y, 2e-3, "noise 1e-4");

    // Slivers and zero-area triangles along with the real ones, and duplicated vertices.
    let mut tris = grid(DVec3::ZERO, DVec3::X, DVec3::NEG_Z, [8.0, 4.0], [4, 4]);
    let (a, b) = (DVec3::new(1.0, 0.0, -1.0), DVec3::new(7.0, 0.0, -1.0));
    tris.push([a, b, a + (b - a) * 0.5 + DVec3::new(0.0, 0.0, -1e-9)]);
    tris.push([a, a, b]);
    tris.extend_from_within(0..4);
    let x = run(&tris);
    assert_one(&x, [8.0, 4.0], DVec3::Y, 1e-9, "slivers");

    // T-junctions: a 2×1 split next to a 1×1 tile, sharing an edge without a shared vertex.
    let mut tris = grid(DVec3::ZERO, DVec3::X, DVec3::NEG_Z, [2.0, 2.0], [2, 1]);
    tris.extend(grid(DVec3::new(2.0, 0.0, 0.0), DVec3::X, DVec3::NEG_Z, [2.0, 2.0], [1, 1]));
    assert_one(&run(&tris), [4.0, 2.0], DVec3::Y, 1e-9, "T-junctions");
}

#[test]
fn huge_tiny_and_far_away_levels() {
    for (what, origin, scale) in [
        ("1e-3 m", DVec3::ZERO, 1e-3),
        ("1e5 m", DVec3::ZERO, 1e5),
        ("10 km away", DVec3::new(1e4, 3.0, -1e4), 1.0),
        ("100 km away", DVec3::new(1e5, -20.0, 1e5), 1.0),
    ] {
        let u = DVec3::new(0.6, 0.0, 0.8);
        let v = DVec3::Y;
        let tris = grid(origin, u, v, [5.0 * scale, 3.0 * scale], [6, 4]);
        // Tolerances are metres: a wall modelled at another scale says its unit.
        let x = run_with(&tris, &ExtractParams::default().in_level_units(1.0 / scale));
        let normal = u.cross(v).normalize();
        assert_one(&x, [5.0 * scale, 3.0 * scale], normal, 1e-9, what);
        let r = &x.set.reflectors[0];
        let expected_center = origin + (u * 5.0 + v * 3.0) * (scale / 2.0);
        let err = (r.center - expected_center).length() / scale;
        eprintln!("{what}: centre off by {err:.2e} of the size");
        assert!(err < 1e-9, "{what}: {err}");
    }
}
