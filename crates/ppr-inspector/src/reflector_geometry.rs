//! In-plane geometry of one reflector: placement (centre, angle, half extents), and the
//! shape operations behind split, merge and re-fit. Pure functions on `ppr_format` types.

use glam::{DVec2, DVec3};
use ppr_extract::hull::convex_hull;
use ppr_extract::plane::Plane;
use ppr_extract::polygon::Polygon;
use ppr_extract::rect_fit::min_area_rect;
use ppr_format::Reflector;

use crate::document::ReflectorRegion;
use crate::error::EditError;

/// Where a rectangle sits in its plane: what move, resize and rotate change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Centre, world space (projected onto the plane when applied).
    pub center: DVec3,
    /// Angle of `axis_u` from [`in_plane_reference`] about the normal, degrees.
    pub angle_deg: f64,
    /// Half sizes along `axis_u` and `axis_v`, metres.
    pub half_extents: DVec2,
}

/// Which rectangle axis a split cuts across.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SplitAxis {
    /// Cut across `axis_u` (the parts sit side by side along u).
    U,
    /// Cut across `axis_v`.
    V,
}

/// How close two reflectors must be to count as one plane (for merging).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoplanarTolerance {
    /// Cosine of the largest angle between the normals.
    pub cos_angle: f64,
    /// Largest distance of a corner of one from the plane of the other, metres.
    pub distance: f64,
}

/// The in-plane direction angles are measured from: world +X projected onto the plane
/// (world +Z where the plane faces ±X).
pub fn in_plane_reference(normal: DVec3) -> DVec3 {
    let helper = if normal.x.abs() > 0.9 { DVec3::Z } else { DVec3::X };
    (helper - normal * helper.dot(normal)).normalize()
}

/// +1 when `axis_v = normal × axis_u`, −1 when the frame is mirrored.
fn handedness(r: &Reflector) -> f64 {
    if r.axis_v.dot(r.normal.cross(r.axis_u)) >= 0.0 { 1.0 } else { -1.0 }
}

/// The placement of `r`.
pub fn placement_of(r: &Reflector) -> Placement {
    let reference = in_plane_reference(r.normal);
    let side = r.normal.cross(reference);
    let angle = r.axis_u.dot(side).atan2(r.axis_u.dot(reference));
    Placement { center: r.center, angle_deg: angle.to_degrees(), half_extents: r.half_extents }
}

/// `r` moved, rotated and resized to `p` within its own plane (normal unchanged, the
/// centre projected onto the plane, the frame's handedness kept).
pub fn place(r: &Reflector, p: &Placement) -> Reflector {
    let n = r.normal;
    let reference = in_plane_reference(n);
    let (sin, cos) = p.angle_deg.to_radians().sin_cos();
    let u = (reference * cos + n.cross(reference) * sin).normalize();
    let v = n.cross(u) * handedness(r);
    let center = p.center - n * (p.center - r.center).dot(n);
    Reflector { center, axis_u: u, axis_v: v, half_extents: p.half_extents, ..r.clone() }
}

/// Reflective area over rectangle area, clamped to `[0, 1]`.
pub fn coverage_of(reflective_area: f64, rect: &Reflector) -> f64 {
    let area = rect.area();
    if area > 0.0 { (reflective_area / area).clamp(0.0, 1.0) } else { 0.0 }
}

/// Reflective area of `r`: its region's when known, else coverage × rectangle area.
pub fn reflective_area(r: &Reflector, region: Option<&ReflectorRegion>) -> f64 {
    region.map_or(r.coverage * r.area(), |g| g.reflective_area)
}

/// Coordinates of `p` in the rectangle's (u, v) frame.
fn local2(r: &Reflector, p: DVec3) -> DVec2 {
    let d = p - r.center;
    DVec2::new(d.dot(r.axis_u), d.dot(r.axis_v))
}

/// The world point with rectangle coordinates `q`.
fn lift2(r: &Reflector, q: DVec2) -> DVec3 {
    r.center + r.axis_u * q.x + r.axis_v * q.y
}

