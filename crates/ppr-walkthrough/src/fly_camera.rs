//! The fly camera: WASD (and Q/E, Space/Ctrl) to move, the mouse to look, the wheel for speed.
//!
//! Yaw and pitch only (no roll); the position is `f64` like `ppr_runtime::Camera`'s, so a
//! level far from the origin flies as smoothly as one at it.

use glam::{DVec3, EulerRot, Quat, Vec3};
use ppr_runtime::{Camera, Projection};

/// Radians of turn per pixel of mouse motion.
pub const LOOK_RADIANS_PER_PIXEL: f32 = 0.0025;
/// Each wheel notch multiplies the speed by this (or divides it).
pub const SPEED_STEP: f64 = 1.25;
/// The speed stays within these bounds, metres per second.
pub const SPEED_RANGE: (f64, f64) = (0.05, 500.0);

/// Which movement keys are held (the window maps its keys to these).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MoveKeys {
    pub forward: bool,
    pub back: bool,
    pub left: bool,
    pub right: bool,
    pub up: bool,
    pub down: bool,
    /// Shift: four times faster while held.
    pub fast: bool,
}

/// A first-person camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyCamera {
    pub position: DVec3,
    /// Turn about world +Y, radians (0 looks down -Z).
    pub yaw: f32,
    /// Up/down, radians, within ±89°.
    pub pitch: f32,
    /// Metres per second.
    pub speed: f64,
    pub projection: Projection,
}

impl FlyCamera {
    /// Starts where `camera` is, looking where it looks (its roll is dropped).
    pub fn from_camera(camera: &Camera, speed: f64) -> Self {
        let f = camera.forward();
        let mut fly =
            Self { position: camera.position, yaw: 0.0, pitch: 0.0, speed, projection: camera.projection };
        fly.yaw = (-f.x).atan2(-f.z);
        fly.pitch = f.y.clamp(-1.0, 1.0).asin();
        fly.clamp_pitch();
        fly
    }

    /// The runtime camera of the current pose.
    pub fn camera(&self) -> Camera {
        Camera { position: self.position, rotation: self.rotation(), projection: self.projection }
    }

    /// World-from-view rotation.
    pub fn rotation(&self) -> Quat {
        Quat::from_euler(EulerRot::YXZ, self.yaw, self.pitch, 0.0)
    }

    /// Turns by a mouse motion of `(dx, dy)` pixels (right and down positive).
    pub fn look(&mut self, dx: f64, dy: f64) {
        self.yaw -= dx as f32 * LOOK_RADIANS_PER_PIXEL;
        self.pitch -= dy as f32 * LOOK_RADIANS_PER_PIXEL;
        self.yaw = self.yaw.rem_euclid(std::f32::consts::TAU);
        self.clamp_pitch();
    }

    /// Changes the speed by wheel notches (positive: faster).
    pub fn scroll(&mut self, notches: f64) {
        let speed = self.speed * SPEED_STEP.powf(notches);
        self.speed = speed.clamp(SPEED_RANGE.0, SPEED_RANGE.1);
    }

    /// Moves for `dt` seconds with `keys` held: along the view direction, sideways, and
    /// straight up or down in world space.
    pub fn advance(&mut self, keys: &MoveKeys, dt: f64) {
        let r = self.rotation();
        let axis = |pos: bool, neg: bool| f32::from(u8::from(pos)) - f32::from(u8::from(neg));
        let dir = r * Vec3::NEG_Z * axis(keys.forward, keys.back)
            + r * Vec3::X * axis(keys.right, keys.left)
            + Vec3::Y * axis(keys.up, keys.down);
        let Some(dir) = dir.try_normalize() else { return };
        let speed = if keys.fast { self.speed * 4.0 } else { self.speed };
        self.position += dir.as_dvec3() * speed * dt.max(0.0);
    }

    fn clamp_pitch(&mut self) {
        let limit = 89f32.to_radians();
        self.pitch = self.pitch.clamp(-limit, limit);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn looking_at(target: DVec3) -> FlyCamera {
        let c = Camera::look_at(DVec3::new(1e6, 2.0, 3.0), target, Vec3::Y, Projection::default());
        FlyCamera::from_camera(&c, 2.0)
    }

    #[test]
    fn keeps_the_view_of_the_camera_it_starts_from() {
        let target = DVec3::new(1e6 + 3.0, 1.0, -1.0);
        let fly = looking_at(target);
        let expected = (target - fly.position).normalize().as_vec3();
        assert!((fly.camera().forward() - expected).length() < 1e-5, "{}", fly.camera().forward());
        assert!((fly.rotation() * Vec3::X).y.abs() < 1e-6, "no roll");
    }

    #[test]
    fn moves_forward_sideways_and_up_at_its_speed() {
        let mut fly = looking_at(DVec3::new(1e6, 2.0, 0.0)); // looks down -Z
        let start = fly.position;
        fly.advance(&MoveKeys { forward: true, ..Default::default() }, 0.5);
        assert!((fly.position - start - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-5);
        fly.advance(&MoveKeys { right: true, up: true, ..Default::default() }, 0.1);
        let step = fly.position - start - DVec3::new(0.0, 0.0, -1.0);
        assert!((step - DVec3::new(1.0, 1.0, 0.0).normalize() * 0.2).length() < 1e-5, "{step}");
        let before = fly.position;
        fly.advance(&MoveKeys { forward: true, back: true, ..Default::default() }, 1.0);
        assert_eq!(fly.position, before, "opposite keys cancel");
    }

    #[test]
    fn pitch_is_clamped_and_speed_follows_the_wheel() {
        let mut fly = looking_at(DVec3::new(1e6, 2.0, 0.0));
        fly.look(0.0, -1e6);
        assert!(fly.pitch <= 89f32.to_radians() + 1e-6);
        fly.scroll(2.0);
        assert!((fly.speed - 2.0 * 1.25 * 1.25).abs() < 1e-9);
        fly.scroll(-1000.0);
        assert_eq!(fly.speed, SPEED_RANGE.0);
    }
}
