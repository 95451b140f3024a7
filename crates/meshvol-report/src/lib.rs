//! meshvol's report layer: what the user sees of a kernel result.
//!
//! Each command's report is a struct here ([`volume::VolumeReport`],
//! [`check::CheckReport`], [`grid::GridReport`], [`profile::ProfileReport`],
//! [`union::UnionReport`], [`intersect::IntersectReport`], [`section::SectionReport`], [`area::AreaReport`],
//! [`hull::HullReport`], [`repair::RepairReport`], [`cutfill::CutFillReport`]): built from the kernels' results by
//! one function, serialized by serde into the JSON the `meshvol` command prints (field
//! names are the keys: a public contract, see docs/json.md) and into the dicts of the
//! Python bindings' `to_dict()`, and rendered as text by the [`Report`] trait. Unit
//! conversion ([`units`]) and the widening of error bounds it needs, the memory estimate
//! of a grid, the reasons to doubt a solid and the rule that makes bodies of a union
//! ([`subject`]) live here and nowhere else. So does the rule that a mesh written
//! (`repair -o`, `hull --out`, Python's `Mesh.save`) is read back and compared with the
//! solid reported before it is kept ([`written`]).
//!
//! Data flows one way: the CLI and Python read or build a surface, check it, wrap it as a
//! [`subject::Subject`], and hand it to a report function; they print or convert what
//! comes back. This crate never prints.

/// `Report::file` and `Report::warnings` of a report with the fields `file` (an
/// `Option<String>`, named `$unnamed` when `None`: a surface from arrays) and `warnings`.
macro_rules! file_and_warnings {
    ($unnamed:literal) => {
        fn file(&self) -> &str {
            self.file.as_deref().unwrap_or($unnamed)
        }

        fn warnings(&self) -> &[String] {
            &self.warnings
        }
    };
}
pub(crate) use file_and_warnings;

pub mod area;
pub mod below;
pub mod check;
pub mod checked;
pub mod cutfill;
pub mod devices;
pub mod grid;
pub mod hull;
pub mod inertial;
pub mod intersect;
pub mod number;
pub mod plane;
pub mod profile;
pub mod quantities;
pub mod repair;
pub mod reported_cells;
pub mod section;
pub mod subject;
pub mod table;
pub mod timings;
pub mod union;
pub mod units;
pub mod view;
pub mod view_slices;
pub mod volume;
pub mod written;

pub(crate) use quantities::unit_slots;

use serde::Serialize;

/// A command's report about one input (or one set of inputs): JSON through serde, text
/// through [`Report::text`].
///
/// Every report has the JSON keys `file` and `warnings`.
pub trait Report: Serialize {
    /// The file reported on, as given (several files: their names joined by `, `).
    fn file(&self) -> &str;
    /// The readers' warnings, the reasons to doubt the solid, and the report's own.
    fn warnings(&self) -> &[String];
    /// The human-readable report.
    fn text(&self) -> String;
    /// False when the input was measured but fails what the command tests (`check`: it
    /// does not bound a volume); the command then exits with status 1.
    fn passed(&self) -> bool {
        true
    }
}

/// One JSON object on one line, newline included.
pub fn json_line(report: &impl Serialize) -> Result<String, String> {
    serde_json::to_string(report).map(|s| s + "\n").map_err(|e| e.to_string())
}

/// The JSON line of an input that failed: `{"file": ..., "error": ...}`, in that order
/// whatever serde_json's features (a `json!` map's order is sorted, or the order written
/// where a dependency such as zarrs turns on `preserve_order`).
pub fn error_line(file: &str, error: &str) -> String {
    #[derive(Serialize)]
    struct ErrorLine<'a> {
        file: &'a str,
        error: &'a str,
    }
    let line = ErrorLine { file, error };
    serde_json::to_string(&line).unwrap_or_default() + "\n"
}
