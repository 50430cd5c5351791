//! The invariants of a reflector set, checked field by field.

use std::collections::HashMap;

use glam::DVec3;

use crate::{FORMAT_NAME, FORMAT_VERSION, FormatError, InvalidField, Reflector, ReflectorRef, ReflectorSet};

/// Largest deviation allowed from unit length, and from orthogonality (as a dot product),
/// for `axis_u`, `axis_v` and `normal`.
pub const AXIS_TOLERANCE: f64 = 1e-6;

/// Largest absolute coordinate or extent accepted, in metres (10 000 km).
pub const MAX_COORDINATE: f64 = 1e7;

/// Largest angle, in degrees, between the normal of a reflector and that of the first
/// reflector of its parallel group. The runtime lets only the nearest reflector of a
/// group reflect a pixel, which is right only for reflectors that face the same way; the
/// extractor groups within half of this (its own angle tolerance, 1° by default, at most
/// 2.5°), so that any two members are within it.
pub const PARALLEL_GROUP_MAX_ANGLE_DEG: f64 = 5.0;

impl ReflectorSet {
    /// Checks every invariant of the format.
    ///
    /// # Errors
    /// [`FormatError::WrongFormat`], [`FormatError::UnknownVersion`], or
    /// [`FormatError::Invalid`] naming the first reflector and field that break one.
    pub fn validate(&self) -> Result<(), FormatError> {
        if self.format != FORMAT_NAME {
            return Err(FormatError::WrongFormat { found: format!("{:?}", self.format) });
        }
        if self.version != FORMAT_VERSION {
            return Err(FormatError::UnknownVersion { found: self.version.to_string() });
        }
        let mut ids: HashMap<u32, usize> = HashMap::with_capacity(self.reflectors.len());
        // The first reflector of each parallel group.
        let mut groups: HashMap<u32, usize> = HashMap::new();
        let reference = |index: usize, r: &Reflector| ReflectorRef { index, id: r.id, name: r.name.clone() };
        for (index, r) in self.reflectors.iter().enumerate() {
            let fail = |field: &str, reason: String| {
                FormatError::Invalid(InvalidField {
                    reflector: Some(reference(index, r)),
                    field: field.to_owned(),
                    reason,
                })
            };
            if let Some(first) = ids.insert(r.id, index) {
                return Err(fail("id", format!("id {} is already used by reflectors[{first}]", r.id)));
            }
            check_reflector(r, self.reflectors.len(), index)
                .map_err(|(field, reason)| fail(&field, reason))?;
            let first = *groups.entry(r.parallel_group).or_insert(index);
            // Both normals are finite and unit (checked above), so the angle is finite.
            let angle = angle_deg(r.normal, self.reflectors[first].normal);
            if angle > PARALLEL_GROUP_MAX_ANGLE_DEG {
                return Err(fail(
                    "parallel_group",
                    format!(
                        "group {} also holds {}, whose normal is {angle:.2}° from this one's \
                         (at most {PARALLEL_GROUP_MAX_ANGLE_DEG}°): reflectors facing other ways \
                         need groups of their own",
                        r.parallel_group,
                        reference(first, &self.reflectors[first]),
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Gives every reflector a parallel group: reflectors whose normals are within half of
    /// [`PARALLEL_GROUP_MAX_ANGLE_DEG`] of a group's first normal join it, in list order
    /// (what the extractor does; for sets made by hand or by tools other than it).
    pub fn assign_parallel_groups(&mut self) {
        let normals: Vec<DVec3> = self.reflectors.iter().map(|r| r.normal).collect();
        let cos = (0.5 * PARALLEL_GROUP_MAX_ANGLE_DEG).to_radians().cos();
        for (r, g) in self.reflectors.iter_mut().zip(parallel_groups(&normals, cos)) {
            r.parallel_group = g;
        }
    }
}

/// Group number of each normal, in order of first appearance: a normal joins the first
/// group whose first normal it is within `cos_angle` of (oriented: a floor and a ceiling
/// are in different groups).
pub fn parallel_groups(normals: &[DVec3], cos_angle: f64) -> Vec<u32> {
    let mut reps: Vec<DVec3> = Vec::new();
    normals
        .iter()
        .map(|n| match reps.iter().position(|r| r.dot(*n) >= cos_angle) {
            Some(g) => g as u32,
            None => {
                reps.push(*n);
                (reps.len() - 1) as u32
            }
        })
        .collect()
}

/// Angle between two unit vectors, degrees.
fn angle_deg(a: DVec3, b: DVec3) -> f64 {
    // atan2 of the cross and dot products: accurate for small angles, unlike acos.
    a.cross(b).length().atan2(a.dot(b)).to_degrees()
}

fn check_reflector(r: &Reflector, count: usize, index: usize) -> Result<(), (String, String)> {
    let err = |field: &str, reason: String| Err((field.to_owned(), reason));
    if !r.center.is_finite() {
        return err("center", format!("not finite: {}", show(r.center)));
    }
    if r.center.abs().max_element() > MAX_COORDINATE {
        return err("center", format!("{} is more than {MAX_COORDINATE} m from the origin", show(r.center)));
    }
    for (field, axis) in [("axis_u", r.axis_u), ("axis_v", r.axis_v), ("normal", r.normal)] {
        if !axis.is_finite() {
            return err(field, format!("not finite: {}", show(axis)));
        }
        let len = axis.length();
        if (len - 1.0).abs() > AXIS_TOLERANCE {
            return err(field, format!("not unit length: |{field}| = {len}"));
        }
    }
    for (field, a, b, other) in [
        ("axis_v", r.axis_u, r.axis_v, "axis_u"),
        ("normal", r.normal, r.axis_u, "axis_u"),
        ("normal", r.normal, r.axis_v, "axis_v"),
    ] {
        let d = a.dot(b);
        if d.abs() > AXIS_TOLERANCE {
            return err(field, format!("not orthogonal to `{other}` (dot product {d})"));
        }
    }
    for (axis, e) in [("u", r.half_extents.x), ("v", r.half_extents.y)] {
        if !(e.is_finite() && e > 0.0 && e <= MAX_COORDINATE) {
            return err(
                "half_extents",
                format!(
                    "half extent along {axis} is {e}; it must be finite, positive and at most {MAX_COORDINATE}"
                ),
            );
        }
    }
    if !(r.coverage.is_finite() && (0.0..=1.0).contains(&r.coverage)) {
        return err("coverage", format!("{} is not in [0, 1]", r.coverage));
    }
    if !(r.roughness.is_finite() && (0.0..=1.0).contains(&r.roughness)) {
        return err("roughness", format!("{} is not in [0, 1] (0 is a mirror, 1 fully rough)", r.roughness));
    }
    let mut seen = vec![false; count];
    for (k, &o) in r.occluders.iter().enumerate() {
        let field = format!("occluders[{k}]");
        let Some(slot) = seen.get_mut(o as usize) else {
            return err(&field, format!("index {o} is out of range (the set has {count} reflectors)"));
        };
        if o as usize == index {
            return err(&field, format!("index {o} is the reflector itself"));
        }
        if std::mem::replace(slot, true) {
            return err(&field, format!("index {o} is listed twice"));
        }
    }
    Ok(())
}

fn show(v: DVec3) -> String {
    format!("[{}, {}, {}]", v.x, v.y, v.z)
}
