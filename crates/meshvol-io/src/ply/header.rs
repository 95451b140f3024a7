//! The PLY header: the encoding, and each element's name, count and properties.

use crate::error::ParseError;
use crate::text;

/// How the data after the header is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Encoding {
    Ascii,
    BinaryLittleEndian,
    BinaryBigEndian,
}

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn from_name(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    pub(super) fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    pub(super) fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}
/// A property: a scalar, or a list of scalars preceded by its length.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug)]
pub(super) struct Property {
    pub name: String,
    pub kind: Kind,
}

#[derive(Debug)]
pub(super) struct Element {
    pub name: String,
    pub count: u64,
    pub properties: Vec<Property>,
    /// The header line that declared it.
    pub line: u64,
}

impl Element {
    /// The bytes of one binary record, when no property is a list.
    pub(super) fn fixed_size(&self) -> Option<usize> {
        self.properties.iter().try_fold(0usize, |sum, p| match p.kind {
            Kind::Scalar(s) => Some(sum + s.size()),
            Kind::List { .. } => None,
        })
    }

    pub(super) fn property(&self, name: &str) -> Option<usize> {
        self.properties.iter().position(|p| p.name == name)
    }
}

#[derive(Debug)]
pub(super) struct Header {
    pub encoding: Encoding,
    pub elements: Vec<Element>,
    /// Where the data starts.
    pub body: usize,
}
/// Parses the header; header lines with an unknown keyword are skipped with a warning.
pub(super) fn parse(bytes: &[u8], warnings: &mut Vec<String>) -> Result<Header, ParseError> {
    let mut pos = 0usize;
    let mut unknown: Vec<String> = Vec::new();
    let mut line_no = 0u64;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        if pos >= bytes.len() {
            return Err(ParseError::line(
                line_no.max(1),
                "the header ends without 'end_header' (the file is cut short, or not PLY)",
            ));
        }
        let end = memchr::memchr(b'\n', &bytes[pos..]).map_or(bytes.len(), |i| pos + i);
        let line = &bytes[pos..end];
        pos = (end + 1).min(bytes.len());
        line_no += 1;
        let words: Vec<&[u8]> =
            line.split(|&b| text::is_blank(b)).filter(|w| !w.is_empty()).collect();
        let bad = |message: String| ParseError::line(line_no, message);
        if line_no == 1 {
            if words.as_slice() != [b"ply"] {
                return Err(bad("expected 'ply' on the first line".into()));
            }
            continue;
        }
        let Some(&keyword) = words.first() else { continue };
        match keyword {
            b"format" => {
                encoding = Some(match words.get(1).copied() {
                    Some(b"ascii") => Encoding::Ascii,
                    Some(b"binary_little_endian") => Encoding::BinaryLittleEndian,
                    Some(b"binary_big_endian") => Encoding::BinaryBigEndian,
                    other => {
                        return Err(bad(format!(
                            "unknown format '{}' (ascii, binary_little_endian or \
                             binary_big_endian)",
                            text::show(other.unwrap_or_default())
                        )))
                    }
                });
                if !matches!(words.get(2).copied(), Some(b"1.0" | b"1")) {
                    return Err(bad(format!(
                        "unsupported PLY version '{}' (1.0 is read)",
                        text::show(words.get(2).copied().unwrap_or_default())
                    )));
                }
            }
            b"comment" | b"obj_info" => {}
            b"element" => {
                let (Some(name), Some(count), 3) = (words.get(1), words.get(2), words.len()) else {
                    return Err(bad("expected 'element NAME COUNT'".into()));
                };
                let count = std::str::from_utf8(count)
                    .ok()
                    .and_then(|c| c.parse::<u64>().ok())
                    .ok_or_else(|| bad(format!("invalid element count '{}'", text::show(count))))?;
                elements.push(Element {
                    name: text::show(name),
                    count,
                    properties: Vec::new(),
                    line: line_no,
                });
            }
            b"property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(bad("'property' before any 'element'".into()));
                };
                let type_of = |w: &[u8]| {
                    Scalar::from_name(w)
                        .ok_or_else(|| bad(format!("unknown property type '{}'", text::show(w))))
                };
                let (kind, name) = match words.as_slice() {
                    [_, b"list", count, item, name] => {
                        let count = type_of(count)?;
                        if !count.is_integer() {
                            return Err(bad("a list's count type must be an integer type".into()));
                        }
                        (Kind::List { count, item: type_of(item)? }, name)
                    }
                    [_, t, name] if *t != b"list" => (Kind::Scalar(type_of(t)?), name),
                    _ => {
                        return Err(bad(
                            "expected 'property TYPE NAME' or 'property list COUNT_TYPE \
                             ITEM_TYPE NAME'"
                                .into(),
                        ))
                    }
                };
                element.properties.push(Property { name: text::show(name), kind });
            }
            b"end_header" => break,
            other => unknown.push(format!("line {line_no} ('{}')", text::show(other))),
        }
    }
    if !unknown.is_empty() {
        const SHOWN: usize = 8;
        let more = unknown.len().saturating_sub(SHOWN);
        warnings.push(format!(
            "skipped {} header lines with an unknown keyword: {}{}",
            unknown.len(),
            unknown[..unknown.len().min(SHOWN)].join(", "),
            if more > 0 { format!(" and {more} more") } else { String::new() }
        ));
    }
    let Some(encoding) = encoding else {
        return Err(ParseError::line(2, "the header has no 'format' line"));
    };
    Ok(Header { encoding, elements, body: pos })
}
