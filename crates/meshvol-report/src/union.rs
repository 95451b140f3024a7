//! `union`: the volume of the union of bodies as a certified interval, widened by the
//! caps' uncertainty, with the warnings that say when it is not certified.

use crate::number::{count, num};
use crate::quantities::{Converter, Dimension::*, Quantities};
use crate::subject::{joined_names, union_bodies, Subject};
use crate::units::{Mass, UnitNames};
use crate::Report;
use meshvol::grid::union_with as kernel;
use meshvol::progress::Progress;
use meshvol::Surface;
use serde::Serialize;
use std::fmt::Write;
use std::time::Instant;

/// The report. Field names are the JSON keys.
#[derive(Clone, Debug, Serialize)]
pub struct UnionReport {
    /// The inputs, joined by `, `.
    pub file: String,
    pub files: Vec<String>,
    /// `lower`, `upper`, `certified` (proven to hold the union of the measured solids),
    /// `uncertified_reason`, `volume` (the midpoint).
    #[serde(flatten)]
    pub interval: CertifiedInterval,
    pub bodies: usize,
    /// Each body's name: `FILE`, or `FILE, shell N` for the bodies of a single input
    /// (`FILE, OBJECT (shell N)` where its objects are bodies).
    pub body_names: Vec<String>,
    /// Σ of the bodies' volumes (overlaps counted more than once).
    pub sum_of_volumes: f64,
    pub cells_refined: usize,
    pub cells_resolved_exactly: usize,
    /// Grid columns left unresolved: their bounds stay in the interval.
    pub columns_unresolved: usize,
    /// Bodies wound inward, measured turned outward (indices into `body_names`).
    pub flipped: Vec<usize>,
    /// How far the caps on the bodies' holes could put the volume off; the interval is
    /// widened by it (0 for closed bodies).
    pub volume_uncertainty: f64,
    /// The base grid's cells.
    pub grid: [usize; 3],
    pub seconds: f64,
    /// The units the numbers are in (`--units`, or the unit the file declares); null:
    /// the file's own numbers, unit unknown.
    pub units: Option<UnitNames>,
    /// With `--density`: `density`, `density_unit`, `mass`, `mass_unit`.
    #[serde(flatten)]
    pub mass: Option<Mass>,
    pub warnings: Vec<String>,
}

/// The union of the bodies of `subjects` (one input: its bodies; several: each whole),
/// refined until `upper − lower ≤ tolerance · lower` where it can be.
pub fn union<S: Surface + Sync>(
    subjects: &[Subject<'_, S>],
    tolerance: f64,
) -> Result<UnionReport, String> {
    union_with(subjects, tolerance, &())
}

/// [`union`], telling `progress` the kernel's stages and how far each is.
pub fn union_with<S: Surface + Sync>(
    subjects: &[Subject<'_, S>],
    tolerance: f64,
    progress: &dyn Progress,
) -> Result<UnionReport, String> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(format!("tolerance must be a positive number; got {tolerance}"));
    }
    let mut warnings = crate::subject::input_warnings(subjects);
    let (bodies, names): (Vec<_>, Vec<String>) =
        union_bodies(subjects).into_iter().map(|b| (b.surface, b.name)).unzip();
    if bodies.is_empty() {
        return Err("no faces: there is no body to measure".into());
    }
    let start = Instant::now();
    let mut u = kernel(&bodies, tolerance, progress).map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    // Caps on holes are guesses: the interval must hold whatever the missing faces were.
    let uncertainty: f64 = subjects.iter().map(Subject::volume_uncertainty).sum();
    u.lower = (u.lower - uncertainty).max(0.0);
    u.upper += uncertainty;
    // A single input's bodies are its outermost shells and objects, each apart; several
    // inputs are each one body, whole.
    let whole = subjects.len() > 1;
    let certification = uncertified(subjects, whole, u.bodies_not_solid.len());
    warnings.extend(
        Interval {
            names: &names,
            flipped: &u.flipped,
            flipped_note: " (if it is a cavity, the union of shells is not what you want)",
            not_solid: &u.bodies_not_solid,
            columns_unresolved: u.columns_unresolved,
            bounds: (u.lower, u.upper),
            tolerance,
            uncertainty,
        }
        .warnings(),
    );
    Ok(UnionReport {
        file: joined_names(subjects),
        files: subjects.iter().map(|s| s.source.name().to_string()).collect(),
        interval: CertifiedInterval::new((u.lower, u.upper), u.volume(), certification),
        bodies: u.bodies,
        body_names: names,
        sum_of_volumes: u.sum_of_volumes,
        cells_refined: u.cells_refined,
        cells_resolved_exactly: u.cells_resolved_exactly,
        columns_unresolved: u.columns_unresolved,
        flipped: u.flipped,
        volume_uncertainty: uncertainty,
        grid: u.grid.counts,
        seconds,
        units: None,
        mass: None,
        warnings,
    })
}

