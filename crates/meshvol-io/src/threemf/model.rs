//! The model part of a 3MF package, parsed: its unit, its objects (meshes or
//! components) and its build items, each with the byte it is at for errors.

use std::borrow::Cow;
use std::collections::HashMap;

use meshvol::assembly::Affine;
use meshvol::Point;
use quick_xml::events::{BytesStart, Event};
use quick_xml::name::ResolveResult;
use quick_xml::NsReader;

use crate::length_unit::LengthUnit;

/// The 3MF core namespace.
const CORE: &[u8] = b"http://schemas.microsoft.com/3dmanufacturing/core/2015/02";

/// The raw value of an unprefixed attribute (borrowed from the part: no allocation per
/// vertex or triangle).
pub(super) fn attribute<'e>(e: &'e BytesStart<'_>, name: &[u8]) -> Option<Cow<'e, [u8]>> {
    e.attributes().with_checks(false).flatten().find(|a| a.key.as_ref() == name).map(|a| a.value)
}

/// What an object holds.
pub(super) enum Content {
    Mesh { positions: Vec<Point>, triangles: Vec<[u32; 3]> },
    Components(Vec<Component>),
}

pub(super) struct Component {
    pub(super) object: u64,
    pub(super) transform: Affine,
    /// Where it is in the part.
    pub(super) at: usize,
}

pub(super) struct ModelObject {
    pub(super) name: Option<String>,
    /// `model` or `solidsupport` (a solid), or another type (not measured).
    pub(super) solid: bool,
    pub(super) kind: String,
    pub(super) content: Content,
}

pub(super) struct Item {
    pub(super) object: u64,
    pub(super) transform: Affine,
    pub(super) part_number: Option<String>,
    /// Where it is in the part.
    pub(super) at: usize,
}

/// The parsed model part.
pub(super) struct Parsed {
    pub(super) unit: LengthUnit,
    pub(super) objects: HashMap<u64, ModelObject>,
    pub(super) items: Vec<Item>,
}

/// Where the parser is.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Tag {
    Model,
    Resources,
    Object,
    Mesh,
    Vertices,
    Triangles,
    Components,
    Build,
    /// A core element not read, or another namespace's element.
    Other,
}

/// An error at byte `at` of the part.
pub(super) type XmlError = (usize, String);

/// An attribute as text, entities expanded.
pub(super) fn text_attribute(e: &BytesStart<'_>, name: &str) -> Option<String> {
    let a = e.try_get_attribute(name).ok().flatten()?;
    a.normalized_value(quick_xml::XmlVersion::Implicit1_0).ok().map(|v| v.into_owned())
}

pub(super) fn number(e: &BytesStart<'_>, name: &[u8], at: usize) -> Result<f64, XmlError> {
    let raw = attribute(e, name).ok_or_else(|| {
        (at, format!("<{}> has no '{}' attribute", show(e), String::from_utf8_lossy(name)))
    })?;
    let value: f64 = fast_float2::parse(raw.trim_ascii()).map_err(|_| {
        (
            at,
            format!(
                "invalid number '{}' in '{}'",
                crate::text::show(&raw),
                String::from_utf8_lossy(name)
            ),
        )
    })?;
    if !value.is_finite() {
        return Err((at, format!("non-finite coordinate '{}'", crate::text::show(&raw))));
    }
    Ok(value)
}

pub(super) fn integer(e: &BytesStart<'_>, name: &[u8], at: usize) -> Result<u64, XmlError> {
    let raw = attribute(e, name).ok_or_else(|| {
        (at, format!("<{}> has no '{}' attribute", show(e), String::from_utf8_lossy(name)))
    })?;
    std::str::from_utf8(raw.trim_ascii()).ok().and_then(|s| s.parse().ok()).ok_or_else(|| {
        (
            at,
            format!(
                "invalid '{}' value '{}'",
                String::from_utf8_lossy(name),
                crate::text::show(&raw)
            ),
        )
    })
}

pub(super) fn show(e: &BytesStart<'_>) -> String {
    String::from_utf8_lossy(e.name().as_ref()).into_owned()
}

/// A `transform` attribute, identity when absent.
pub(super) fn transform(e: &BytesStart<'_>, at: usize) -> Result<Affine, XmlError> {
    let Some(raw) = attribute(e, b"transform") else { return Ok(Affine::IDENTITY) };
    let values: Vec<f64> = raw
        .split(|b| b.is_ascii_whitespace())
        .filter(|w| !w.is_empty())
        .map(|w| fast_float2::parse::<f64, _>(w).ok().filter(|v| v.is_finite()))
        .collect::<Option<_>>()
        .filter(|v: &Vec<f64>| v.len() == 12)
        .ok_or_else(|| {
            (
                at,
                format!(
                    "invalid transform '{}': expected 12 finite numbers",
                    crate::text::show(&raw)
                ),
            )
        })?;
    // Row-vector convention: x' = x·m00 + y·m10 + z·m20 + m30.
    Ok(Affine([0, 1, 2].map(|r| [values[r], values[3 + r], values[6 + r], values[9 + r]])))
}

/// An error for a reference into another model part (production extension).
pub(super) fn no_path(e: &BytesStart<'_>, at: usize) -> Result<(), XmlError> {
    let other_part = e
        .attributes()
        .with_checks(false)
        .flatten()
        .any(|a| a.key.local_name().as_ref() == b"path" && a.key.prefix().is_some());
    if other_part {
        return Err((
            at,
            "refers to an object in another model part (p:path), which is not read".into(),
        ));
    }
    Ok(())
}