/// The two halves of `r` cut across `axis` at fraction `at` of its length (0 < at < 1).
/// With a region, each part shrinks to the part of the region's convex hull on its side,
/// and gets that share of the reflective area; without one, the parts are exact cuts with
/// the parent's coverage.
///
/// # Errors
/// [`EditError::NotSplittable`] when `at` is outside (0, 1) or one side has no region.
pub fn split(
    r: &Reflector,
    region: Option<&ReflectorRegion>,
    axis: SplitAxis,
    at: f64,
) -> Result<[(Reflector, Option<ReflectorRegion>); 2], EditError> {
    let refuse = |reason: String| EditError::NotSplittable { name: r.name.clone(), reason };
    if !(at > 0.0 && at < 1.0) {
        return Err(refuse(format!("the cut must be strictly inside the rectangle (0 < at < 1, not {at})")));
    }
    let dir = match axis {
        SplitAxis::U => DVec2::X,
        SplitAxis::V => DVec2::Y,
    };
    let half = r.half_extents;
    let extent = half.dot(dir);
    let cut = -extent + 2.0 * extent * at;
    // The two halves of the rectangle in its own frame: (lo, hi) corners.
    let sides = [(-half, half - dir * (extent - cut)), (-half + dir * (cut + extent), half)];
    let hull = region.map(|g| {
        let flat = convex_hull(&g.points.iter().map(|&p| local2(r, p)).collect::<Vec<_>>());
        let spatial = flat.iter().map(|&q| lift2(r, q)).collect();
        Polygon { flat, spatial, roughness: r.roughness }
    });
    let mut parts = Vec::with_capacity(2);
    for (k, (lo, hi)) in sides.into_iter().enumerate() {
        let (lo, hi, part_region) = match (&hull, region) {
            (Some(hull), Some(g)) if hull.flat.len() >= 3 => {
                let Some(piece) = hull.clip(dir, cut, k == 0) else {
                    return Err(refuse(format!("no reflective region on side {} of the cut", k + 1)));
                };
                let (plo, phi) = bounds2(&piece.flat);
                let share = piece.area() / hull.area().max(f64::MIN_POSITIVE);
                let area = g.reflective_area * share.clamp(0.0, 1.0);
                (
                    plo.max(lo),
                    phi.min(hi),
                    Some(ReflectorRegion { points: piece.spatial, reflective_area: area }),
                )
            }
            _ => (lo, hi, None),
        };
        let size = (hi - lo) * 0.5;
        if !(size.x > 0.0 && size.y > 0.0) {
            return Err(refuse(format!("part {} of the cut would be empty", k + 1)));
        }
        let mut part = r.clone();
        part.center = lift2(r, (lo + hi) * 0.5);
        part.half_extents = size;
        part.coverage = match &part_region {
            Some(g) => coverage_of(g.reflective_area, &part),
            None => r.coverage,
        };
        part.name = format!("{} [{}]", r.name, if k == 0 { "a" } else { "b" });
        parts.push((part, part_region));
    }
    let b = parts.pop();
    let a = parts.pop();
    match (a, b) {
        (Some(a), Some(b)) => Ok([a, b]),
        _ => Err(refuse("internal: a split makes two parts".into())),
    }
}

fn bounds2(points: &[DVec2]) -> (DVec2, DVec2) {
    points.iter().fold((DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)), |(lo, hi), &p| {
        (lo.min(p), hi.max(p))
    })
}

/// The minimum-area rectangle in `template`'s plane enclosing `points`, with the axes
/// turned to stay closest to `template`'s (its other fields are kept).
fn fit_in_plane(template: &Reflector, points: &[DVec3]) -> Option<Reflector> {
    let plane = Plane::new(template.center, template.normal);
    let flat: Vec<DVec2> = points.iter().map(|&p| plane.project(p)).collect();
    let rect = min_area_rect(&flat)?;
    let a = plane.lift_direction(rect.axis).normalize();
    let b = plane.lift_direction(rect.perp()).normalize();
    // Of ±a and ±b, the direction closest to the old u becomes u.
    let swapped = DVec2::new(rect.half.y, rect.half.x);
    let candidates = [(a, rect.half), (-a, rect.half), (b, swapped), (-b, swapped)];
    let (u, half) = candidates
        .into_iter()
        .max_by(|x, y| x.0.dot(template.axis_u).total_cmp(&y.0.dot(template.axis_u)))?;
    let mut out = template.clone();
    out.center = plane.lift(rect.center);
    out.axis_u = u;
    out.axis_v = template.normal.cross(u) * handedness(template);
    out.half_extents = half;
    Some(out)
}

/// `r` re-fitted to its region: the minimum-area rectangle of the region in `r`'s plane.
///
/// # Errors
/// [`EditError::NoRegion`] without a region or when the region is degenerate.
pub fn refit(r: &Reflector, region: Option<&ReflectorRegion>) -> Result<Reflector, EditError> {
    let refuse = |reason: &str| EditError::NoRegion { name: r.name.clone(), reason: reason.to_owned() };
    let region = region.ok_or_else(|| {
        refuse("its region is unknown (regions come from an extraction, not from a loaded file: re-run extraction)")
    })?;
    let mut out = fit_in_plane(r, &region.points).ok_or_else(|| refuse("its region has no points"))?;
    if !(out.half_extents.x > 0.0 && out.half_extents.y > 0.0) {
        return Err(refuse("its region has no area"));
    }
    out.coverage = coverage_of(region.reflective_area, &out);
    Ok(out)
}

