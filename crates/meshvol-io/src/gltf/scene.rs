//! The scene: nodes and their transforms, primitives and their modes, and the placed
//! mesh of every primitive reached from the default scene.

use meshvol::Point;
use rayon::prelude::*;

use super::buffers::{packed_triangles, read_accessor, strided, Buffers, Component};
use super::schema::{at, Document, Node, Primitive};
use crate::error::ParseError;
use crate::limits::Limits;
use crate::transform::{Gathered, Placed};
use meshvol::assembly::Affine;

/// glTF's componentType of 32-bit floats.
const FLOAT: u64 = 5126;

/// A node's own transform.
pub(super) fn local(node: &Node) -> Affine {
    if let Some(m) = node.matrix {
        // Column-major.
        return Affine([0, 1, 2].map(|r| [m[r], m[4 + r], m[8 + r], m[12 + r]]));
    }
    let [tx, ty, tz] = node.translation.unwrap_or([0.0; 3]);
    let [x, y, z, w] = node.rotation.unwrap_or([0.0, 0.0, 0.0, 1.0]);
    let [sx, sy, sz] = node.scale.unwrap_or([1.0; 3]);
    let r = [
        [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w)],
        [2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w)],
        [2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y)],
    ];
    Affine([
        [r[0][0] * sx, r[0][1] * sy, r[0][2] * sz, tx],
        [r[1][0] * sx, r[1][1] * sy, r[1][2] * sz, ty],
        [r[2][0] * sx, r[2][1] * sy, r[2][2] * sz, tz],
    ])
}

/// A node with a mesh, placed.
pub(super) struct Instance {
    node: usize,
    mesh: usize,
    placement: Affine,
}

/// The nodes with meshes reached from the default scene, in depth-first order.
pub(super) fn instances(doc: &Document) -> Result<Vec<Instance>, ParseError> {
    let roots: Vec<usize> = match (doc.scene, doc.scenes.first()) {
        (Some(s), _) => {
            doc.scenes.get(s).ok_or_else(|| at("scene", format!("no scene {s}")))?.nodes.clone()
        }
        (None, Some(first)) => first.nodes.clone(),
        (None, None) => {
            let mut child = vec![false; doc.nodes.len()];
            for node in &doc.nodes {
                for &c in &node.children {
                    if let Some(flag) = child.get_mut(c) {
                        *flag = true;
                    }
                }
            }
            (0..doc.nodes.len()).filter(|&n| !child[n]).collect()
        }
    };
    let mut seen = vec![false; doc.nodes.len()];
    let mut out = Vec::new();
    let mut stack: Vec<(usize, Affine)> =
        roots.iter().rev().map(|&n| (n, Affine::IDENTITY)).collect();
    while let Some((n, parent)) = stack.pop() {
        let node = doc.nodes.get(n).ok_or_else(|| at("scenes", format!("no node {n}")))?;
        if std::mem::replace(&mut seen[n], true) {
            return Err(at(
                format!("nodes[{n}]"),
                "reached twice: the node hierarchy must be a forest (no cycles, no shared \
                 children)",
            ));
        }
        let placement = local(node).then(&parent);
        if !placement.is_finite() {
            return Err(at(format!("nodes[{n}]"), "its transform is not finite"));
        }
        if let Some(mesh) = node.mesh {
            if mesh >= doc.meshes.len() {
                return Err(at(format!("nodes[{n}].mesh"), format!("no mesh {mesh}")));
            }
            out.push(Instance { node: n, mesh, placement });
        }
        for &c in node.children.iter().rev() {
            if c >= doc.nodes.len() {
                return Err(at(format!("nodes[{n}].children"), format!("no node {c}")));
            }
            stack.push((c, placement));
        }
    }
    Ok(out)
}

/// How a primitive's vertices form triangles.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Mode {
    Triangles,
    Strip,
    Fan,
}

impl Mode {
    pub(super) fn triangles(self, n: usize) -> usize {
        match self {
            Mode::Triangles => n / 3,
            Mode::Strip | Mode::Fan => n.saturating_sub(2),
        }
    }

    /// The vertices (positions in the index list) of triangle `i`.
    #[inline]
    pub(super) fn corners(self, i: usize) -> [usize; 3] {
        match self {
            Mode::Triangles => [3 * i, 3 * i + 1, 3 * i + 2],
            Mode::Strip if i.is_multiple_of(2) => [i, i + 1, i + 2],
            Mode::Strip => [i, i + 2, i + 1],
            Mode::Fan => [i + 1, i + 2, 0],
        }
    }
}

/// A primitive's mode, `None` for points and lines.
pub(super) fn mode(primitive: &Primitive, item: &str) -> Result<Option<Mode>, ParseError> {
    match primitive.mode.unwrap_or(4) {
        0..=3 => Ok(None),
        4 => Ok(Some(Mode::Triangles)),
        5 => Ok(Some(Mode::Strip)),
        6 => Ok(Some(Mode::Fan)),
        m => Err(at(format!("{item}.mode"), format!("invalid mode {m}"))),
    }
}