pub(super) fn unit(raw: &[u8], at: usize) -> Result<LengthUnit, XmlError> {
    Ok(match raw {
        b"micron" => LengthUnit::Micrometre,
        b"millimeter" => LengthUnit::Millimetre,
        b"centimeter" => LengthUnit::Centimetre,
        b"inch" => LengthUnit::Inch,
        b"foot" => LengthUnit::Foot,
        b"meter" => LengthUnit::Metre,
        _ => return Err((at, format!("unknown unit '{}'", crate::text::show(raw)))),
    })
}

/// Parses the model part.
pub(super) fn parse_model(xml: &[u8]) -> Result<Parsed, XmlError> {
    let mut reader = NsReader::from_reader(xml);
    let mut parsed =
        Parsed { unit: LengthUnit::Millimetre, objects: HashMap::new(), items: Vec::new() };
    let mut stack: Vec<Tag> = Vec::new();
    // The object being read: its id and what it holds so far.
    let mut object: Option<(u64, ModelObject)> = None;
    loop {
        let at = reader.buffer_position() as usize;
        let (ns, event) = match reader.read_resolved_event() {
            Ok(resolved) => resolved,
            Err(e) => {
                let message = format!("invalid XML: {e}");
                return Err((reader.error_position() as usize, message));
            }
        };
        let core = match ns {
            ResolveResult::Bound(ns) => ns.as_ref() == CORE,
            ResolveResult::Unbound => true,
            ResolveResult::Unknown(_) => false,
        };
        let (e, empty) = match event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                if stack.pop() == Some(Tag::Object) {
                    if let Some((id, done)) = object.take() {
                        if parsed.objects.insert(id, done).is_some() {
                            return Err((at, format!("object id {id} is defined twice")));
                        }
                    }
                }
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        let parent = stack.last().copied();
        let name = e.local_name();
        let tag = match (core, parent, name.as_ref()) {
            (true, None, b"model") => {
                if let Some(raw) = attribute(&e, b"unit") {
                    parsed.unit = unit(&raw, at)?;
                }
                Tag::Model
            }
            (true, Some(Tag::Model), b"resources") => Tag::Resources,
            (true, Some(Tag::Model), b"build") => Tag::Build,
            (true, Some(Tag::Resources), b"object") => {
                let id = integer(&e, b"id", at)?;
                let kind = attribute(&e, b"type")
                    .map_or("model".to_string(), |t| String::from_utf8_lossy(&t).into_owned());
                let name = text_attribute(&e, "name");
                let solid = kind == "model" || kind == "solidsupport";
                let content = Content::Components(Vec::new());
                let done = ModelObject { name, solid, kind, content };
                if empty {
                    if parsed.objects.insert(id, done).is_some() {
                        return Err((at, format!("object id {id} is defined twice")));
                    }
                    continue;
                }
                object = Some((id, done));
                Tag::Object
            }
            (true, Some(Tag::Object), b"mesh") => {
                if let Some((_, o)) = &mut object {
                    o.content = Content::Mesh { positions: Vec::new(), triangles: Vec::new() };
                }
                Tag::Mesh
            }
            (true, Some(Tag::Object), b"components") => Tag::Components,
            (true, Some(Tag::Mesh), b"vertices") => Tag::Vertices,
            (true, Some(Tag::Mesh), b"triangles") => Tag::Triangles,
            (true, Some(Tag::Vertices), b"vertex") => {
                let p = [number(&e, b"x", at)?, number(&e, b"y", at)?, number(&e, b"z", at)?];
                if let Some((_, ModelObject { content: Content::Mesh { positions, .. }, .. })) =
                    &mut object
                {
                    positions.push(p);
                }
                Tag::Other
            }
            (true, Some(Tag::Triangles), b"triangle") => {
                let v = [integer(&e, b"v1", at)?, integer(&e, b"v2", at)?, integer(&e, b"v3", at)?];
                if let Some((
                    _,
                    ModelObject { content: Content::Mesh { positions, triangles }, .. },
                )) = &mut object
                {
                    if let Some(&bad) = v.iter().find(|&&i| i >= positions.len() as u64) {
                        return Err((
                            at,
                            format!(
                                "triangle {} uses vertex {bad}, but the object has {} vertices \
                                 before it",
                                triangles.len(),
                                positions.len()
                            ),
                        ));
                    }
                    triangles.push(v.map(|i| i as u32));
                }
                Tag::Other
            }
            (true, Some(Tag::Components), b"component") => {
                no_path(&e, at)?;
                let component = Component {
                    object: integer(&e, b"objectid", at)?,
                    transform: transform(&e, at)?,
                    at,
                };
                if let Some((_, ModelObject { content: Content::Components(list), .. })) =
                    &mut object
                {
                    list.push(component);
                }
                Tag::Other
            }
            (true, Some(Tag::Build), b"item") => {
                no_path(&e, at)?;
                parsed.items.push(Item {
                    object: integer(&e, b"objectid", at)?,
                    transform: transform(&e, at)?,
                    part_number: text_attribute(&e, "partnumber"),
                    at,
                });
                Tag::Other
            }
            (_, None, _) => {
                return Err((at, format!("the root element is <{}>, not <model>", show(&e))))
            }
            _ => Tag::Other,
        };
        if !empty {
            stack.push(tag);
        }
    }
    if !stack.is_empty() {
        return Err((xml.len(), "the XML ends inside an element".into()));
    }
    Ok(parsed)
}
