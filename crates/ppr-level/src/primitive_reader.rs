//! One glTF primitive read into mesh-space geometry: positions (`f64`), the triangle
//! list (strips and fans converted), normals (the file's or flat), UV set 0 and skin
//! weights.

use std::path::Path;

use glam::{DVec3, Vec2, Vec3};

use crate::LoadError;
use crate::accessor::{read_accessor, read_indices};
use crate::buffers::BufferData;

/// Per vertex, the (joint, weight) pairs of a skinned primitive.
pub(crate) type SkinWeights = Vec<Vec<(usize, f64)>>;

/// One primitive's geometry in its mesh's space, shared by every instance.
pub(crate) struct PrimitiveGeometry {
    pub positions: Vec<DVec3>,
    pub normals: Vec<Vec3>,
    pub uvs: Vec<Vec2>,
    /// Triangle list.
    pub indices: Vec<u32>,
    pub material: usize,
    /// Per vertex, (joint, weight) pairs when the primitive is skinned.
    pub skin: Option<SkinWeights>,
}

/// Reads glTF primitives of one document.
pub(crate) struct PrimitiveReader<'a> {
    pub path: &'a Path,
    pub data: &'a BufferData,
    pub default_material: usize,
}

impl PrimitiveReader<'_> {
    /// The primitive's geometry; `None` for points and lines.
    pub(crate) fn read(
        &self,
        mesh: &gltf::Mesh,
        prim: &gltf::Primitive,
    ) -> Result<Option<PrimitiveGeometry>, LoadError> {
        use gltf::mesh::Mode;
        let mode = prim.mode();
        if matches!(mode, Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip) {
            return Ok(None);
        }
        let field = format!("meshes[{}].primitives[{}]", mesh.index(), prim.index());
        let Some(pos_acc) = prim.get(&gltf::Semantic::Positions) else {
            return Err(LoadError::Invalid {
                path: self.path.to_owned(),
                field: format!("{field}.attributes"),
                reason: "has no POSITION".into(),
            });
        };
        let values = read_accessor(self.path, self.data, &pos_acc)?;
        if values.components != 3 {
            return Err(self.bad_accessor(pos_acc.index(), "POSITION must be VEC3"));
        }
        let mut positions = Vec::with_capacity(values.len());
        for k in 0..values.len() {
            let v = values.get(k);
            let p = DVec3::new(v[0], v[1], v[2]);
            if !p.is_finite() {
                return Err(LoadError::NonFinitePosition {
                    path: self.path.to_owned(),
                    field: format!("accessors[{}]", pos_acc.index()),
                    detail: format!("at vertex {k} of {field}: [{}, {}, {}]", v[0], v[1], v[2]),
                });
            }
            positions.push(p);
        }
        drop(values);
        let n = positions.len();
        let indices: Vec<u32> = match prim.indices() {
            Some(acc) => read_indices(self.path, self.data, &acc, n)?,
            None => {
                let n = u32::try_from(n)
                    .map_err(|_| self.bad_accessor(pos_acc.index(), "more than 2^32 vertices"))?;
                (0..n).collect()
            }
        };
        let indices = assemble_triangles(mode, &indices);
        let normals = self.read_vec(prim, &gltf::Semantic::Normals, 3, n)?;
        let uvs = self.read_vec(prim, &gltf::Semantic::TexCoords(0), 2, n)?;
        let skin = self.read_skin_weights(prim, n)?;
        let material = prim.material().index().unwrap_or(self.default_material);
        let mut g = PrimitiveGeometry {
            positions,
            normals: Vec::new(),
            uvs: uvs
                .map(|v| v.chunks_exact(2).map(|c| Vec2::new(c[0] as f32, c[1] as f32)).collect())
                .unwrap_or_default(),
            indices,
            material,
            skin,
        };
        match normals {
            Some(v) => {
                g.normals = v
                    .chunks_exact(3)
                    .map(|c| {
                        Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32).try_normalize().unwrap_or(Vec3::Y)
                    })
                    .collect();
            }
            None => flat_normals(&mut g),
        }
        Ok(Some(g))
    }

    fn bad_accessor(&self, index: usize, reason: &str) -> LoadError {
        LoadError::BadAccessor {
            path: self.path.to_owned(),
            field: format!("accessors[{index}]"),
            reason: reason.into(),
        }
    }

    /// A per-vertex attribute of `components` components, one element per vertex.
    fn read_vec(
        &self,
        prim: &gltf::Primitive,
        semantic: &gltf::Semantic,
        components: usize,
        n: usize,
    ) -> Result<Option<Vec<f64>>, LoadError> {
        let Some(acc) = prim.get(semantic) else { return Ok(None) };
        let values = read_accessor(self.path, self.data, &acc)?;
        if values.components != components || values.len() != n {
            return Err(self.bad_accessor(
                acc.index(),
                &format!(
                    "{} must have {components} components and {n} elements like POSITION, not {} and {}",
                    semantic.to_string(),
                    values.components,
                    values.len()
                ),
            ));
        }
        Ok(Some(values.values))
    }

    fn read_skin_weights(&self, prim: &gltf::Primitive, n: usize) -> Result<Option<SkinWeights>, LoadError> {
        let mut out: Option<SkinWeights> = None;
        for set in 0.. {
            let (Some(j), Some(w)) =
                (prim.get(&gltf::Semantic::Joints(set)), prim.get(&gltf::Semantic::Weights(set)))
            else {
                break;
            };
            let jv = read_accessor(self.path, self.data, &j)?;
            let wv = read_accessor(self.path, self.data, &w)?;
            if jv.len() != n || wv.len() != n || jv.components != wv.components {
                return Err(self.bad_accessor(w.index(), "JOINTS and WEIGHTS do not match POSITION"));
            }
            let per = out.get_or_insert_with(|| vec![Vec::new(); n]);
            for (k, slot) in per.iter_mut().enumerate() {
                for (&joint, &weight) in jv.get(k).iter().zip(wv.get(k)) {
                    if weight != 0.0 {
                        slot.push((joint as usize, weight));
                    }
                }
            }
        }
        Ok(out)
    }
}

