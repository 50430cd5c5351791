//! The viewport's camera: orbit (around a target) and fly (free position), framing, and
//! the conversions between world points, screen pixels and picking rays.

use glam::{DVec3, Vec2, Vec3, Vec4};
use ppr_runtime::{Camera, Projection};

/// How mouse and keys move the camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum CameraMode {
    /// Drag to turn around the target, scroll to zoom, right-drag to pan.
    #[default]
    Orbit,
    /// Drag to look around, W/A/S/D/Q/E to move.
    Fly,
}

/// A camera that mouse and keys steer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraRig {
    /// Orbit or fly.
    pub mode: CameraMode,
    /// What the orbit camera turns around.
    pub target: DVec3,
    /// Distance from the target (orbit).
    pub distance: f64,
    /// Position (fly; kept in step with orbit so switching does not jump).
    pub position: DVec3,
    /// Heading, radians (0 looks down −Z).
    pub yaw: f64,
    /// Elevation, radians (positive looks up).
    pub pitch: f64,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    /// Scale of the scene, metres: sets the near/far planes and speeds.
    pub scene_size: f64,
}

impl Default for CameraRig {
    fn default() -> Self {
        let mut rig = Self {
            mode: CameraMode::Orbit,
            target: DVec3::ZERO,
            distance: 10.0,
            position: DVec3::ZERO,
            yaw: 0.5,
            pitch: -0.45,
            fov_y: 60f32.to_radians(),
            scene_size: 10.0,
        };
        rig.sync_position();
        rig
    }
}

impl CameraRig {
    /// Unit view direction.
    pub fn forward(&self) -> DVec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        DVec3::new(-sy * cp, sp, -cy * cp)
    }

    /// Where the camera is.
    pub fn eye(&self) -> DVec3 {
        match self.mode {
            CameraMode::Orbit => self.target - self.forward() * self.distance,
            CameraMode::Fly => self.position,
        }
    }

    fn sync_position(&mut self) {
        self.position = self.target - self.forward() * self.distance;
    }

    /// Switches mode without moving the view.
    pub fn set_mode(&mut self, mode: CameraMode) {
        if mode == self.mode {
            return;
        }
        match mode {
            CameraMode::Fly => self.position = self.eye(),
            CameraMode::Orbit => self.target = self.position + self.forward() * self.distance,
        }
        self.mode = mode;
    }

    /// The runtime camera (standard depth, near and far from the scene size).
    pub fn camera(&self) -> Camera {
        let near = (self.scene_size * 1e-3).clamp(1e-4, 0.1) as f32;
        let far = (self.scene_size * 20.0 + self.distance * 2.0) as f32;
        let projection = Projection { fov_y: self.fov_y, near, far: Some(far), ..Projection::default() };
        let eye = self.eye();
        Camera::look_at(eye, eye + self.forward(), Vec3::Y, projection)
    }

    /// Turns the view by a mouse movement in pixels.
    pub fn rotate(&mut self, delta: Vec2) {
        self.yaw -= f64::from(delta.x) * 0.008;
        self.pitch = (self.pitch - f64::from(delta.y) * 0.008).clamp(-1.55, 1.55);
        // Orbit turns around the target; fly turns in place.
        if self.mode == CameraMode::Orbit {
            self.sync_position();
        }
    }

    /// Moves the view sideways and up by a mouse movement in pixels (`height`: viewport height).
    pub fn pan(&mut self, delta: Vec2, height: f32) {
        let f = self.forward();
        let right = f.cross(DVec3::Y).normalize_or(DVec3::X);
        let up = right.cross(f);
        let scale = self.distance * 2.0 * (f64::from(self.fov_y) * 0.5).tan() / f64::from(height.max(1.0));
        let shift = (-right * f64::from(delta.x) + up * f64::from(delta.y)) * scale;
        self.target += shift;
        self.position += shift;
    }

    /// Zooms by scroll amount (orbit: distance; fly: moves forward).
    pub fn zoom(&mut self, scroll: f32) {
        let factor = (-f64::from(scroll) * 0.002).exp();
        match self.mode {
            CameraMode::Orbit => {
                self.distance =
                    (self.distance * factor).clamp(self.scene_size * 1e-3, self.scene_size * 50.0);
                self.sync_position();
            }
            CameraMode::Fly => self.position += self.forward() * (1.0 - factor) * self.distance,
        }
    }

    /// Moves the fly camera by `local` (x right, y up, z forward) for `seconds`.
    pub fn fly(&mut self, local: DVec3, seconds: f64) {
        let f = self.forward();
        let right = f.cross(DVec3::Y).normalize_or(DVec3::X);
        let speed = self.scene_size * 0.25;
        let step = (right * local.x + DVec3::Y * local.y + f * local.z) * speed * seconds;
        self.position += step;
        self.target += step;
    }

    /// Looks from `eye` along `forward` (orbiting a target `distance` ahead).
    pub fn look_from(&mut self, eye: DVec3, forward: DVec3, distance: f64) {
        let f = forward.normalize_or(DVec3::NEG_Z);
        self.pitch = f.y.clamp(-1.0, 1.0).asin().clamp(-1.55, 1.55);
        self.yaw = (-f.x).atan2(-f.z);
        self.distance = distance.max(1e-3);
        self.position = eye;
        self.target = eye + self.forward() * self.distance;
    }

    /// Frames the box `lo..hi`: looks at its centre from far enough to see all of it.
    pub fn frame_box(&mut self, lo: DVec3, hi: DVec3) {
        let radius = ((hi - lo).length() * 0.5).max(1e-3);
        self.target = (lo + hi) * 0.5;
        self.distance = radius / (f64::from(self.fov_y) * 0.5).sin() * 1.05;
        if self.mode == CameraMode::Fly {
            self.position = self.target - self.forward() * self.distance;
        }
        self.sync_position();
    }

    /// Screen position (pixels from the top-left of a `size` viewport) of a world point,
    /// with its clip-space `w`; `None` behind the near plane.
    pub fn project(&self, world: DVec3, size: Vec2) -> Option<Vec2> {
        let clip = self.clip(world, size);
        (clip.z >= 0.0 && clip.w > 0.0).then(|| clip_to_screen(clip, size))
    }

    /// Clip-space position of a world point.
    pub fn clip(&self, world: DVec3, size: Vec2) -> Vec4 {
        let camera = self.camera();
        camera.project_relative(camera.relative(world), size.x / size.y.max(1.0))
    }

    /// The ray (origin, unit direction) from the camera through pixel `pixel`.
    pub fn ray(&self, pixel: Vec2, size: Vec2) -> (DVec3, DVec3) {
        let camera = self.camera();
        let inverse = camera.clip_from_relative(size.x / size.y.max(1.0)).inverse();
        let ndc = Vec2::new(2.0 * pixel.x / size.x.max(1.0) - 1.0, 1.0 - 2.0 * pixel.y / size.y.max(1.0));
        let near = inverse.project_point3(ndc.extend(0.0));
        let far = inverse.project_point3(ndc.extend(0.5));
        let dir = (far - near).as_dvec3().normalize_or(self.forward());
        (camera.position + near.as_dvec3(), dir)
    }
}

