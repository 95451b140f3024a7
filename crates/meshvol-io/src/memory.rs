//! The memory guard: a file refused before it is parsed when reading it, and checking
//! it, would need more memory than the machine has available: an error naming the file,
//! the estimate and the figure available, instead of a process the system kills part way
//! (or an allocation it overcommits, which kills it later).
//!
//! The estimate comes from what is known before parsing: a binary STL's triangle count
//! (its header, which the size rule has confirmed); for the other formats, the triangles
//! a file of that size holds at most when written as exporters write it (coordinates
//! with six decimals: fewer digits, more triangles a byte, are underestimated). Each
//! triangle then costs what the reader and the check were measured to hold at their
//! peak, and the file's own bytes (mapped or in memory) are counted too. The figures
//! below were measured by tests/memory_estimate.rs (the allocator counting the heap's
//! peak while a generated sphere of 100,800 triangles is read and checked in each
//! format), which also checks that every estimate is above its peak.
//!
//! The memory available is `MESHVOL_MEMORY_LIMIT` bytes when set (a machine's own cap,
//! and how tests force a refusal), else Linux's `MemAvailable`; where neither is known,
//! nothing is refused. The grid's estimate (`meshvol grid`) compares with the same
//! figure.

use crate::error::{Budget, ParseError};
use crate::family::Family;
use crate::{gltf, stl};
use meshvol::grid::bytes_text;

pub use crate::source::{available_memory, MEMORY_LIMIT_VARIABLE};

/// What a triangle costs in one layout: the fewest file bytes it takes as exporters
/// write it, and the heap's bytes at the peak of reading the file, and of reading and
/// checking it (the file's own bytes are counted apart). Measured by
/// tests/memory_estimate.rs on a sphere of 100,800 triangles (in brackets after each:
/// file bytes, heap read, heap checked): `file` a little under what was measured, the
/// others 1.4 to 1.9 times what was measured, since the heap counted there is not all of the
/// process's resident memory, and a vector growing by doubling may hold more at another
/// size. A binary STL's pages are let go once welded, so its file and its check do not
/// peak together: a checked binary STL of 5 and 20 million triangles peaked at 104 and
/// 101 bytes a triangle resident, file included (issue 53), against 170 estimated here. Text with fewer digits
/// than six decimals holds more triangles a byte than estimated.
struct Cost {
    file: u128,
    read: u128,
    checked: u128,
}

/// A binary STL, read in place: its triangle count is its header's, and `file` the size
/// of its records.
const BINARY_STL: Cost = Cost { file: 50, read: 8, checked: 120 }; // (50, 0.2, 107)
const ASCII_STL: Cost = Cost { file: 140, read: 250, checked: 280 }; // (153.5, 164, 191)
const OBJ: Cost = Cost { file: 30, read: 150, checked: 200 }; // (34.6, 103, 131)
const OFF: Cost = Cost { file: 30, read: 70, checked: 200 }; // (33.6, 44, 131)
const PLY_ASCII: Cost = Cost { file: 30, read: 150, checked: 200 }; // (33.6, 105, 131)
/// `float` positions, `uchar` counts and `int` indices, as scanners write them.
const PLY_BINARY: Cost = Cost { file: 17, read: 40, checked: 200 }; // (19.0, 24, 131)
/// `f32` positions and `u32` indices.
const GLB: Cost = Cost { file: 16, read: 70, checked: 200 }; // (18.0, 48, 131)
/// A GLB's buffer in base64 in the JSON (a buffer in another file is not counted).
const GLTF: Cost = Cost { file: 21, read: 130, checked: 200 }; // (24.0, 90, 131)
/// Deflated XML: the model part is inflated whole before it is parsed.
const THREE_MF: Cost = Cost { file: 6, read: 180, checked: 200 }; // (7.1, 123, 131)

/// The cost of a triangle of `bytes`, a file of `family` other than a binary STL.
fn cost(family: Family, bytes: &[u8]) -> Cost {
    match family {
        // A binary STL is counted by its header (see [`estimate`]).
        Family::Stl => ASCII_STL,
        Family::Obj => OBJ,
        Family::Off => OFF,
        Family::Ply if ply_is_ascii(bytes) => PLY_ASCII,
        Family::Ply => PLY_BINARY,
        Family::Gltf if gltf::looks_like_glb(bytes) => GLB,
        Family::Gltf => GLTF,
        Family::ThreeMf => THREE_MF,
    }
}

/// Whether a PLY's header says `format ascii` (its first lines: the header is short).
fn ply_is_ascii(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(256)];
    head.windows(12).any(|w| w == b"format ascii")
}

/// What reading (and checking) a file is estimated to need.
pub(crate) struct Estimate {
    /// The triangles: a binary STL's count, else the most a file of its size holds.
    pub triangles: u128,
    /// Whether `triangles` is the file's own count.
    pub exact: bool,
    pub bytes: u128,
}

/// The estimate for `bytes` of `family`, read and, if `checked`, checked.
pub(crate) fn estimate(family: Family, bytes: &[u8], checked: bool) -> Estimate {
    let len = bytes.len() as u128;
    let (triangles, exact, cost) = match stl::classify(bytes) {
        Ok(stl::Kind::Binary { triangles, .. }) if family == Family::Stl => {
            (triangles as u128, true, BINARY_STL)
        }
        _ => {
            let cost = cost(family, bytes);
            (len.div_ceil(cost.file), false, cost)
        }
    };
    let per_triangle = if checked { cost.checked } else { cost.read };
    Estimate { triangles, exact, bytes: triangles * per_triangle + len }
}

/// An error unless reading `bytes` of `family` (and, if `checked`, checking it) fits in
/// `available` bytes (`None`: unknown, not refused): called before the file is parsed.
/// (The read's [`crate::Limits`] give both.)
pub(crate) fn fits(
    family: Family,
    bytes: &[u8],
    available: Option<u128>,
    checked: bool,
) -> Result<(), ParseError> {
    let Some(available) = available else { return Ok(()) };
    let need = estimate(family, bytes, checked);
    if need.bytes <= available {
        return Ok(());
    }
    let doing = if checked { "reading and checking" } else { "reading" };
    let triangles = if need.exact {
        format!("{} triangles", need.triangles)
    } else {
        format!(
            "a {} {} (up to {} triangles)",
            bytes_text(bytes.len() as u128),
            family.name(),
            need.triangles
        )
    };
    let message = format!(
        "{doing} {triangles} needs about {}; {} is available (the estimate errs high: \
         {MEMORY_LIMIT_VARIABLE}=BYTES sets the figure available, to try anyway)",
        bytes_text(need.bytes),
        bytes_text(available)
    );
    Err(ParseError::new(None, message).over(Budget::Memory))
}
