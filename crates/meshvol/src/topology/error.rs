//! Why a check stops ([`CheckError`]) and each stage's start ([`enter`]): a leaf below mod.rs.

use crate::progress::StageReport;

/// Why a surface could not be checked.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum CheckError {
    #[error("{corners} face corners: checks index corners with 32 bits (at most 4294967295)")]
    TooLarge { corners: usize },
    #[error("{faces} faces: checks number faces with 31 bits (at most 2147483646)")]
    TooManyFaces { faces: usize },
    /// The caller's hook said the result is no longer wanted
    /// ([`Progress::cancelled`](crate::progress::Progress::cancelled)).
    #[error("the check was cancelled")]
    Cancelled,
}

/// Starts the stage `name`, unless the caller has cancelled the check: each stage is
/// near-linear in the faces, so a cancelled check stops within one stage's time.
pub(super) fn enter(stage: StageReport<'_>, name: &'static str) -> Result<(), CheckError> {
    if stage.cancelled() {
        return Err(CheckError::Cancelled);
    }
    stage.stage(name);
    Ok(())
}
