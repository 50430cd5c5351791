//! Mirror panels for generated rooms: each panel is a coloured polished quad in the level
//! and the same rectangle in the reflector set, so the set is the geometry, exactly.

use glam::{DVec2, DVec3};
use ppr_format::{Reflector, ReflectorKind, ReflectorSet};
use ppr_testbed::{Level, Material};

use crate::scaling::quad_builder::QuadBuilder;

/// A level and its reflector set built panel by panel.
pub struct MirrorPanels {
    quads: QuadBuilder,
    /// The reflectors added so far, one per panel.
    pub set: ReflectorSet,
}

impl MirrorPanels {
    /// An empty level named `name` in the set.
    pub fn new(name: &str) -> Self {
        Self { quads: QuadBuilder::default(), set: ReflectorSet::new(name) }
    }

    /// Adds the mirror `center ± u ± v` (half vectors, orthogonal), reflecting towards
    /// `u × v`, tinted `color`, named `name`.
    pub fn panel(
        &mut self,
        level: &mut Level,
        name: &str,
        color: [f32; 3],
        center: DVec3,
        u: DVec3,
        v: DVec3,
    ) {
        let slot = self.quads.material(level, Material::polished(name, color));
        self.quads.quad(slot, center, u, v);
        let id = self.set.next_id();
        self.set.reflectors.push(Reflector::new(
            id,
            name,
            ReflectorKind::Opaque,
            center,
            u.cross(v).normalize(),
            u.normalize(),
            DVec2::new(u.length(), v.length()),
        ));
    }

    /// The faces of the axis-aligned box `center ± half`, facing out (a box in the room) or
    /// in (the room itself); `skip_bottom` leaves out the face at the lowest y (a box
    /// standing on the floor). Face `k` gets `color(k)`.
    #[allow(clippy::too_many_arguments)]
    pub fn cuboid(
        &mut self,
        level: &mut Level,
        name: &str,
        center: DVec3,
        half: DVec3,
        inward: bool,
        skip_bottom: bool,
        color: &dyn Fn(usize) -> [f32; 3],
    ) {
        for (k, (n, u, v, label)) in BOX_FACES.into_iter().enumerate() {
            if skip_bottom && n == DVec3::NEG_Y {
                continue;
            }
            let (u, v) = (u * half, v * half);
            // Swapping the axes flips the facing: u × v = n, v × u = −n.
            let (u, v) = if inward { (v, u) } else { (u, v) };
            self.panel(level, &format!("{name} {label}"), color(k), center + n * half, u, v);
        }
    }

    /// Puts the geometry into `level` as one mesh.
    pub fn finish(self, level: &mut Level, mesh_name: &str) -> ReflectorSet {
        self.quads.finish(level, mesh_name);
        self.set
    }
}

/// The outward normal and the two in-plane axes (`u × v = n`) of each face of a box.
const BOX_FACES: [(DVec3, DVec3, DVec3, &str); 6] = [
    (DVec3::X, DVec3::NEG_Z, DVec3::Y, "+x"),
    (DVec3::NEG_X, DVec3::Z, DVec3::Y, "-x"),
    (DVec3::Y, DVec3::X, DVec3::NEG_Z, "+y"),
    (DVec3::NEG_Y, DVec3::X, DVec3::Z, "-y"),
    (DVec3::Z, DVec3::X, DVec3::Y, "+z"),
    (DVec3::NEG_Z, DVec3::NEG_X, DVec3::Y, "-z"),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn room_faces_point_in_and_box_faces_out() {
        let mut level = Level::new();
        let mut p = MirrorPanels::new("t");
        let grey = |_| [0.5; 3];
        p.cuboid(&mut level, "room", DVec3::ZERO, DVec3::new(4.0, 1.5, 3.0), true, false, &grey);
        p.cuboid(&mut level, "box", DVec3::new(1.0, -1.0, 0.0), DVec3::splat(0.5), false, true, &grey);
        let mut set = p.finish(&mut level, "t");
        assert_eq!(set.reflectors.len(), 11);
        for (g, r) in (0..).zip(&mut set.reflectors) {
            r.parallel_group = g;
        }
        set.validate().expect("valid set");
        for r in &set.reflectors[..6] {
            // The room's centre is on every face's reflecting side.
            assert!((DVec3::ZERO - r.center).dot(r.normal) > 0.0, "{}", r.name);
        }
        for r in &set.reflectors[6..] {
            assert!((DVec3::new(1.0, -1.0, 0.0) - r.center).dot(r.normal) < 0.0, "{}", r.name);
            assert!(r.normal != DVec3::NEG_Y, "{}: bottom kept", r.name);
        }
    }
}