/// The element count of accessor `index`, once its data are known to fit its buffer
/// view (or the file's size, without one): a count that can be trusted for reserving.
pub(super) fn checked_count(buffers: &mut Buffers<'_>, index: usize) -> Result<u64, ParseError> {
    let item = format!("accessors[{index}]");
    let doc = buffers.doc;
    let accessor = doc.accessors.get(index).ok_or_else(|| at(item.clone(), "no such accessor"))?;
    let components = match accessor.kind.as_str() {
        "SCALAR" => 1,
        "VEC3" => 3,
        other => return Err(at(item, format!("type {other} holds no positions or indices"))),
    };
    let component = Component::from_code(accessor.component_type).ok_or_else(|| {
        at(item.clone(), format!("invalid componentType {}", accessor.component_type))
    })?;
    let count = usize::try_from(accessor.count).unwrap_or(usize::MAX);
    let fits = match accessor.buffer_view {
        Some(view) => {
            let element = components * component.size();
            let (data, stride) = buffers.view(view)?;
            strided(data, accessor.byte_offset, count, stride.unwrap_or(element), element).is_some()
        }
        None => count <= buffers.file_bytes,
    };
    if !fits {
        return Err(at(item, format!("its {count} elements do not fit its data")));
    }
    Ok(accessor.count)
}

/// The number of vertices and triangles of a primitive.
pub(super) fn primitive_size(
    buffers: &mut Buffers<'_>,
    primitive: &Primitive,
    mode: Mode,
) -> Result<(u64, u64), ParseError> {
    let vertices = match primitive.attributes.position {
        Some(a) => checked_count(buffers, a)?,
        None => 0,
    };
    let listed = match primitive.indices {
        Some(a) => checked_count(buffers, a)?,
        None => vertices,
    };
    let triangles = mode.triangles(usize::try_from(listed).unwrap_or(usize::MAX)) as u64;
    Ok((vertices, triangles))
}

/// Reads the scene's primitives into one mesh, its size checked against `limits` first.
pub(super) fn place(
    doc: &Document,
    mut buffers: Buffers<'_>,
    warnings: &mut Vec<String>,
    limits: &Limits,
) -> Result<Gathered, ParseError> {
    let instances = instances(doc)?;

    // Totals first: an accessor's count is checked against its data when it is read,
    // and an instanced mesh counts once per instance.
    let mut vertices = 0u64;
    let mut triangles = 0u64;
    let mut skipped = 0usize;
    for instance in &instances {
        for (p, primitive) in doc.meshes[instance.mesh].primitives.iter().enumerate() {
            let item = format!("meshes[{}].primitives[{p}]", instance.mesh);
            match mode(primitive, &item)? {
                Some(mode) => {
                    let (v, t) = primitive_size(&mut buffers, primitive, mode)?;
                    vertices = vertices.saturating_add(v);
                    triangles = triangles.saturating_add(t);
                }
                None => skipped += 1,
            }
        }
    }
    if skipped > 0 {
        warnings.push(format!("skipped {skipped} point and line primitives (no volume)"));
    }
    // A mesh placed by several nodes is decoded once and placed from the copy; one
    // placed once is decoded and moved in.
    let mut uses = vec![0usize; doc.meshes.len()];
    instances.iter().for_each(|i| uses[i.mesh] += 1);
    let copies = uses.iter().any(|&n| n > 1).then(|| {
        let primitives = |m: usize| doc.meshes[m].primitives.len() as u64;
        instances.iter().map(|i| primitives(i.mesh)).sum()
    });
    limits.expansion(triangles, instances.len() as u64)?;
    let mut placed = Placed::with_capacity(vertices, triangles, copies)
        .map_err(|message| ParseError::new(None, message))?;
    let mut decoded: Vec<Option<Vec<Part>>> = (0..doc.meshes.len()).map(|_| None).collect();
    for instance in &instances {
        let first = placed.triangle_count();
        let m = instance.mesh;
        if uses[m] == 1 {
            for (p, (positions, tris)) in decode_mesh(doc, &mut buffers, m)?.into_iter().enumerate()
            {
                placed.add_owned((m as u64, p as u64), positions, tris, &instance.placement);
            }
        } else {
            if decoded[m].is_none() {
                decoded[m] = Some(decode_mesh(doc, &mut buffers, m)?);
            }
            for (p, (positions, tris)) in decoded[m].iter().flatten().enumerate() {
                placed.add((m as u64, p as u64), positions, tris, &instance.placement);
            }
        }
        let node = &doc.nodes[instance.node];
        let name = node
            .name
            .clone()
            .or_else(|| doc.meshes[instance.mesh].name.clone())
            .unwrap_or_else(|| format!("node {}", instance.node));
        // A mesh instance is a body: its primitives (split by material) are its parts.
        placed.close_body(name.clone(), first);
        placed.close_object(name, first);
    }
    placed.finish().map_err(|e| ParseError::new(None, e.to_string()))
}

