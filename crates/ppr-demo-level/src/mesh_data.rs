//! `MeshData`: one triangle list (positions, normals, texture coordinates, indices) and the shapes the level is made of.

use glam::{DVec2, DVec3};

use crate::exact_trig::sin_cos_degrees;

/// A face of an axis-aligned box, named by its outward normal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoxFace {
    PosX,
    NegX,
    PosY,
    NegY,
    PosZ,
    NegZ,
}

impl BoxFace {
    /// All six faces.
    pub const ALL: [BoxFace; 6] =
        [BoxFace::PosX, BoxFace::NegX, BoxFace::PosY, BoxFace::NegY, BoxFace::PosZ, BoxFace::NegZ];
    /// The four side faces (no top, no bottom).
    pub const SIDES: [BoxFace; 4] = [BoxFace::PosX, BoxFace::NegX, BoxFace::PosZ, BoxFace::NegZ];
    /// Everything but the bottom (for boxes standing on the floor).
    pub const ALL_BUT_BOTTOM: [BoxFace; 5] =
        [BoxFace::PosX, BoxFace::NegX, BoxFace::PosY, BoxFace::PosZ, BoxFace::NegZ];
}

/// A triangle list in local space. Triangles are counter-clockwise seen from the side their
/// normals point to (glTF's front face). Texture coordinates are in metres along the
/// surface divided by the `uv_metres` the shape was made with (so a repeating texture
/// keeps its scale).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    pub positions: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    pub uvs: Vec<DVec2>,
    pub indices: Vec<u32>,
}

impl MeshData {
    /// Appends `other`, renumbering its indices.
    pub fn append(&mut self, other: &MeshData) {
        let base = u32::try_from(self.positions.len()).expect("meshes of the demo level are small");
        self.positions.extend_from_slice(&other.positions);
        self.normals.extend_from_slice(&other.normals);
        self.uvs.extend_from_slice(&other.uvs);
        self.indices.extend(other.indices.iter().map(|i| i + base));
    }

    /// Several shapes merged into one triangle list.
    pub fn merged(parts: &[MeshData]) -> MeshData {
        let mut merged = MeshData::default();
        for part in parts {
            merged.append(part);
        }
        merged
    }

    fn push_vertex(&mut self, position: DVec3, normal: DVec3, uv: DVec2) -> u32 {
        let index = u32::try_from(self.positions.len()).expect("meshes of the demo level are small");
        self.positions.push(position);
        self.normals.push(normal);
        self.uvs.push(uv);
        index
    }

    /// A parallelogram (a rectangle when the edges are orthogonal) with corners `origin`,
    /// `origin + edge_u`, `origin + edge_u + edge_v`, `origin + edge_v`; its front face
    /// and normal point along `edge_u × edge_v`.
    pub fn quad(origin: DVec3, edge_u: DVec3, edge_v: DVec3, uv_metres: f64) -> MeshData {
        let normal = edge_u.cross(edge_v).normalize();
        let (len_u, len_v) = (edge_u.length() / uv_metres, edge_v.length() / uv_metres);
        let mut mesh = MeshData::default();
        let a = mesh.push_vertex(origin, normal, DVec2::new(0.0, len_v));
        let b = mesh.push_vertex(origin + edge_u, normal, DVec2::new(len_u, len_v));
        let c = mesh.push_vertex(origin + edge_u + edge_v, normal, DVec2::new(len_u, 0.0));
        let d = mesh.push_vertex(origin + edge_v, normal, DVec2::new(0.0, 0.0));
        mesh.indices.extend_from_slice(&[a, b, c, a, c, d]);
        mesh
    }

    /// The chosen faces of the axis-aligned box `min..max`, each facing outwards.
    pub fn cuboid(min: DVec3, max: DVec3, faces: &[BoxFace], uv_metres: f64) -> MeshData {
        let size = max - min;
        let (dx, dy, dz) = (DVec3::X * size.x, DVec3::Y * size.y, DVec3::Z * size.z);
        let mut mesh = MeshData::default();
        for face in faces {
            let (origin, edge_u, edge_v) = match face {
                BoxFace::PosX => (DVec3::new(max.x, min.y, max.z), -dz, dy),
                BoxFace::NegX => (min, dz, dy),
                BoxFace::PosY => (DVec3::new(min.x, max.y, max.z), dx, -dz),
                BoxFace::NegY => (min, dx, dz),
                BoxFace::PosZ => (DVec3::new(min.x, min.y, max.z), dx, dy),
                BoxFace::NegZ => (DVec3::new(max.x, min.y, min.z), -dx, dy),
            };
            mesh.append(&MeshData::quad(origin, edge_u, edge_v, uv_metres));
        }
        mesh
    }

