//! One upload measured: bytes → reader → check → the reports and the view, exactly as
//! `meshvol check --json` and `meshvol volume --json` make them.

use crate::config::Budgets;
use meshvol::grid::{Axis, Levels};
use meshvol::progress::Progress;
use meshvol::topology::{self, CheckError, CheckOptions};
use meshvol_io::{Budget, Limits};
use meshvol_report::check::{check, CheckReport};
use meshvol_report::checked::check_loaded;
use meshvol_report::profile::{profile, ProfileReport};
use meshvol_report::quantities::Quantities;
use meshvol_report::subject::{Source, Subject};
use meshvol_report::units::{Density, UnitOptions};
use meshvol_report::view::{view, View};
use meshvol_report::view_slices::{slices, Slices};
use meshvol_report::volume::{volume, VolumeOptions, VolumeReport};
use serde::Serialize;
use std::path::Path;

/// What the page asks for, as the command's flags do.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// `--units` and `--density`.
    pub units: UnitOptions,
    /// `--weld-tolerance` and `--no-intersections`.
    pub check: CheckOptions,
}

/// What the page shows of one file: `check`'s report, `volume`'s and `profile`'s
/// (`--levels 128` along z; both absent for a file without faces: it has no volume to
/// report; the profile absent too for a solid flat along z), the sections and grid under the slider (`view_slices`; absent too for a
/// solid flat along an axis) and the view.
#[derive(Debug, Serialize)]
pub struct Page {
    pub check: CheckReport,
    pub volume: Option<VolumeReport>,
    pub profile: Option<ProfileReport>,
    pub slices: Option<Slices>,
    pub view: View,
}

/// The profile's levels on the page: its chart, and the volume below the clip slider.
///
/// Twice the sections' 64 layers: every other level is a section's level (the middle of
/// its layer), so the volume below shown beside a section is at the section's level.
pub const PROFILE_LEVELS: usize = 128;

/// An upload's name as a file name: its last path component, without control
/// characters; `upload` when nothing is left.
pub fn file_name(given: &str) -> String {
    let last = given.rsplit(['/', '\\']).next().unwrap_or_default();
    let clean: String = last.chars().filter(|c| !c.is_control()).collect();
    match clean.trim() {
        "" | "." | ".." => "upload".to_string(),
        name => name.to_string(),
    }
}

/// Why an upload was not measured.
#[derive(Debug)]
pub enum Failure {
    /// No reader takes it, or the check refuses it: the command's error.
    Unreadable(String),
    /// It goes past a budget, named by its flag.
    Over { budget: &'static str, message: String },
    /// Reading and checking it would need more memory than the server has available:
    /// another time, or another server, may have it.
    NoMemory(String),
    /// `hook` said the answer is no longer wanted.
    Cancelled,
}

/// Why a read was refused: past one of the budgets that the request's flags set, or the
/// memory the server has.
fn refused(budget: Budget, message: String) -> Failure {
    let budget = match budget {
        Budget::InflatedBytes => "--max-inflated",
        Budget::Placements => "--max-placements",
        Budget::Faces => "--max-faces",
        Budget::Memory => return Failure::NoMemory(message),
    };
    Failure::Over { budget, message }
}

/// Reads `bytes`, uploaded as `name` (a plain file name), as if it were a file of that
/// name in `folder` (an empty folder of the server's own: a glTF's external buffers are
/// looked for there, and found nowhere, unless the upload is a zip that holds them),
/// within `budgets`; checks it and reports, with `view` the page's geometry too. The
/// check, and each step after it, first asks `hook` whether it is still wanted. Errors
/// name the file as uploaded.
pub fn measure(
    folder: &Path,
    name: &str,
    bytes: Vec<u8>,
    options: &Options,
    with_view: bool,
    budgets: &Budgets,
    hook: &dyn Progress,
) -> Result<(CheckReport, Option<Page>), Failure> {
    let path = folder.join(name);
    let unfold = |e: String| e.replace(&format!("{}/", folder.display()), "");
    let limits = Limits {
        inflated_bytes: budgets.inflated_bytes,
        placements: budgets.placements,
        faces: budgets.faces,
        // The server's own memory, as the command's: an upload too large for it is
        // refused before it is parsed, not a server the system kills.
        memory: meshvol_io::memory::available_memory(),
        checked: true,
    };
    let loaded = meshvol_io::read_bytes_within(&path, bytes, &limits).map_err(|e| {
        let message = unfold(e.to_string());
        match e.budget {
            Some(budget) => refused(budget, message),
            None => Failure::Unreadable(message),
        }
    })?;
    let faces = loaded.face_count() as u64;
    if faces > budgets.faces {
        let message = format!("{name}: {faces} faces; more than {} are not checked", budgets.faces);
        return Err(Failure::Over { budget: "--max-faces", message });
    }
    let c = check_loaded(name, &loaded, &options.check, hook).map_err(|e| match e.error {
        CheckError::Cancelled => Failure::Cancelled,
        _ => Failure::Unreadable(e.to_string()),
    })?;
    let source = Source::of(name, &loaded);
    let report =
        check(&source, &c).in_units(&options.units, loaded.unit).map_err(Failure::Unreadable)?;
    if !with_view {
        return Ok((report, None));
    }
    if hook.cancelled() {
        return Err(Failure::Cancelled);
    }
    let page = page(&source, &loaded.surface, &c, report.clone(), &options.units)
        .map_err(Failure::Unreadable)?;
    Ok((report, Some(page)))
}

/// The page's content for a surface read from `source` and checked as `c`, whose
/// `check` report is `report`.
pub fn page<S: meshvol::Surface>(
    source: &Source,
    surface: &S,
    c: &topology::Check,
    report: CheckReport,
    units: &UnitOptions,
) -> Result<Page, String> {
    let subject = Subject { source, surface, check: Some(c) };
    let (volume, profile, slices) = if surface.face_count() == 0 {
        (None, None, None)
    } else {
        let options = VolumeOptions {
            density: units.density.unwrap_or(Density::plain(1.0)),
            units: units.units,
            exact: false,
        };
        let volume = volume(&subject, &options)?;
        // A solid flat along z (a sheet lying in a plane) has nothing to profile.
        let profile = if volume.bounds.as_ref().is_some_and(|b| b.max[2] > b.min[2]) {
            let levels = Levels::Count(PROFILE_LEVELS);
            Some(profile(&subject, Axis::Z, levels)?.in_units(units, source.unit)?)
        } else {
            None
        };
        (Some(volume), profile, slices(&subject, units)?)
    };
    Ok(Page { check: report, volume, profile, slices, view: view(surface, c) })
}

#[cfg(test)]
mod tests {
    use super::file_name;

    #[test]
    fn upload_names_lose_their_folders_and_control_characters() {
        assert_eq!(file_name("part.stl"), "part.stl");
        assert_eq!(file_name("../../etc/passwd"), "passwd");
        assert_eq!(file_name("C:\\parts\\a.obj"), "a.obj");
        assert_eq!(file_name("a\nb.obj"), "ab.obj");
        assert_eq!(file_name(".."), "upload");
        assert_eq!(file_name(""), "upload");
    }
}