/// `a` and `b` as one rectangle in `a`'s plane: the minimum-area rectangle around both
/// regions (or both rectangles when a region is unknown), with their summed reflective
/// area. The result keeps `a`'s id, kind and frame handedness.
///
/// # Errors
/// [`EditError::NotMergeable`] when the two are not coplanar within `tolerance`.
pub fn merge(
    a: &Reflector,
    a_region: Option<&ReflectorRegion>,
    b: &Reflector,
    b_region: Option<&ReflectorRegion>,
    tolerance: CoplanarTolerance,
) -> Result<(Reflector, Option<ReflectorRegion>), EditError> {
    let refuse = |reason: String| EditError::NotMergeable { a: a.name.clone(), b: b.name.clone(), reason };
    if a.id == b.id {
        return Err(refuse("a reflector cannot be merged with itself".into()));
    }
    let cos = a.normal.dot(b.normal);
    if cos < tolerance.cos_angle {
        let angle = cos.clamp(-1.0, 1.0).acos().to_degrees();
        return Err(refuse(format!("they are not parallel (normals {angle:.2}° apart)")));
    }
    let off = b.corners().iter().map(|&p| a.signed_distance(p).abs()).fold(0.0, f64::max);
    if off > tolerance.distance {
        return Err(refuse(format!(
            "they are not in one plane ({off:.4} m apart, tolerance {:.4} m)",
            tolerance.distance
        )));
    }
    let (points, region): (Vec<DVec3>, Option<ReflectorRegion>) = match (a_region, b_region) {
        (Some(ga), Some(gb)) => {
            let points: Vec<DVec3> = ga.points.iter().chain(&gb.points).copied().collect();
            let area = ga.reflective_area + gb.reflective_area;
            (points.clone(), Some(ReflectorRegion { points, reflective_area: area }))
        }
        _ => (a.corners().into_iter().chain(b.corners()).collect(), None),
    };
    let mut merged = fit_in_plane(a, &points).ok_or_else(|| refuse("nothing to fit".into()))?;
    let (area_a, area_b) = (reflective_area(a, a_region), reflective_area(b, b_region));
    let area = area_a + area_b;
    merged.coverage = coverage_of(area, &merged);
    // The extractor's rule for a region of several surfaces: the area-weighted mean.
    merged.roughness = if area > 0.0 {
        ((area_a * a.roughness + area_b * b.roughness) / area).clamp(0.0, 1.0)
    } else {
        0.5 * (a.roughness + b.roughness)
    };
    merged.name = format!("{} + {}", a.name, b.name);
    merged.enabled = a.enabled || b.enabled;
    for n in &b.source.nodes {
        if !merged.source.nodes.contains(n) {
            merged.source.nodes.push(n.clone());
        }
    }
    for m in &b.source.materials {
        if !merged.source.materials.contains(m) {
            merged.source.materials.push(m.clone());
        }
    }
    Ok((merged, region))
}

#[cfg(test)]
mod tests {
    use ppr_format::ReflectorKind;

    use super::*;

    fn floor(center: DVec3, half: DVec2) -> Reflector {
        Reflector::new(1, "floor", ReflectorKind::Opaque, center, DVec3::Y, DVec3::X, half)
    }

    fn square_region(lo: DVec2, hi: DVec2) -> ReflectorRegion {
        let points = vec![
            DVec3::new(lo.x, 0.0, -lo.y),
            DVec3::new(hi.x, 0.0, -lo.y),
            DVec3::new(hi.x, 0.0, -hi.y),
            DVec3::new(lo.x, 0.0, -hi.y),
        ];
        let size = hi - lo;
        ReflectorRegion { points, reflective_area: size.x * size.y }
    }

    #[test]
    fn placement_round_trips_and_stays_in_plane() {
        let r = floor(DVec3::new(1.0, 2.0, 3.0), DVec2::new(2.0, 1.0));
        let p = placement_of(&r);
        let back = place(&r, &p);
        assert!((back.axis_u - r.axis_u).length() < 1e-12 && (back.axis_v - r.axis_v).length() < 1e-12);
        let moved =
            place(&r, &Placement { center: DVec3::new(5.0, 9.0, 3.0), angle_deg: p.angle_deg + 90.0, ..p });
        assert!(
            (moved.center - DVec3::new(5.0, 2.0, 3.0)).length() < 1e-12,
            "centre projected onto the plane"
        );
        assert!((moved.axis_u.dot(r.axis_u)).abs() < 1e-12, "turned by 90°");
        assert!(moved.axis_v.dot(moved.normal.cross(moved.axis_u)) > 0.99, "handedness kept");
        let mut set = ppr_format::ReflectorSet::new("x");
        set.reflectors.push(moved);
        assert!(set.validate().is_ok());
    }

