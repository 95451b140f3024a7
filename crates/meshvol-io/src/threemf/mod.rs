//! 3MF: a zip archive (OPC package) whose model part, an XML document, holds the mesh.
//!
//! ```text
//! <model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
//!   <resources>
//!     <object id="1" name="bolt" type="model">
//!       <mesh>
//!         <vertices> <vertex x="0" y="0" z="0"/> ... </vertices>
//!         <triangles> <triangle v1="0" v2="1" v3="2"/> ... </triangles>
//!       </mesh>
//!     </object>
//!     <object id="2"> <components> <component objectid="1" transform="..."/> </components> </object>
//!   </resources>
//!   <build> <item objectid="2" transform="m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32"/> </build>
//! </model>
//! ```
//!
//! The model part is the target of the package's `3dmodel` relationship
//! (`_rels/.rels`), or `3D/3dmodel.model`; a zip archive with neither is "not a 3MF
//! package". Any zip is recognised by content as 3MF, so that this is what a zip
//! without the `.3mf` extension is told. Read: every build item, its object expanded
//! through components (any depth), each mesh placed by the product of the component
//! and item transforms (3 × 4 affine matrices, row-vector convention: a point
//! `[x y z 1]` times the matrix). A mirroring transform (negative determinant) reverses
//! the winding, so outward faces stay outward. Each build item is an
//! [`Object`], named after its object's `name`, else the item's
//! `partnumber`, else `object ID`. Each placed mesh (an item's object, or each mesh its
//! components reach) is a body ([`crate::Loaded::bodies`]): the 3MF specification makes
//! objects and components separate parts. Items whose object is of type `support`,
//! `surface` or `other` hold no solid: skipped with a warning.
//!
//! The model's `unit` (`micron`, `millimeter` — the default —, `centimeter`, `inch`,
//! `foot`, `meter`) becomes [`crate::Loaded::unit`]. Elements of other namespaces
//! (materials, beam lattices, slices) are ignored; a component or item in another model
//! part (the production extension's `p:path`) is an error, as it is not read.
//!
//! Checked: every coordinate finite, every triangle's indices within its object's
//! vertices, every referenced object defined, no component cycles, and the expanded
//! build within 32-bit vertex indices and 10 million placements before anything is
//! reserved. Errors name the archive part and its line.

use std::collections::HashMap;
use std::io::Read;

use meshvol::Mesh;
use quick_xml::events::Event;

use crate::error::{line_of, Location, ParseError};
use crate::length_unit::LengthUnit;
use crate::limits::{Budget, Limits};
use crate::object::Object;
use crate::transform::Placed;
use meshvol::assembly::Assembly;
use model::{attribute, parse_model, Content, Parsed};

mod model;

/// The model part when the package names none.
const DEFAULT_MODEL: &str = "3D/3dmodel.model";
/// The most bytes one archive part may decompress to, whatever the read's limit.
const MAX_PART: u64 = 1 << 32;

/// What a 3MF file gave.
pub(crate) struct Model {
    pub mesh: Mesh,
    pub objects: Vec<Object>,
    /// Each placed mesh object (a build item's, or one of its components'): a body.
    pub bodies: Vec<Object>,
    pub unit: LengthUnit,
    /// Which object each placed copy is, when an object is placed more than once.
    pub assembly: Option<Assembly>,
}

/// Whether the bytes start like a zip archive.
pub(crate) fn looks_like_zip(bytes: &[u8]) -> bool {
    bytes.starts_with(b"PK\x03\x04")
}

/// Reads a 3MF package within `limits`: its parts' inflated bytes, the placements of its
/// build and their triangles.
pub(crate) fn read(
    bytes: &[u8],
    warnings: &mut Vec<String>,
    limits: &Limits,
) -> Result<Model, ParseError> {
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes))
        .map_err(|e| ParseError::new(None, format!("not a readable zip archive: {e}")))?;
    let part = model_part(&mut archive, limits)?;
    let xml = read_part(&mut archive, &part, limits)?;
    let in_part = |at: usize, message: String| {
        let line = line_of(&xml, at);
        ParseError::new(Some(Location::PartLine { part: part.clone(), line }), message)
    };
    let parsed = parse_model(&xml).map_err(|(at, message)| in_part(at, message))?;
    build(&parsed, warnings, &in_part, limits)
}

