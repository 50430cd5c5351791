//! The node hierarchy walked without recursion: world matrices (`f64`), cycles and
//! depth refused by name, and the default scene's nodes in depth-first order.

use std::path::Path;

use glam::{DMat4, DQuat, DVec3};

use crate::{LoadError, MAX_NODE_DEPTH, MAX_NODE_VISITS};

/// Every node's world matrix (identity for nodes outside any hierarchy root).
pub(crate) fn world_matrices(path: &Path, doc: &gltf::Document) -> Result<Vec<DMat4>, LoadError> {
    let nodes: Vec<gltf::Node> = doc.nodes().collect();
    let cycle = |i: usize| LoadError::Invalid {
        path: path.to_owned(),
        field: format!("nodes[{i}].children"),
        reason: "the node hierarchy has a cycle".into(),
    };
    let mut world = vec![DMat4::IDENTITY; nodes.len()];
    let mut state = vec![0u8; nodes.len()]; // 0 unvisited, 1 on the path, 2 done
    for root in root_nodes(doc) {
        // Depth-first with explicit enter/leave, to see cycles; (node, parent world, depth, leaving).
        let mut stack = vec![(root, DMat4::IDENTITY, 0usize, false)];
        while let Some((i, parent, depth, leaving)) = stack.pop() {
            if leaving {
                state[i] = 2;
                continue;
            }
            match state[i] {
                1 => return Err(cycle(i)),
                2 => continue, // a node with two parents: keep its first world matrix
                _ => {}
            }
            if depth > MAX_NODE_DEPTH {
                return Err(LoadError::TooLarge {
                    path: path.to_owned(),
                    field: format!("nodes[{i}]"),
                    reason: format!("the node hierarchy is deeper than {MAX_NODE_DEPTH} levels"),
                });
            }
            state[i] = 1;
            let local = local_matrix(&nodes[i]);
            if !local.is_finite() {
                return Err(LoadError::NonFinitePosition {
                    path: path.to_owned(),
                    field: format!("nodes[{i}]"),
                    detail: "in the node's transform".into(),
                });
            }
            world[i] = parent * local;
            stack.push((i, parent, depth, true));
            for c in nodes[i].children() {
                if state[c.index()] == 1 {
                    return Err(cycle(i));
                }
                stack.push((c.index(), world[i], depth + 1, false));
            }
        }
    }
    if let Some(i) = state.iter().position(|&s| s == 0) {
        // Every node of a cycle has a parent, so no root reaches it.
        if nodes[i].children().next().is_some() {
            return Err(cycle(i));
        }
    }
    Ok(world)
}

/// The nodes of the default scene (or the first, or every root without scenes), depth
/// first with children in order. Call after [`world_matrices`], which refuses cycles.
pub(crate) fn scene_order(path: &Path, doc: &gltf::Document) -> Result<Vec<usize>, LoadError> {
    let roots: Vec<usize> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => scene.nodes().map(|n| n.index()).collect(),
        None => root_nodes(doc),
    };
    let nodes: Vec<gltf::Node> = doc.nodes().collect();
    let mut order = Vec::new();
    let mut stack: Vec<usize> = roots.into_iter().rev().collect();
    while let Some(i) = stack.pop() {
        if order.len() >= MAX_NODE_VISITS {
            return Err(LoadError::TooLarge {
                path: path.to_owned(),
                field: "nodes".into(),
                reason: format!(
                    "the scene visits more than {MAX_NODE_VISITS} nodes (nodes listed as children of several parents)"
                ),
            });
        }
        order.push(i);
        let first_child = stack.len();
        stack.extend(nodes[i].children().map(|c| c.index()));
        stack[first_child..].reverse();
    }
    Ok(order)
}

/// The node's local transform in `f64` (a zero quaternion reads as identity).
pub(crate) fn local_matrix(node: &gltf::Node) -> DMat4 {
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