    #[test]
    fn split_with_and_without_region() {
        let r = floor(DVec3::ZERO, DVec2::new(2.0, 1.0));
        let [a, b] = split(&r, None, SplitAxis::U, 0.25).expect("split");
        assert!((a.0.half_extents - DVec2::new(0.5, 1.0)).length() < 1e-12);
        assert!((a.0.center - DVec3::new(-1.5, 0.0, 0.0)).length() < 1e-12);
        assert!((b.0.half_extents - DVec2::new(1.5, 1.0)).length() < 1e-12);
        assert!((b.0.center - DVec3::new(0.5, 0.0, 0.0)).length() < 1e-12);
        // A region covering only the left three quarters: the right part shrinks to it.
        let region = square_region(DVec2::new(-2.0, -1.0), DVec2::new(1.0, 1.0));
        let mut r2 = r.clone();
        r2.coverage = 0.75;
        let [a, b] = split(&r2, Some(&region), SplitAxis::U, 0.5).expect("split");
        assert!((a.0.half_extents - DVec2::new(1.0, 1.0)).length() < 1e-9 && a.0.coverage > 0.999);
        assert!((b.0.half_extents - DVec2::new(0.5, 1.0)).length() < 1e-9, "{:?}", b.0.half_extents);
        assert!((b.0.center - DVec3::new(0.5, 0.0, 0.0)).length() < 1e-9);
        let total =
            a.1.as_ref().map_or(0.0, |g| g.reflective_area) + b.1.as_ref().map_or(0.0, |g| g.reflective_area);
        assert!((total - 6.0).abs() < 1e-9);
        assert!(matches!(split(&r, None, SplitAxis::V, 1.0), Err(EditError::NotSplittable { .. })));
        let narrow = square_region(DVec2::new(-2.0, -1.0), DVec2::new(-1.0, 1.0));
        assert!(matches!(split(&r, Some(&narrow), SplitAxis::U, 0.75), Err(EditError::NotSplittable { .. })));
    }

    #[test]
    fn merge_fits_both_and_refuses_other_planes() {
        let tol = CoplanarTolerance { cos_angle: 1f64.to_radians().cos(), distance: 0.01 };
        let a = floor(DVec3::new(-1.0, 0.0, 0.0), DVec2::new(1.0, 1.0));
        let mut b = floor(DVec3::new(1.0, 0.0, 0.0), DVec2::new(1.0, 1.0));
        b.id = 2;
        let (m, region) = merge(&a, None, &b, None, tol).expect("merge");
        assert!(region.is_none());
        assert!((m.half_extents - DVec2::new(2.0, 1.0)).length() < 1e-9, "{:?}", m.half_extents);
        assert!((m.center - DVec3::ZERO).length() < 1e-9);
        assert!(m.axis_u.dot(a.axis_u) > 0.999 && m.coverage > 0.999 && m.id == a.id);
        let mut up = b.clone();
        up.center.y = 0.5;
        assert!(matches!(merge(&a, None, &up, None, tol), Err(EditError::NotMergeable { .. })));
        let mut wall =
            Reflector::new(3, "wall", ReflectorKind::Opaque, DVec3::ZERO, DVec3::Z, DVec3::X, DVec2::ONE);
        wall.normal = DVec3::Z;
        assert!(matches!(merge(&a, None, &wall, None, tol), Err(EditError::NotMergeable { .. })));
        assert!(matches!(merge(&a, None, &a, None, tol), Err(EditError::NotMergeable { .. })));
    }

    #[test]
    fn refit_shrinks_to_the_region() {
        let mut r = floor(DVec3::ZERO, DVec2::new(3.0, 3.0));
        r.coverage = 2.0 / 36.0;
        let region = square_region(DVec2::new(0.0, 0.0), DVec2::new(2.0, 1.0));
        let fitted = refit(&r, Some(&region)).expect("refit");
        assert!((fitted.half_extents - DVec2::new(1.0, 0.5)).length() < 1e-9, "{:?}", fitted.half_extents);
        assert!((fitted.center - DVec3::new(1.0, 0.0, -0.5)).length() < 1e-9, "{:?}", fitted.center);
        assert!(fitted.coverage > 0.999 && fitted.axis_u.dot(DVec3::X) > 0.999);
        assert!(matches!(refit(&r, None), Err(EditError::NoRegion { .. })));
    }
}