/// The name of the model part: the `3dmodel` relationship's target, or the default.
fn model_part(
    archive: &mut zip::ZipArchive<std::io::Cursor<&[u8]>>,
    limits: &Limits,
) -> Result<String, ParseError> {
    let target = match read_part(archive, "_rels/.rels", limits) {
        Ok(rels) => relationship_target(&rels),
        Err(_) => None,
    };
    let named = target.is_some();
    let wanted = target.unwrap_or_else(|| DEFAULT_MODEL.to_string());
    let names: Vec<&str> = archive.file_names().collect();
    if names.contains(&wanted.as_str()) {
        return Ok(wanted);
    }
    names.iter().find(|n| n.eq_ignore_ascii_case(&wanted)).map(|n| n.to_string()).ok_or_else(|| {
        // No 3MF relationship and no default model part: any other zip (a zipped STL,
        // an Office file) ends here.
        let message = if named {
            format!("the archive has no model part '{wanted}'")
        } else {
            format!("not a 3MF package (no {DEFAULT_MODEL})")
        };
        ParseError::new(None, message)
    })
}

/// The target of the first relationship whose type ends in `/3dmodel`, without its
/// leading `/`.
fn relationship_target(rels: &[u8]) -> Option<String> {
    let mut reader = quick_xml::Reader::from_reader(rels);
    loop {
        match reader.read_event().ok()? {
            Event::Start(e) | Event::Empty(e) if e.local_name().as_ref() == b"Relationship" => {
                let ty = attribute(&e, b"Type")?;
                if ty.ends_with(b"/3dmodel") {
                    let target = attribute(&e, b"Target")?;
                    return Some(
                        String::from_utf8_lossy(&target).trim_start_matches('/').to_string(),
                    );
                }
            }
            Event::Eof => return None,
            _ => {}
        }
    }
}

/// The decompressed bytes of an archive part, up to the read's inflated bytes.
fn read_part(
    archive: &mut zip::ZipArchive<std::io::Cursor<&[u8]>>,
    name: &str,
    limits: &Limits,
) -> Result<Vec<u8>, ParseError> {
    let error = |m: String| ParseError::new(None, format!("archive part '{name}': {m}"));
    let limit = limits.inflated_bytes.min(MAX_PART);
    let file = archive.by_name(name).map_err(|e| error(e.to_string()))?;
    let mut data = Vec::with_capacity(file.size().min(limit).min(64 << 20) as usize);
    file.take(limit + 1).read_to_end(&mut data).map_err(|e| error(e.to_string()))?;
    if data.len() as u64 > limit {
        return Err(error(format!("more than {limit} bytes")).over(Budget::InflatedBytes));
    }
    Ok(data)
}

/// What an object expands to: vertices, triangles, placements (itself included) and
/// copies of meshes.
#[derive(Clone, Copy, Default)]
struct Size {
    vertices: u64,
    triangles: u64,
    placements: u64,
    meshes: u64,
}