/// The volume as the union's machinery (`union`, `intersect`) gives it: an interval,
/// whether it is certified, and its midpoint. Flattened into the reports: the field names
/// are their JSON keys.
#[derive(Clone, Debug, Serialize)]
pub struct CertifiedInterval {
    /// `lower ≤ volume ≤ upper`.
    pub lower: f64,
    pub upper: f64,
    /// Whether [lower, upper] is proven to hold the volume of the measured solids (see
    /// [`uncertified`]: the rule).
    pub certified: bool,
    /// Why it is not, when it is not (null when certified).
    pub uncertified_reason: Option<String>,
    /// The midpoint of [lower, upper].
    pub volume: f64,
}

impl CertifiedInterval {
    /// `bounds` with their `midpoint`, certified unless there is a reason it is not
    /// (`uncertified`'s).
    pub fn new((lower, upper): (f64, f64), midpoint: f64, uncertified: Option<String>) -> Self {
        let certified = uncertified.is_none();
        CertifiedInterval {
            lower,
            upper,
            certified,
            uncertified_reason: uncertified,
            volume: midpoint,
        }
    }

    /// The bounds and midpoint in reported units (the bounds widened outward).
    pub(crate) fn convert(&mut self, to: &Converter) {
        to.interval(&mut self.lower, &mut self.upper);
        to.one(Volume, &mut self.volume);
    }

    /// The text lines of the interval: its midpoint, its bounds and width, `certified`
    /// only when it is (else the reason it is not), and the caps' share of it.
    pub(crate) fn text(&self, s: &mut String, caps: f64) {
        let (lower, upper) = (self.lower, self.upper);
        let _ = writeln!(s, "  volume           {}  (midpoint)", num(self.volume, 15));
        let bounds = format!("[{}, {}]", num(lower, 17), num(upper, 17));
        let width = num(upper - lower, 3);
        let _ = match &self.uncertified_reason {
            None => writeln!(s, "  certified        {bounds}  (width {width})"),
            Some(why) => {
                writeln!(s, "  interval         {bounds}  (width {width}; not certified: {why})")
            }
        };
        if caps > 0.0 {
            let _ = writeln!(s, "  caps on holes    ± {} (in the interval)", num(caps, 4));
        }
    }
}

/// Why the interval of the union's machinery (`union`, `intersect`) over `subjects` is
/// not certified, `None` when it is. The kernel proves its bounds for closed solids that
/// do not cross themselves, so it is certified when every body was checked, no body's
/// cell volumes left their bounds (`not_solid` bodies did), no surface crosses itself, a
/// body taken whole (`whole`: each input one body) holds no shells or objects that
/// overlap (its solid would count their common volume twice), and no hole was capped by
/// a guess (a ragged cap's uncertainty is an estimate, not a bound; a flat hole's cap is
/// exact).
pub(crate) fn uncertified<S: Surface>(
    subjects: &[Subject<'_, S>],
    whole: bool,
    not_solid: usize,
) -> Option<String> {
    let named = |s: &Subject<'_, S>, why: String| match subjects {
        [_] => why,
        _ => format!("{}: {why}", s.source.name()),
    };
    if let Some(s) = subjects.iter().find(|s| s.check.is_none()) {
        return Some(named(s, "measured unchecked, so not known to be closed solids".into()));
    }
    if not_solid > 0 {
        return Some(format!(
            "{} not a closed solid (volume outside a cell's bounds)",
            count(not_solid, "body is", "bodies are")
        ));
    }
    for s in subjects {
        let Some(c) = s.check else { continue };
        if let Some(n) = c.self_intersections.filter(|&n| n > 0) {
            let pairs = count(n, "self-intersecting face pair", "self-intersecting face pairs");
            return Some(named(s, format!("the surface crosses itself ({pairs})")));
        }
        if whole && !(c.overlapping_shells.is_empty() && c.overlapping_bodies.is_empty()) {
            return Some(named(
                s,
                "its shells or objects overlap, so as one body it counts their common \
                     volume twice"
                    .into(),
            ));
        }
        if c.volume_uncertainty > 0.0 {
            return Some(named(
                s,
                "holes capped by a guess (their uncertainty is an estimate)".into(),
            ));
        }
    }
    None
}

