//! The one solid behind every number: a file read (by `meshvol_io`, from a path, from
//! standard input or from an upload) and checked the one way that the command, the
//! server (`meshvol serve`) and Python's batch (`meshvol.measure`) all take. Without
//! check options the surface is measured as wound (`--no-check`, `check=False`).

use crate::subject::{Source, Subject};
use meshvol::progress::Progress;
use meshvol::topology::{check_assembled, Check, CheckError, CheckOptions};
use meshvol_io::{Loaded, LoadedSurface};
use std::fmt;

/// A file read and, unless asked not to, checked: what every report measures.
pub struct Checked {
    pub source: Source,
    pub surface: LoadedSurface,
    /// The check the solid comes from; `None`: the surface as wound.
    pub check: Option<Check>,
}

/// Why a file read was not checked: the check's error, and the file it names.
#[derive(Debug)]
pub struct Unchecked {
    pub file: String,
    pub error: CheckError,
}

impl fmt::Display for Unchecked {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.file, self.error)
    }
}

impl Checked {
    /// `loaded`, read from the file named `file`, checked with `options`
    /// ([`check_loaded`]); `None`: not checked.
    pub fn of(
        file: &str,
        loaded: Loaded,
        options: Option<&CheckOptions>,
        progress: &dyn Progress,
    ) -> Result<Checked, Unchecked> {
        let check = match options {
            None => None,
            Some(options) => Some(check_loaded(file, &loaded, options, progress)?),
        };
        let source = Source::of(file, &loaded);
        Ok(Checked { source, surface: loaded.surface, check })
    }

    /// The solid as the reports take it.
    pub fn subject(&self) -> Subject<'_, LoadedSurface> {
        Subject { source: &self.source, surface: &self.surface, check: self.check.as_ref() }
    }
}

/// The error of a measuring command for a file without faces (`volume` and the others
/// refuse it, before its check: there is nothing to measure; `check` reports it).
pub fn refuse_empty(file: &str, loaded: &Loaded) -> Result<(), String> {
    if loaded.face_count() == 0 {
        return Err(format!("{file}: {}", crate::volume::NO_FACES));
    }
    Ok(())
}

/// The check of `loaded`, read from the file named `file`, with `options`: each of the
/// file's bodies on its own (`topology::check_assembled`), telling `progress` its stages.
pub fn check_loaded(
    file: &str,
    loaded: &Loaded,
    options: &CheckOptions,
    progress: &dyn Progress,
) -> Result<Check, Unchecked> {
    let (assembly, bodies) = (loaded.assembly.as_ref(), loaded.body_faces());
    check_assembled(&loaded.surface, assembly, &bodies, options, progress)
        .map_err(|error| Unchecked { file: file.to_string(), error })
}