/// Pixels from a clip-space position (after the divide).
pub fn clip_to_screen(clip: Vec4, size: Vec2) -> Vec2 {
    let ndc = clip.truncate() / clip.w;
    Vec2::new((ndc.x * 0.5 + 0.5) * size.x, (0.5 - ndc.y * 0.5) * size.y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_through_a_projected_point_hits_it() {
        let mut rig = CameraRig::default();
        rig.frame_box(DVec3::new(-8.0, 0.0, -6.0), DVec3::new(8.0, 5.0, 6.0));
        let size = Vec2::new(800.0, 500.0);
        let p = DVec3::new(1.0, 0.5, -2.0);
        let pixel = rig.project(p, size).expect("in front");
        let (o, d) = rig.ray(pixel, size);
        let closest = o + d * (p - o).dot(d);
        assert!((closest - p).length() < 1e-3, "{closest} vs {p}");
    }

    #[test]
    fn look_from_reproduces_eye_and_direction() {
        let mut rig = CameraRig::default();
        let f = DVec3::new(0.3, -0.2, -1.0).normalize();
        rig.look_from(DVec3::new(1.0, 2.0, 5.0), f, 4.0);
        assert!(
            (rig.forward() - f).length() < 1e-12 && (rig.eye() - DVec3::new(1.0, 2.0, 5.0)).length() < 1e-9
        );
    }

    #[test]
    fn switching_modes_keeps_the_view() {
        let mut rig = CameraRig::default();
        rig.rotate(Vec2::new(30.0, -12.0));
        let (eye, f) = (rig.eye(), rig.forward());
        rig.set_mode(CameraMode::Fly);
        assert!((rig.eye() - eye).length() < 1e-9 && (rig.forward() - f).length() < 1e-12);
        rig.fly(DVec3::Z, 1.0);
        rig.set_mode(CameraMode::Orbit);
        assert!((rig.eye() - (eye + f * rig.scene_size * 0.25)).length() < 1e-9);
    }
}
