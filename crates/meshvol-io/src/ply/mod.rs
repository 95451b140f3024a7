//! PLY (the Stanford polygon format): ASCII, binary little-endian and binary big-endian.
//!
//! ```text
//! ply
//! format binary_little_endian 1.0      # or ascii 1.0, binary_big_endian 1.0
//! comment written by ...               # comment and obj_info lines anywhere in the header
//! element vertex 8
//! property float x                     # any scalar type, any order, other properties too
//! property float y
//! property float z
//! property uchar red
//! element face 6
//! property list uchar int vertex_indices   # or vertex_index; any integer types
//! element edge 12                      # other elements: skipped
//! property int vertex1
//! property int vertex2
//! end_header
//! ...data, element by element in header order...
//! ```
//!
//! Scalar types: `char`/`int8`, `uchar`/`uint8`, `short`/`int16`, `ushort`/`uint16`,
//! `int`/`int32`, `uint`/`uint32`, `float`/`float32`, `double`/`float64`. Header lines may
//! end with CRLF, or with CR alone (old Mac files; an ASCII body may too); blank header
//! lines are skipped. A header line with an unknown keyword (Blender 2.47 writes
//! `Created by ...` lines without `comment`) is skipped with a warning naming its line,
//! as other PLY readers do.
//!
//! Read: the element named `vertex` (its `x`, `y`, `z` properties, of any scalar type;
//! every coordinate must be finite) and the element named `face` (its list
//! `vertex_indices`, or `vertex_index`, of an integer type; indices count from 0). Faces
//! of three or more vertices keep their size ([`meshvol::Faces::Polygons`] unless every
//! face is a triangle); faces of fewer vertices hold no area and are skipped with a
//! warning. Every other element and property is skipped. A file without a `face`
//! element (a point cloud) reads as a mesh with no faces.
//!
//! Triangle strips, as some old scanners and converters write them, are read too:
//!
//! ```text
//! element tristrips 1
//! property list int int vertex_indices     # -1 ends a strip
//! end_header
//! 9 0 1 2 3 -1 4 5 6 7
//! ```
//!
//! Each strip `v0 v1 v2 v3 …` gives the triangles `v0 v1 v2`, `v2 v1 v3`, `v2 v3 v4`, …
//! (every second one reversed, so all keep the strip's winding); each element instance
//! ends a strip too. Triangles that repeat a vertex (the joins writers put between
//! strips) hold no area and are left out. The strips' triangles follow the `face`
//! element's faces. Data after the last declared
//! element is ignored with a warning.
//!
//! ASCII data: one element instance per line, values separated by blanks; blank lines
//! are skipped. A line with fewer values than its element's properties is an error; one
//! with more (VCG/MeshLab writes some) is read, and a warning counts such lines. Binary
//! data: the values packed in header order, no padding.
//!
//! Counts in the header are never trusted for allocation: a binary element of fixed size
//! must fit the bytes that remain before anything is reserved, and ASCII elements are
//! counted in the file's lines first. Errors say where: the line (ASCII), or the byte and
//! element instance (binary).
//!
//! # Files
//!
//! This file: the layout (which elements hold the geometry). `body.rs`: what the body
//! readers give, strips, and the mesh. `header.rs` reads the header; `ascii.rs` and `binary.rs` read the bodies, in parallel
//! where the format allows (see each).

mod ascii;
mod binary;
mod body;
mod header;

use meshvol::Mesh;

use crate::error::ParseError;
use crate::text;
use body::Layout;
pub(crate) use header::Encoding;
use header::{Header, Kind};

/// Whether the bytes start with the PLY magic line (ended by LF, CRLF or CR).
pub(crate) fn looks_like_ply(bytes: &[u8]) -> bool {
    bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r")
}

/// Parses a PLY file; returns its encoding and mesh.
pub(crate) fn read(
    bytes: &[u8],
    warnings: &mut Vec<String>,
) -> Result<(Encoding, Mesh), ParseError> {
    // A file with CR line ends: its header and an ASCII body are read from a copy with
    // LF ones. The copy has the same length, so a binary body is read at the same offset
    // from the file's own bytes, which the copy would have changed.
    let lf = text::lf_line_ends(bytes);
    let lines = lf.as_deref().unwrap_or(bytes);
    let header = header::parse(lines, warnings)?;
    let layout = layout(&header)?;
    let body = match header.encoding {
        Encoding::Ascii => ascii::read(lines, &header, &layout, warnings, ascii::CHUNK)?,
        Encoding::BinaryLittleEndian => binary::read(bytes, &header, &layout, false, warnings)?,
        Encoding::BinaryBigEndian => binary::read(bytes, &header, &layout, true, warnings)?,
    };
    Ok((header.encoding, body.into_mesh()?))
}

fn layout(header: &Header) -> Result<Layout, ParseError> {
    let mut layout = Layout { vertex: None, face: None, strips: None, vertices: 0 };
    let find = |name: &str| header.elements.iter().position(|e| e.name == name);
    if let Some(v) = find("vertex") {
        let element = &header.elements[v];
        let mut xyz = [0; 3];
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            let p = element.property(axis).ok_or_else(|| {
                ParseError::line(
                    element.line,
                    format!("the vertex element has no property '{axis}'"),
                )
            })?;
            if !matches!(element.properties[p].kind, Kind::Scalar(_)) {
                return Err(ParseError::line(
                    element.line,
                    format!("vertex property '{axis}' is a list, not a number"),
                ));
            }
            xyz[k] = p;
        }
        layout.vertices = u32::try_from(element.count).map_err(|_| {
            ParseError::line(
                element.line,
                format!("{} vertices do not fit 32-bit indices", element.count),
            )
        })? as usize;
        layout.vertex = Some((v, xyz));
    }
    let index_list = |e: usize| -> Result<(usize, usize), ParseError> {
        let element = &header.elements[e];
        let list = element
            .property("vertex_indices")
            .or_else(|| element.property("vertex_index"))
            .ok_or_else(|| {
                ParseError::line(
                    element.line,
                    format!(
                        "the {} element has no 'vertex_indices' (or 'vertex_index') list",
                        element.name
                    ),
                )
            })?;
        match element.properties[list].kind {
            Kind::List { item, .. } if item.is_integer() => {}
            _ => {
                return Err(ParseError::line(
                    element.line,
                    format!(
                        "{} property '{}' must be a list of an integer type",
                        element.name, element.properties[list].name
                    ),
                ))
            }
        }
        if layout.vertex.is_none() && element.count > 0 {
            return Err(ParseError::line(
                element.line,
                format!("{}, but no vertex element", element.name),
            ));
        }
        Ok((e, list))
    };
    layout.face = find("face").map(index_list).transpose()?;
    layout.strips = find("tristrips").map(index_list).transpose()?;
    Ok(layout)
}