/// What a certified interval from the union's machinery (`union`, `intersect`) says
/// about its bodies and its width.
pub(crate) struct Interval<'a> {
    /// The bodies' names, indexed by `flipped` and `not_solid`.
    pub names: &'a [String],
    pub flipped: &'a [usize],
    /// Added to the warning about a body wound inward.
    pub flipped_note: &'a str,
    pub not_solid: &'a [usize],
    pub columns_unresolved: usize,
    pub bounds: (f64, f64),
    pub tolerance: f64,
    /// The caps' uncertainty in the interval.
    pub uncertainty: f64,
}

impl Interval<'_> {
    /// Bodies wound inward or not solid, columns unresolved, an interval wider than the
    /// tolerance.
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings = Vec::new();
        for &b in self.flipped {
            warnings.push(format!(
                "{}: wound inward (negative volume); measured as a solid turned outward{}",
                self.names[b], self.flipped_note
            ));
        }
        for &b in self.not_solid {
            warnings.push(format!(
                "{}: not a closed solid (its volume in some cells leaves [0, cell volume]): the \
                 interval is ordered but not certified",
                self.names[b]
            ));
        }
        if self.columns_unresolved > 0 {
            warnings.push(format!(
                "{} of the grid could not be resolved exactly; the interval keeps their bounds",
                count(self.columns_unresolved, "column", "columns")
            ));
        }
        let (lower, upper) = self.bounds;
        if upper - lower > self.tolerance * lower.abs() {
            let why = if self.uncertainty > 0.0 {
                "the caps on holes leave it uncertain"
            } else {
                "refinement and exact resolution could not close it"
            };
            warnings.push(format!(
                "the interval is wider than the tolerance {}: {why}",
                self.tolerance
            ));
        }
        warnings
    }
}

impl Report for UnionReport {
    fn file(&self) -> &str {
        &self.file
    }

    fn warnings(&self) -> &[String] {
        &self.warnings
    }

    fn text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "union of {}: {}",
            count(self.bodies, "body", "bodies"),
            self.body_names.join("; ")
        );
        self.interval.text(&mut s, self.volume_uncertainty);
        let _ = writeln!(s, "  sum of volumes   {}", num(self.sum_of_volumes, 15));
        grid_text(&mut s, self.grid, self.cells_refined, self.cells_resolved_exactly);
        footer_text(&mut s, self.seconds, &self.units, &self.mass);
        s
    }
}

/// The grid line of `union`'s and `intersect`'s text: its cells, how many were refined
/// and how many resolved exactly.
pub(crate) fn grid_text(s: &mut String, [nx, ny, nz]: [usize; 3], refined: usize, exact: usize) {
    let refined = count(refined, "cell", "cells");
    let _ = writeln!(
        s,
        "  grid             {nx}×{ny}×{nz}, {refined} refined, {exact} resolved exactly"
    );
}

/// The last lines of `union`'s and `intersect`'s text: the time, the units and mass.
pub(crate) fn footer_text(
    s: &mut String,
    seconds: f64,
    units: &Option<UnitNames>,
    mass: &Option<Mass>,
) {
    let _ = writeln!(s, "  time             {seconds:.3} s");
    s.push_str(&crate::units::units_text(units, mass));
}

impl Quantities for UnionReport {
    fn convert(&mut self, to: &Converter) {
        self.interval.convert(to);
        to.all(Volume, [&mut self.sum_of_volumes, &mut self.volume_uncertainty]);
    }

    /// The interval's midpoint's.
    fn mass_basis(&self) -> f64 {
        self.interval.volume
    }

    crate::unit_slots!();
}