    /// An upright cylinder standing on the origin: `segments` flat-ish sides with smooth
    /// normals plus a top cap.
    pub fn cylinder(radius: f64, height: f64, segments: u32, uv_metres: f64) -> MeshData {
        let mut mesh = MeshData::default();
        let circumference_step = 2.0 * std::f64::consts::PI * radius / f64::from(segments) / uv_metres;
        for i in 0..=segments {
            let (sin, cos) = sin_cos_degrees(360.0 * f64::from(i) / f64::from(segments));
            // Counter-clockwise seen from +Y: angle runs from +X towards -Z.
            let outward = DVec3::new(cos, 0.0, -sin);
            let u = f64::from(i) * circumference_step;
            mesh.push_vertex(outward * radius, outward, DVec2::new(u, height / uv_metres));
            mesh.push_vertex(outward * radius + DVec3::Y * height, outward, DVec2::new(u, 0.0));
        }
        for i in 0..segments {
            let (b0, t0, b1, t1) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
            mesh.indices.extend_from_slice(&[b0, b1, t1, b0, t1, t0]);
        }
        let cap_radii = vec![radius; segments as usize];
        let mut cap = MeshData::radial_polygon(&cap_radii, DVec2::ONE, uv_metres);
        for position in &mut cap.positions {
            position.y = height;
        }
        mesh.append(&cap);
        mesh
    }

    /// A star-shaped polygon in the XZ plane facing +Y, fan-triangulated from the origin:
    /// vertex `i` lies at angle `360° · i / n` (from +X towards -Z) and distance
    /// `radii[i]`, with the polygon then scaled by `scale` (x, z).
    pub fn radial_polygon(radii: &[f64], scale: DVec2, uv_metres: f64) -> MeshData {
        let mut mesh = MeshData::default();
        let centre = mesh.push_vertex(DVec3::ZERO, DVec3::Y, DVec2::ZERO);
        let count = u32::try_from(radii.len()).expect("polygons of the demo level are small");
        for (i, radius) in (0..count).zip(radii) {
            let (sin, cos) = sin_cos_degrees(360.0 * f64::from(i) / f64::from(count));
            let position = DVec3::new(cos * radius * scale.x, 0.0, -sin * radius * scale.y);
            mesh.push_vertex(position, DVec3::Y, DVec2::new(position.x, position.z) / uv_metres);
        }
        for i in 0..count {
            mesh.indices.extend_from_slice(&[centre, 1 + i, 1 + (i + 1) % count]);
        }
        mesh
    }

    /// A horizontal grid facing +Y made of the unit-sized `cells` (x, z cell coordinates,
    /// cell `(i, j)` spans `[i, i+1] × [j, j+1]` times `cell_size`). Vertices are shared
    /// between neighbouring cells, across any internal edge. Cell `k` owns triangles
    /// `2k` and `2k + 1`.
    pub fn cell_grid(cells: &[(i32, i32)], cell_size: f64, uv_metres: f64) -> MeshData {
        let mut mesh = MeshData::default();
        let mut corner_index: Vec<((i32, i32), u32)> = Vec::new();
        let mut vertex_at = |mesh: &mut MeshData, corner: (i32, i32)| -> u32 {
            if let Some((_, index)) = corner_index.iter().find(|(c, _)| *c == corner) {
                return *index;
            }
            let position = DVec3::new(f64::from(corner.0), 0.0, f64::from(corner.1)) * cell_size;
            let index = mesh.push_vertex(position, DVec3::Y, DVec2::new(position.x, position.z) / uv_metres);
            corner_index.push((corner, index));
            index
        };
        for &(i, j) in cells {
            // Seen from +Y with x right and z down, counter-clockwise is (i,j) -> (i,j+1) -> (i+1,j+1).
            let a = vertex_at(&mut mesh, (i, j));
            let b = vertex_at(&mut mesh, (i, j + 1));
            let c = vertex_at(&mut mesh, (i + 1, j + 1));
            let d = vertex_at(&mut mesh, (i + 1, j));
            mesh.indices.extend_from_slice(&[a, b, c, a, c, d]);
        }
        mesh
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every triangle's winding agrees with its vertex normals.
    fn check_winding(mesh: &MeshData) {
        for triangle in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[triangle[k] as usize]);
            let geometric = (b - a).cross(c - a);
            assert!(geometric.length() > 0.0, "degenerate triangle {triangle:?}");
            for &k in triangle {
                assert!(geometric.normalize().dot(mesh.normals[k as usize]) > 0.5, "{triangle:?}");
            }
        }
    }

    #[test]
    fn shapes_face_their_normals() {
        check_winding(&MeshData::quad(DVec3::ZERO, DVec3::X, DVec3::Y, 1.0));
        check_winding(&MeshData::cuboid(-DVec3::ONE, DVec3::new(2.0, 3.0, 4.0), &BoxFace::ALL, 1.0));
        check_winding(&MeshData::cylinder(0.3, 5.0, 12, 1.0));
        check_winding(&MeshData::radial_polygon(&[1.0, 1.2, 0.8, 1.1, 0.9], DVec2::new(2.0, 1.0), 1.0));
        check_winding(&MeshData::cell_grid(&[(0, 0), (1, 0), (0, -1)], 1.0, 1.0));
    }

    #[test]
    fn cell_grid_shares_vertices_across_internal_edges() {
        let grid = MeshData::cell_grid(&[(0, 0), (1, 0), (2, 0), (0, 1)], 1.0, 1.0);
        assert_eq!(grid.indices.len(), 3 * 8);
        assert_eq!(grid.positions.len(), 10);
    }
}
