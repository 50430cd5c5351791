//! The invariants of a reflector set, checked field by field.

use std::collections::HashMap;

use glam::DVec3;

use crate::{FORMAT_NAME, FORMAT_VERSION, FormatError, InvalidField, Reflector, ReflectorRef, ReflectorSet};

/// Largest deviation allowed from unit length, and from orthogonality (as a dot product),
/// for `axis_u`, `axis_v` and `normal`.
pub const AXIS_TOLERANCE: f64 = 1e-6;

/// Largest absolute coordinate or extent accepted, in metres (10 000 km).
pub const MAX_COORDINATE: f64 = 1e7;

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
        for (index, r) in self.reflectors.iter().enumerate() {
            let fail = |field: &str, reason: String| {
                FormatError::Invalid(InvalidField {
                    reflector: Some(ReflectorRef { index, id: r.id, name: r.name.clone() }),
                    field: field.to_owned(),
                    reason,
                })
            };
            if let Some(first) = ids.insert(r.id, index) {
                return Err(fail("id", format!("id {} is already used by reflectors[{first}]", r.id)));
            }
            check_reflector(r, self.reflectors.len(), index)
                .map_err(|(field, reason)| fail(&field, reason))?;
        }
        Ok(())
    }
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
