//! Platform-independent trigonometry and rotations, so the level is the same bytes everywhere.
//!
//! `f64::sin` and friends call the platform's maths library, whose last bit may differ
//! between operating systems; that would make the committed `.glb` differ from a fresh
//! run on another machine. Everything here uses only `+ - * /` and `sqrt`, which IEEE 754
//! rounds exactly, and glam's `f64` types, which are plain scalar code.

use glam::{DMat3, DQuat, DVec3};

/// Sine and cosine of an angle in degrees (Taylor series after reduction to [-180°, 180°]).
pub fn sin_cos_degrees(degrees: f64) -> (f64, f64) {
    let mut reduced = degrees % 360.0;
    if reduced > 180.0 {
        reduced -= 360.0;
    } else if reduced < -180.0 {
        reduced += 360.0;
    }
    let x = reduced * (std::f64::consts::PI / 180.0);
    let x2 = x * x;
    // Terms x^n / n!, built one from the previous; 30 terms reach 1e-17 for |x| <= pi.
    let mut sin = 0.0;
    let mut cos = 0.0;
    let mut sin_term = x;
    let mut cos_term = 1.0;
    for n in 0..30 {
        sin += sin_term;
        cos += cos_term;
        let k = f64::from(2 * n + 2);
        sin_term = -sin_term * x2 / (k * (k + 1.0));
        cos_term = -cos_term * x2 / ((k - 1.0) * k);
    }
    (sin, cos)
}

/// Rotation of `degrees` around the +X axis (right-handed).
pub fn rotation_x_degrees(degrees: f64) -> DQuat {
    let (s, c) = sin_cos_degrees(degrees * 0.5);
    DQuat::from_xyzw(s, 0.0, 0.0, c)
}

/// Rotation of `degrees` around the +Y axis (right-handed).
pub fn rotation_y_degrees(degrees: f64) -> DQuat {
    let (s, c) = sin_cos_degrees(degrees * 0.5);
    DQuat::from_xyzw(0.0, s, 0.0, c)
}

/// The orientation of a glTF camera node at `eye` looking at `target` (+Y up):
/// glTF cameras look along their local -Z with local +Y up.
pub fn look_at_rotation(eye: DVec3, target: DVec3) -> DQuat {
    let forward = (target - eye).normalize();
    let right = forward.cross(DVec3::Y).normalize();
    let up = right.cross(forward);
    DQuat::from_mat3(&DMat3::from_cols(right, up, -forward)).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_platform_within_rounding() {
        for tenth in -7200..=7200 {
            let degrees = f64::from(tenth) * 0.1;
            let (s, c) = sin_cos_degrees(degrees);
            let (s_ref, c_ref) = degrees.to_radians().sin_cos();
            assert!((s - s_ref).abs() < 1e-14 && (c - c_ref).abs() < 1e-14, "{degrees}: {s} {c}");
        }
    }

    #[test]
    fn look_at_points_minus_z_at_the_target() {
        let eye = DVec3::new(1.0, 2.0, 3.0);
        let target = DVec3::new(-4.0, 0.5, -2.0);
        let rotation = look_at_rotation(eye, target);
        let forward = rotation * DVec3::NEG_Z;
        assert!((forward - (target - eye).normalize()).length() < 1e-12);
        assert!((rotation * DVec3::X).y.abs() < 1e-12, "camera must not roll");
    }
}
