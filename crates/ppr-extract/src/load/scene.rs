//! Flattens the scene graph: world transforms (f64), instancing (shared meshes and
//! `EXT_mesh_gpu_instancing`), skinning at rest pose, and winding flips for mirroring
//! transforms.

use std::collections::HashMap;
use std::path::Path;
use std::rc::Rc;

use glam::{DMat4, DQuat, DVec3};

use super::LoadError;
use super::accessor::{read_accessor, read_indices};
use super::buffers::BufferData;
use super::materials::{display_name, read_override};
use crate::level::{Level, LevelTriangle, TriangleSource};

/// Per vertex, the (joint, weight) pairs of a skinned primitive.
type SkinWeights = Vec<Vec<(usize, f64)>>;

/// One primitive's geometry in its mesh's space, shared by every instance.
struct PrimitiveGeometry {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    /// Per vertex, (joint, weight) pairs when the primitive is skinned.
    skin: Option<SkinWeights>,
}

/// Everything needed to flatten the scene.
pub(crate) struct SceneReader<'a> {
    pub path: &'a Path,
    pub doc: &'a gltf::Document,
    pub data: &'a BufferData,
    /// Index of the glTF default material in the level's material list.
    pub default_material: u32,
}

impl SceneReader<'_> {
    /// Appends every triangle of the default scene (or the first, or all root nodes) to `level`.
    pub(crate) fn flatten(&self, level: &mut Level) -> Result<(), LoadError> {
        let worlds = self.world_matrices()?;
        let roots: Vec<usize> = match self.doc.default_scene().or_else(|| self.doc.scenes().next()) {
            Some(scene) => scene.nodes().map(|n| n.index()).collect(),
            None => root_nodes(self.doc),
        };
        let mut cache: HashMap<(usize, usize), Rc<PrimitiveGeometry>> = HashMap::new();
        let mut notes = NoteCounter::default();
        let nodes: Vec<gltf::Node> = self.doc.nodes().collect();
        // Depth-first over the scene, children in order: deterministic triangle order.
        let mut stack: Vec<usize> = roots.into_iter().rev().collect();
        let mut visits = 0usize;
        while let Some(i) = stack.pop() {
            visits += 1;
            if visits > 1_000_000 {
                return Err(
                    self.invalid("nodes", "the node hierarchy is too deep or shared too often".into())
                );
            }
            let node = &nodes[i];
            stack.extend(node.children().map(|c| c.index()).collect::<Vec<_>>().into_iter().rev());
            let Some(mesh) = node.mesh() else { continue };
            let node_name = display_name(node.name(), i);
            let node_extras =
                read_override(self.path, &format!("nodes[{i}] ({node_name:?})"), node.extras())?;
            let mesh_name = display_name(mesh.name(), mesh.index());
            let mesh_extras = read_override(
                self.path,
                &format!("meshes[{}] ({mesh_name:?})", mesh.index()),
                mesh.extras(),
            )?;
            let instances = self.instances(node, worlds[i])?;
            for prim in mesh.primitives() {
                let geometry = match cache.get(&(mesh.index(), prim.index())) {
                    Some(g) => Rc::clone(g),
                    None => {
                        let Some(g) = self.read_primitive(&mesh, &prim, &mut notes)? else { continue };
                        let g = Rc::new(g);
                        cache.insert((mesh.index(), prim.index()), Rc::clone(&g));
                        g
                    }
                };
                let source = level.sources.len() as u32;
                level.sources.push(TriangleSource {
                    node: node_name.clone(),
                    mesh: mesh_name.clone(),
                    material: prim.material().index().map_or(self.default_material, |m| m as u32),
                    node_extras,
                    mesh_extras,
                });
                match (&geometry.skin, node.skin()) {
                    (Some(weights), Some(skin)) => {
                        let joints = self.joint_matrices(&skin, &worlds)?;
                        self.emit_skinned(level, &geometry, weights, &joints, source, i)?;
                    }
                    _ => {
                        for m in &instances {
                            self.emit(level, &geometry, *m, source, i)?;
                        }
                    }
                }
            }
        }
        level.notes.extend(notes.into_notes());
        Ok(())
    }

    fn invalid(&self, field: &str, reason: String) -> LoadError {
        LoadError::Invalid { path: self.path.to_owned(), field: field.to_owned(), reason }
    }

    /// World matrix of every node (identity for nodes outside any hierarchy root).
    fn world_matrices(&self) -> Result<Vec<DMat4>, LoadError> {
        let nodes: Vec<gltf::Node> = self.doc.nodes().collect();
        let mut world = vec![DMat4::IDENTITY; nodes.len()];
        let mut state = vec![0u8; nodes.len()]; // 0 unvisited, 1 on the path, 2 done
        for root in root_nodes(self.doc) {
            // Iterative DFS with explicit enter/leave to detect cycles.
            let mut stack = vec![(root, DMat4::IDENTITY, false)];
            while let Some((i, parent, leaving)) = stack.pop() {
                if leaving {
                    state[i] = 2;
                    continue;
                }
                if state[i] == 1 {
                    return Err(self
                        .invalid(&format!("nodes[{i}].children"), "the node hierarchy has a cycle".into()));
                }
                if state[i] == 2 {
                    continue; // a node with two parents: keep its first world matrix
                }
                state[i] = 1;
                let local = local_matrix(&nodes[i]);
                if !local.is_finite() {
                    return Err(LoadError::NonFinitePosition {
                        path: self.path.to_owned(),
                        field: format!("nodes[{i}]"),
                        detail: "in the node's transform".into(),
                    });
                }
                world[i] = parent * local;
                stack.push((i, parent, true));
                for c in nodes[i].children() {
                    if state[c.index()] == 1 {
                        return Err(self.invalid(
                            &format!("nodes[{i}].children"),
                            "the node hierarchy has a cycle".into(),
                        ));
                    }
                    stack.push((c.index(), world[i], false));
                }
            }
        }
        if let Some(i) = state.iter().position(|&s| s == 0) {
            // Every node of a cycle has a parent, so no root reaches it.
            if nodes[i].children().next().is_some() {
                return Err(
                    self.invalid(&format!("nodes[{i}].children"), "the node hierarchy has a cycle".into())
                );
            }
        }
        Ok(world)
    }

    /// The node's world matrix, once per `EXT_mesh_gpu_instancing` instance if it has any.
    fn instances(&self, node: &gltf::Node, world: DMat4) -> Result<Vec<DMat4>, LoadError> {
        let Some(ext) = node.extension_value("EXT_mesh_gpu_instancing") else { return Ok(vec![world]) };
        let attrs = ext.get("attributes").and_then(|a| a.as_object());
        let read = |name: &str, comps: usize| -> Result<Option<Vec<Vec<f64>>>, LoadError> {
            let Some(index) = attrs.and_then(|a| a.get(name)).and_then(serde_json::Value::as_u64) else {
                return Ok(None);
            };
            let accessor = self.doc.accessors().nth(index as usize).ok_or_else(|| {
                self.invalid(
                    &format!("nodes[{}].extensions.EXT_mesh_gpu_instancing.attributes.{name}", node.index()),
                    format!("accessor {index} does not exist"),
                )
            })?;
            let values = read_accessor(self.path, self.data, &accessor)?;
            if values.components != comps {
                return Err(LoadError::BadAccessor {
                    path: self.path.to_owned(),
                    field: format!("accessors[{index}]"),
                    reason: format!("instance {name} needs {comps} components"),
                });
            }
            Ok(Some((0..values.len()).map(|k| values.get(k).to_vec()).collect()))
        };
        let t = read("TRANSLATION", 3)?;
        let r = read("ROTATION", 4)?;
        let s = read("SCALE", 3)?;
        let count = [&t, &r, &s].iter().filter_map(|v| v.as_ref().map(Vec::len)).max().unwrap_or(0);
        let mut out = Vec::with_capacity(count);
        for k in 0..count {
            let tr = t.as_ref().and_then(|v| v.get(k)).map_or(DVec3::ZERO, |v| DVec3::new(v[0], v[1], v[2]));
            let rot = r
                .as_ref()
                .and_then(|v| v.get(k))
                .map_or(DQuat::IDENTITY, |v| DQuat::from_xyzw(v[0], v[1], v[2], v[3]).normalize());
            let sc = s.as_ref().and_then(|v| v.get(k)).map_or(DVec3::ONE, |v| DVec3::new(v[0], v[1], v[2]));
            out.push(world * DMat4::from_scale_rotation_translation(sc, rot, tr));
        }
        Ok(out)
    }

    fn joint_matrices(&self, skin: &gltf::Skin, worlds: &[DMat4]) -> Result<Vec<DMat4>, LoadError> {
        let inverse_binds = match skin.inverse_bind_matrices() {
            Some(acc) => {
                let v = read_accessor(self.path, self.data, &acc)?;
                if v.components != 16 {
                    return Err(LoadError::BadAccessor {
                        path: self.path.to_owned(),
                        field: format!("accessors[{}]", acc.index()),
                        reason: "inverseBindMatrices must be MAT4".into(),
                    });
                }
                (0..v.len()).map(|k| DMat4::from_cols_slice(v.get(k))).collect()
            }
            None => Vec::new(),
        };
        Ok(skin
            .joints()
            .enumerate()
            .map(|(k, j)| worlds[j.index()] * inverse_binds.get(k).copied().unwrap_or(DMat4::IDENTITY))
            .collect())
    }

    fn read_primitive(
        &self,
        mesh: &gltf::Mesh,
        prim: &gltf::Primitive,
        notes: &mut NoteCounter,
    ) -> Result<Option<PrimitiveGeometry>, LoadError> {
        use gltf::mesh::Mode;
        let mode = prim.mode();
        if matches!(mode, Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip) {
            notes.point_and_line_primitives += 1;
            return Ok(None);
        }
        let field = format!("meshes[{}].primitives[{}]", mesh.index(), prim.index());
        let Some(pos_acc) = prim.get(&gltf::Semantic::Positions) else {
            return Err(self.invalid(&format!("{field}.attributes"), "has no POSITION".into()));
        };
        let values = read_accessor(self.path, self.data, &pos_acc)?;
        if values.components != 3 {
            return Err(LoadError::BadAccessor {
                path: self.path.to_owned(),
                field: format!("accessors[{}]", pos_acc.index()),
                reason: "POSITION must be VEC3".into(),
            });
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
        let n = positions.len();
        let indices: Vec<u32> = match prim.indices() {
            Some(acc) => read_indices(self.path, self.data, &acc, n)?,
            None => (0..n as u32).collect(),
        };
        let triangles = assemble_triangles(mode, &indices);
        let skin = self.read_skin_weights(prim, n)?;
        Ok(Some(PrimitiveGeometry { positions, triangles, skin }))
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
                return Err(LoadError::BadAccessor {
                    path: self.path.to_owned(),
                    field: format!("accessors[{}]", w.index()),
                    reason: "JOINTS and WEIGHTS do not match POSITION".into(),
                });
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

    fn emit(
        &self,
        level: &mut Level,
        g: &PrimitiveGeometry,
        m: DMat4,
        source: u32,
        node: usize,
    ) -> Result<(), LoadError> {
        let world: Vec<DVec3> = g.positions.iter().map(|&p| m.transform_point3(p)).collect();
        self.check_finite(&world, node)?;
        let flip = m.determinant() < 0.0;
        push_triangles(level, &world, &g.triangles, |_| flip, source);
        Ok(())
    }

    fn emit_skinned(
        &self,
        level: &mut Level,
        g: &PrimitiveGeometry,
        weights: &[Vec<(usize, f64)>],
        joints: &[DMat4],
        source: u32,
        node: usize,
    ) -> Result<(), LoadError> {
        let mut world = Vec::with_capacity(g.positions.len());
        let mut flips = Vec::with_capacity(g.positions.len());
        for (k, &p) in g.positions.iter().enumerate() {
            let mut m = DMat4::ZERO;
            for &(j, w) in &weights[k] {
                let joint = joints.get(j).ok_or_else(|| {
                    self.invalid(
                        &format!("nodes[{node}].skin"),
                        format!("vertex {k} uses joint {j}, which the skin does not have"),
                    )
                })?;
                m += *joint * w;
            }
            world.push(m.transform_point3(p));
            flips.push(m.determinant() < 0.0);
        }
        self.check_finite(&world, node)?;
        push_triangles(level, &world, &g.triangles, |a| flips[a as usize], source);
        Ok(())
    }

    fn check_finite(&self, world: &[DVec3], node: usize) -> Result<(), LoadError> {
        if let Some(k) = world.iter().position(|p| !p.is_finite()) {
            return Err(LoadError::NonFinitePosition {
                path: self.path.to_owned(),
                field: format!("nodes[{node}]"),
                detail: format!("vertex {k} after the world transform"),
            });
        }
        Ok(())
    }
}

fn push_triangles(
    level: &mut Level,
    world: &[DVec3],
    tris: &[[u32; 3]],
    flip: impl Fn(u32) -> bool,
    source: u32,
) {
    level.triangles.extend(tris.iter().map(|&[a, b, c]| {
        let (pa, pb, pc) = (world[a as usize], world[b as usize], world[c as usize]);
        let positions = if flip(a) { [pa, pc, pb] } else { [pa, pb, pc] };
        LevelTriangle { positions, source }
    }));
}

/// Triangle lists from triangle lists, strips and fans (glTF 2.0 §3.7.2.1).
fn assemble_triangles(mode: gltf::mesh::Mode, idx: &[u32]) -> Vec<[u32; 3]> {
    use gltf::mesh::Mode;
    match mode {
        Mode::TriangleStrip => {
            (0..idx.len().saturating_sub(2))
                .map(|i| {
                    if i % 2 == 0 {
                        [idx[i], idx[i + 1], idx[i + 2]]
                    } else {
                        [idx[i], idx[i + 2], idx[i + 1]]
                    }
                })
                .collect()
        }
        Mode::TriangleFan => (1..idx.len().saturating_sub(1)).map(|i| [idx[i], idx[i + 1], idx[0]]).collect(),
        _ => idx.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
    }
}

fn local_matrix(node: &gltf::Node) -> DMat4 {
    match node.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            DMat4::from_cols_array_2d(&matrix.map(|col| col.map(f64::from)))
        }
        gltf::scene::Transform::Decomposed { translation: t, rotation: r, scale: s } => {
            let q = DQuat::from_xyzw(f64::from(r[0]), f64::from(r[1]), f64::from(r[2]), f64::from(r[3]));
            let q = if q.length_squared() > 0.0 { q.normalize() } else { DQuat::IDENTITY };
            DMat4::from_scale_rotation_translation(
                DVec3::from_array(s.map(f64::from)),
                q,
                DVec3::from_array(t.map(f64::from)),
            )
        }
    }
}