/// The expanded size of object `root` (referenced at byte `at`) and of every object
/// reachable from it, memoized in `sizes`; errors on undefined objects and cycles.
/// Iterative: component chains may be as deep as the file is long.
fn size(
    parsed: &Parsed,
    root: u64,
    at: usize,
    sizes: &mut HashMap<u64, Option<Size>>,
) -> Result<Size, (usize, String)> {
    // (object, where it is referenced, the next component to visit; None before the
    // first visit). `sizes` holds None for the objects on the stack.
    let mut stack: Vec<(u64, usize, Option<usize>)> = vec![(root, at, None)];
    while let Some(top) = stack.last_mut() {
        let (id, at) = (top.0, top.1);
        let object =
            parsed.objects.get(&id).ok_or_else(|| (at, format!("object {id} is not defined")))?;
        let next = match top.2 {
            Some(next) => next,
            None => {
                match sizes.get(&id) {
                    Some(Some(_)) => {
                        stack.pop();
                        continue;
                    }
                    Some(None) => {
                        return Err((
                            at,
                            format!("object {id} contains itself through its components"),
                        ))
                    }
                    None => {}
                }
                if let Content::Mesh { positions, triangles } = &object.content {
                    let size = Size {
                        vertices: positions.len() as u64,
                        triangles: triangles.len() as u64,
                        placements: 1,
                        meshes: 1,
                    };
                    sizes.insert(id, Some(size));
                    stack.pop();
                    continue;
                }
                sizes.insert(id, None);
                0
            }
        };
        let Content::Components(list) = &object.content else { continue };
        if let Some(c) = list.get(next) {
            top.2 = Some(next + 1);
            stack.push((c.object, c.at, None));
            continue;
        }
        let mut sum = Size { placements: 1, ..Size::default() };
        for c in list {
            let s = sizes.get(&c.object).copied().flatten().unwrap_or_default();
            sum.vertices = sum.vertices.saturating_add(s.vertices);
            sum.triangles = sum.triangles.saturating_add(s.triangles);
            sum.placements = sum.placements.saturating_add(s.placements);
            sum.meshes = sum.meshes.saturating_add(s.meshes);
        }
        sizes.insert(id, Some(sum));
        stack.pop();
    }
    Ok(sizes.get(&root).copied().flatten().unwrap_or_default())
}

/// Places every build item's meshes.
fn build(
    parsed: &Parsed,
    warnings: &mut Vec<String>,
    in_part: &dyn Fn(usize, String) -> ParseError,
    limits: &Limits,
) -> Result<Model, ParseError> {
    // Sizes first, each object's once: nothing is reserved before the totals are known.
    let mut sizes = HashMap::new();
    let mut total = Size::default();
    let mut measured = Vec::new();
    let mut skipped = Vec::new();
    for item in &parsed.items {
        let s = size(parsed, item.object, item.at, &mut sizes).map_err(|(at, m)| in_part(at, m))?;
        let object = &parsed.objects[&item.object];
        if !object.solid {
            skipped.push(format!("object {} ({})", item.object, object.kind));
            continue;
        }
        total.vertices = total.vertices.saturating_add(s.vertices);
        total.triangles = total.triangles.saturating_add(s.triangles);
        total.placements = total.placements.saturating_add(s.placements);
        total.meshes = total.meshes.saturating_add(s.meshes);
        measured.push(item);
    }
    if !skipped.is_empty() {
        warnings.push(format!(
            "skipped {} build items that are not solids: {}",
            skipped.len(),
            skipped.join(", ")
        ));
    }
    limits.expansion(total.triangles, total.placements)?;
    let mesh_objects =
        parsed.objects.values().filter(|o| matches!(o.content, Content::Mesh { .. })).count();
    let copies = (total.meshes > mesh_objects as u64).then_some(total.meshes);
    let mut placed = Placed::with_capacity(total.vertices, total.triangles, copies)
        .map_err(|m| ParseError::new(None, m))?;
    for item in measured {
        let first = placed.triangle_count();
        let object = &parsed.objects[&item.object];
        let name = object
            .name
            .clone()
            .or_else(|| item.part_number.clone())
            .unwrap_or_else(|| format!("object {}", item.object));
        let mut stack = vec![(item.object, item.transform)];
        while let Some((id, placement)) = stack.pop() {
            // Defined: `size` checked every reachable object.
            let Some(object) = parsed.objects.get(&id) else { continue };
            match &object.content {
                Content::Mesh { positions, triangles } => {
                    let body_first = placed.triangle_count();
                    placed.add((id, 0), positions, triangles, &placement);
                    // A component is a body of its own, named after its object.
                    let body = match &object.name {
                        _ if id == item.object => name.clone(),
                        Some(own) => own.clone(),
                        None => format!("object {id}"),
                    };
                    placed.close_body(body, body_first);
                }
                Content::Components(list) => {
                    for c in list.iter().rev() {
                        stack.push((c.object, c.transform.then(&placement)));
                    }
                }
            }
        }
        placed.close_object(name, first);
    }
    let g = placed.finish().map_err(|e| ParseError::new(None, e.to_string()))?;
    let (mesh, objects, bodies, assembly) = (g.mesh, g.objects, g.bodies, g.assembly);
    Ok(Model { mesh, objects, bodies, unit: parsed.unit, assembly })
}
