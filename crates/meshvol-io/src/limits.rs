//! What one read may cost, checked before the work it bounds: the bytes a compressed
//! input (or a 3MF part) inflates to, the placed copies a 3MF build or a glTF scene
//! expands to, the faces of that expansion, and the memory of reading (and checking)
//! the file ([`crate::memory`]). The command reads with
//! [`Limits::from_env`]; a server reading uploads sets its own per request
//! ([`crate::read_bytes_within`]), and an error past one names it ([`Budget`]).

pub use crate::error::Budget;
use crate::error::ParseError;
use crate::source::{available_memory, stream_limit};

/// The limits of one read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// The most bytes a compressed input, a zip's member or a 3MF part inflates to.
    pub inflated_bytes: u64,
    /// The most placed copies (3MF build items and components expanded, glTF nodes
    /// placing a mesh).
    pub placements: u64,
    /// The most triangles the placed copies expand to.
    pub faces: u64,
    /// The bytes of memory the read, and the check after it, may use: a file estimated
    /// to need more is refused before it is parsed. `None` where unknown: not refused.
    pub memory: Option<u128>,
    /// Whether the file is checked after it is read: the check's memory is counted.
    pub checked: bool,
}

/// The placed copies read without another limit: a 6 KB 3MF can place a part this
/// often, and 10⁷ copies are checked in tens of seconds (docs/security.md).
const MAX_PLACEMENTS: u64 = 10_000_000;

impl Limits {
    /// The command's limits: [`stream_limit`] inflated bytes (`MESHVOL_MAX_STREAM_BYTES`,
    /// 2 GiB), 10⁷ placements, faces bounded by the bytes only, and the memory available
    /// ([`available_memory`]: `MESHVOL_MEMORY_LIMIT`, else the system's) for a read that
    /// a check follows.
    pub fn from_env() -> Limits {
        Limits {
            inflated_bytes: stream_limit(),
            placements: MAX_PLACEMENTS,
            faces: u64::MAX,
            memory: available_memory(),
            checked: true,
        }
    }

    /// An error unless an expansion into `placements` copies of `faces` triangles in all
    /// is within the limits: called before anything is reserved for it.
    pub(crate) fn expansion(&self, faces: u64, placements: u64) -> Result<(), ParseError> {
        if placements > self.placements {
            let message = format!(
                "the build expands to {placements} placed objects; more than {} are not read",
                self.placements
            );
            return Err(ParseError::new(None, message).over(Budget::Placements));
        }
        if faces > self.faces {
            let message = format!(
                "the placed parts have {faces} triangles in all; more than {} are not read",
                self.faces
            );
            return Err(ParseError::new(None, message).over(Budget::Faces));
        }
        Ok(())
    }
}