/// Nodes that are nobody's child, in index order.
fn root_nodes(doc: &gltf::Document) -> Vec<usize> {
    let mut has_parent = vec![false; doc.nodes().len()];
    for n in doc.nodes() {
        for c in n.children() {
            has_parent[c.index()] = true;
        }
    }
    (0..has_parent.len()).filter(|&i| !has_parent[i]).collect()
}

#[derive(Default)]
struct NoteCounter {
    point_and_line_primitives: usize,
}

impl NoteCounter {
    fn into_notes(self) -> Vec<String> {
        let mut out = Vec::new();
        if self.point_and_line_primitives > 0 {
            out.push(format!("{} point or line primitives skipped", self.point_and_line_primitives));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gltf::mesh::Mode;

    #[test]
    fn assembles_strips_and_fans_with_consistent_winding() {
        assert_eq!(assemble_triangles(Mode::Triangles, &[0, 1, 2, 3, 4, 5, 6]), vec![[0, 1, 2], [3, 4, 5]]);
        assert_eq!(assemble_triangles(Mode::TriangleStrip, &[0, 1, 2, 3]), vec![[0, 1, 2], [1, 3, 2]]);
        assert_eq!(assemble_triangles(Mode::TriangleFan, &[0, 1, 2, 3]), vec![[1, 2, 0], [2, 3, 0]]);
        assert!(assemble_triangles(Mode::TriangleStrip, &[0, 1]).is_empty());
    }
}