/// Flat normals (glTF §3.7.2.1 for primitives without `NORMAL`): the triangles are
/// unwelded, each corner a vertex of its own carrying its face's normal.
fn flat_normals(g: &mut PrimitiveGeometry) {
    let corners = std::mem::take(&mut g.indices);
    let pick = |i: &u32| *i as usize;
    g.positions = corners.iter().map(|i| g.positions[pick(i)]).collect();
    if !g.uvs.is_empty() {
        g.uvs = corners.iter().map(|i| g.uvs[pick(i)]).collect();
    }
    if let Some(skin) = &mut g.skin {
        *skin = corners.iter().map(|i| skin[pick(i)].clone()).collect();
    }
    g.normals = g
        .positions
        .chunks_exact(3)
        .flat_map(|t| {
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero().as_vec3();
            [if n == Vec3::ZERO { Vec3::Y } else { n }; 3]
        })
        .collect();
    g.indices = (0..g.positions.len() as u32).collect();
}

/// Triangle lists from triangle lists, strips and fans (glTF 2.0 §3.7.2.1).
fn assemble_triangles(mode: gltf::mesh::Mode, idx: &[u32]) -> Vec<u32> {
    use gltf::mesh::Mode;
    match mode {
        Mode::TriangleStrip => (0..idx.len().saturating_sub(2))
            .flat_map(|i| {
                if i % 2 == 0 { [idx[i], idx[i + 1], idx[i + 2]] } else { [idx[i], idx[i + 2], idx[i + 1]] }
            })
            .collect(),
        Mode::TriangleFan => {
            (1..idx.len().saturating_sub(1)).flat_map(|i| [idx[i], idx[i + 1], idx[0]]).collect()
        }
        _ => idx[..idx.len() - idx.len() % 3].to_vec(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gltf::mesh::Mode;

    #[test]
    fn assembles_strips_and_fans_with_consistent_winding() {
        assert_eq!(assemble_triangles(Mode::Triangles, &[0, 1, 2, 3, 4, 5, 6]), vec![0, 1, 2, 3, 4, 5]);
        assert_eq!(assemble_triangles(Mode::TriangleStrip, &[0, 1, 2, 3]), vec![0, 1, 2, 1, 3, 2]);
        assert_eq!(assemble_triangles(Mode::TriangleFan, &[0, 1, 2, 3]), vec![1, 2, 0, 2, 3, 0]);
        assert!(assemble_triangles(Mode::TriangleStrip, &[0, 1]).is_empty());
    }

    #[test]
    fn flat_normals_unweld_and_face_each_triangle() {
        // A roof: two triangles sharing an edge, tilted ±45°.
        let mut g = PrimitiveGeometry {
            positions: vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(0.0, 0.0, 1.0),
                DVec3::new(1.0, 1.0, 1.0),
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::new(2.0, 0.0, 1.0),
            ],
            normals: Vec::new(),
            uvs: (0..6).map(|i| Vec2::splat(i as f32)).collect(),
            indices: vec![0, 1, 2, 0, 2, 3, 3, 2, 5, 3, 5, 4],
            material: 0,
            skin: None,
        };
        flat_normals(&mut g);
        assert_eq!(g.positions.len(), 12);
        assert_eq!(g.indices, (0..12).collect::<Vec<u32>>());
        assert_eq!(g.uvs[4], Vec2::splat(2.0));
        let s = std::f32::consts::FRAC_1_SQRT_2;
        for k in 0..6 {
            assert!((g.normals[k] - Vec3::new(-s, s, 0.0)).length() < 1e-6, "{k}: {}", g.normals[k]);
            assert!(
                (g.normals[k + 6] - Vec3::new(s, s, 0.0)).length() < 1e-6,
                "{}: {}",
                k + 6,
                g.normals[k + 6]
            );
        }
    }
}