/// The triangle primitives of mesh `mesh`, decoded: each its positions and its
/// triangles (indexing them).
fn decode_mesh(
    doc: &Document,
    buffers: &mut Buffers<'_>,
    mesh: usize,
) -> Result<Vec<Part>, ParseError> {
    let mut parts = Vec::new();
    for (p, primitive) in doc.meshes[mesh].primitives.iter().enumerate() {
        let item = format!("meshes[{mesh}].primitives[{p}]");
        let Some(mode) = mode(primitive, &item)? else { continue };
        let position = primitive
            .attributes
            .position
            .ok_or_else(|| at(item.clone(), "no POSITION attribute"))?;
        // The core spec allows only FLOAT positions; integers need KHR_mesh_quantization
        // (read as it says). Read as numbers without it, they would be silently wrong.
        let quantized = doc.extensions_used.iter().any(|e| e == "KHR_mesh_quantization");
        let kind = doc.accessors.get(position).map(|a| a.component_type);
        if let Some(kind) = kind.filter(|&k| k != FLOAT && !quantized) {
            return Err(at(
                format!("accessors[{position}]"),
                format!(
                    "POSITION has componentType {kind}; glTF allows only FLOAT (5126) \
                     without KHR_mesh_quantization in extensionsUsed"
                ),
            ));
        }
        let positions: Vec<Point> =
            read_accessor(buffers, position, "VEC3", 3, |data, at, c, normalized| {
                match c {
                    // The common case, without a type dispatch per coordinate.
                    Component::F32 => [0, 4, 8].map(|k| {
                        let b =
                            [data[at + k], data[at + k + 1], data[at + k + 2], data[at + k + 3]];
                        f64::from(f32::from_le_bytes(b))
                    }),
                    _ => [0, 1, 2].map(|k| c.read(data, at + k * c.size(), normalized)),
                }
            })?;
        let bad = positions.par_iter().position_first(|p| p.iter().any(|c| !c.is_finite()));
        if let Some(bad) = bad {
            return Err(at(
                format!("accessors[{position}]"),
                format!("element {bad} is not finite"),
            ));
        }
        let n = positions.len();
        if let (Mode::Triangles, Some(a)) = (mode, primitive.indices) {
            if let Some(tris) = packed_triangles(buffers, a, n)? {
                parts.push((positions, tris));
                continue;
            }
        }
        let listed: Vec<u32> = match primitive.indices {
            Some(a) => {
                let item = format!("accessors[{a}]");
                let ty = doc.accessors.get(a).map_or(0, |a| a.component_type);
                if !matches!(ty, 5121 | 5123 | 5125) {
                    return Err(at(item, "indices must be unsigned byte, short or int"));
                }
                let values =
                    read_accessor(buffers, a, "SCALAR", 1, |data, at, c, _| c.index(data, at))?;
                if let Some((k, &v)) =
                    values.par_iter().enumerate().find_first(|(_, &v)| v as usize >= n)
                {
                    return Err(at(
                        item,
                        format!(
                            "index {v} (element {k}) is out of range: POSITION has {n} \
                             elements"
                        ),
                    ));
                }
                values
            }
            None => {
                let n32 = u32::try_from(n).map_err(|_| {
                    at(item.clone(), format!("{n} vertices do not fit 32-bit indices"))
                })?;
                (0..n32).collect()
            }
        };
        let count = mode.triangles(listed.len());
        let tris: Vec<[u32; 3]> =
            (0..count).into_par_iter().map(|t| mode.corners(t).map(|k| listed[k])).collect();
        parts.push((positions, tris));
    }
    Ok(parts)
}

/// One primitive: positions, and triangles indexing them.
type Part = (Vec<Point>, Vec<[u32; 3]>);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gltf::buffers::percent_decode;

    #[test]
    pub(super) fn strips_and_fans_cover_the_polygon() {
        assert_eq!(Mode::Strip.triangles(5), 3);
        assert_eq!(Mode::Strip.corners(0), [0, 1, 2]);
        assert_eq!(Mode::Strip.corners(1), [1, 3, 2]);
        assert_eq!(Mode::Fan.corners(1), [2, 3, 0]);
        assert_eq!(Mode::Triangles.triangles(7), 2);
    }

    #[test]
    pub(super) fn trs_is_translation_rotation_scale() {
        // A quarter turn about z (quaternion (0, 0, sin 45°, cos 45°)), scale 2, shift x.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let node = Node {
            translation: Some([10.0, 0.0, 0.0]),
            rotation: Some([0.0, 0.0, h, h]),
            scale: Some([2.0, 2.0, 2.0]),
            ..Node::default()
        };
        let p = local(&node).apply([1.0, 0.0, 0.0]);
        assert!((p[0] - 10.0).abs() < 1e-12 && (p[1] - 2.0).abs() < 1e-12, "{p:?}");
        let m = Node {
            matrix: Some([1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 5., 6., 7., 1.]),
            ..Node::default()
        };
        assert_eq!(local(&m).apply([1.0, 1.0, 1.0]), [6.0, 7.0, 8.0]);
        assert_eq!(percent_decode("a%20b%zz.bin"), "a b%zz.bin");
    }
}
