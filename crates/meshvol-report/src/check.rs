//! `check`: can the volume be trusted? The same facts appear in `volume`'s report.

use crate::number::{count, num};
use crate::quantities::{Converter, Dimension::*, Quantities};
use crate::subject::Source;
use crate::units::{Mass, UnitNames};
use crate::Report;
use meshvol::topology::{Check, Orientation, Shell};
use serde::ser::{SerializeStruct, Serializer};
use serde::Serialize;
use std::fmt::Write;

/// One shell in the report: the check's [`Shell`], whose facts are its JSON keys, all but
/// `consistently_oriented` (the report says that of the whole surface).
#[derive(Clone, Debug)]
pub struct ShellReport(pub Shell);

impl Serialize for ShellReport {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let shell = &self.0;
        let mut keys = serializer.serialize_struct("ShellReport", 10)?;
        keys.serialize_field("faces", &shell.faces)?;
        keys.serialize_field("closed", &shell.closed)?;
        keys.serialize_field("orientable", &shell.orientable)?;
        keys.serialize_field("volume", &shell.volume)?;
        keys.serialize_field("cavity", &shell.cavity)?;
        keys.serialize_field("parent", &shell.parent)?;
        keys.serialize_field("wound_outward", &shell.wound_outward)?;
        keys.serialize_field("boundary_loops", &shell.boundary_loops)?;
        keys.serialize_field("euler_characteristic", &shell.euler_characteristic)?;
        keys.serialize_field("genus", &shell.genus)?;
        keys.end()
    }
}

/// Two of a file's objects (its bodies: 3MF, glTF) that share volume.
#[derive(Clone, Debug, Serialize)]
pub struct ObjectOverlap {
    /// Their names, as the file gives them (`object N` for an unnamed one).
    pub objects: [String; 2],
    /// One lies inside the other's material, their surfaces apart; else they cross.
    pub nested: bool,
}

/// The topology facts. Field names are JSON keys; `volume` flattens them into its
/// report.
#[derive(Clone, Debug, Serialize)]
pub struct CheckFacts {
    pub bounds_a_volume: bool,
    pub verdict: String,
    pub closed: bool,
    /// The weld tolerance used (`null`: exact).
    pub weld_tolerance: Option<f64>,
    pub welded_vertices: usize,
    pub edges: usize,
    pub boundary_edges: usize,
    pub boundary_loops: usize,
    pub non_manifold_edges: usize,
    /// Faces left alone at non-manifold edges (odd counts), capped like holes.
    pub unpaired_at_non_manifold_edges: usize,
    pub non_manifold_vertices: usize,
    pub degenerate_faces: usize,
    /// Degenerate faces with distinct vertices (zero area): kept in the edge table.
    pub flat_faces: usize,
    pub duplicate_faces: usize,
    /// Duplicate faces left out because they cancel with a twin wound the other way.
    pub double_wall_faces: usize,
    pub consistently_oriented: bool,
    /// `outward`, `inward` or `mixed`.
    pub orientation: Option<&'static str>,
    /// `ccw` (counter-clockwise seen from outside) or `cw` (as OpenSCAD wants).
    pub winding: Option<&'static str>,
    pub shells: usize,
    pub cavities: usize,
    pub shell_details: Vec<ShellReport>,
    pub overlapping_shells: Vec<[usize; 2]>,
    /// Objects that share volume: the volume counts it twice (`meshvol union` once).
    pub overlapping_objects: Vec<ObjectOverlap>,
    pub self_intersections: Option<usize>,
    pub intersection_examples: Vec<[usize; 2]>,
    pub euler_characteristic: i64,
    /// The solid's volume from the topology (cavities subtracted, holes capped).
    pub solid_volume: f64,
    pub volume_uncertainty: f64,
}

impl CheckFacts {
    /// The facts of `c`, a check of the surface `source` describes (which names its
    /// objects).
    pub fn of(c: &Check, source: &Source) -> CheckFacts {
        CheckFacts {
            bounds_a_volume: c.bounds_a_volume(),
            verdict: c.verdict(),
            closed: c.closed,
            weld_tolerance: c.weld_tolerance,
            welded_vertices: c.vertices,
            edges: c.edges,
            boundary_edges: c.boundary_edges,
            boundary_loops: c.boundary_loops,
            non_manifold_edges: c.non_manifold_edges,
            unpaired_at_non_manifold_edges: c.unpaired_at_non_manifold_edges,
            non_manifold_vertices: c.non_manifold_vertices,
            degenerate_faces: c.degenerate_faces,
            flat_faces: c.flat_faces,
            duplicate_faces: c.duplicate_faces,
            double_wall_faces: c.double_wall_faces,
            consistently_oriented: c.consistently_oriented,
            orientation: c.orientation.map(Orientation::name),
            winding: c.orientation.and_then(Orientation::winding),
            shells: c.shells.len(),
            cavities: c.cavities,
            shell_details: c.shells.iter().cloned().map(ShellReport).collect(),
            overlapping_shells: c.overlapping_shells.clone(),
            overlapping_objects: c
                .overlapping_bodies
                .iter()
                .map(|o| ObjectOverlap {
                    objects: o.bodies.map(|b| source.body_name(b)),
                    nested: o.nested,
                })
                .collect(),
            self_intersections: c.self_intersections,
            intersection_examples: c.intersection_examples.clone(),
            euler_characteristic: c.euler_characteristic,
            solid_volume: c.volume,
            volume_uncertainty: c.volume_uncertainty,
        }
    }

    /// The facts in reported units: volumes, and the weld tolerance a length.
    pub fn convert(&mut self, to: &Converter) {
        to.one(Volume, &mut self.solid_volume);
        to.one(Volume, &mut self.volume_uncertainty);
        to.all(Volume, self.shell_details.iter_mut().map(|s| &mut s.0.volume));
        to.some(Length, &mut self.weld_tolerance);
    }
}

/// `check`'s report on one input: the file, its format, the facts and the reader's
/// warnings. (Serialized directly, not through `serde_json::Value`: a map per shell cost
/// 0.13 s for the 85k shells of the benchmark's cubes.)
#[derive(Clone, Debug, Serialize)]
pub struct CheckReport {
    pub file: Option<String>,
    pub format: Option<&'static str>,
    #[serde(flatten)]
    pub facts: CheckFacts,
    /// The units the numbers are in (`--units`, or the unit the file declares); null:
    /// the file's own numbers, unit unknown.
    pub units: Option<UnitNames>,
    /// With `--density`: `density`, `density_unit`, `mass`, `mass_unit`.
    #[serde(flatten)]
    pub mass: Option<Mass>,
    pub warnings: Vec<String>,
}

/// The report of `check` made on the surface `source` describes.
pub fn check(source: &Source, c: &Check) -> CheckReport {
    CheckReport {
        file: source.file.clone(),
        format: source.format,
        facts: CheckFacts::of(c, source),
        units: None,
        mass: None,
        warnings: source.warnings.clone(),
    }
}

/// How many shells or pairs the text report lists before summarising.
const LISTED: usize = 10;

impl Report for CheckReport {
    crate::file_and_warnings!("mesh");

    fn passed(&self) -> bool {
        self.facts.bounds_a_volume
    }

    /// The verdict first, details after.
    fn text(&self) -> String {
        let r = &self.facts;
        let mut s = String::new();
        let _ = writeln!(s, "{}: {}", self.file(), r.verdict);
        let _ = writeln!(s, "  format             {}", self.format.unwrap_or("arrays"));
        let _ = writeln!(
            s,
            "  closed             {} ({} in {})",
            r.closed,
            count(r.boundary_edges, "boundary edge", "boundary edges"),
            count(r.boundary_loops, "loop", "loops")
        );
        let weld =
            r.weld_tolerance.map_or("exact".to_string(), |t| format!("within {}", num(t, 4)));
        let _ = writeln!(
            s,
            "  vertices           {} welded ({weld}), {}",
            r.welded_vertices,
            count(r.edges, "edge", "edges")
        );
        let _ = writeln!(
            s,
            "  manifold           {}, {}",
            count(r.non_manifold_edges, "non-manifold edge", "non-manifold edges"),
            count(r.non_manifold_vertices, "non-manifold vertex", "non-manifold vertices")
        );
        let _ = writeln!(
            s,
            "  faces dropped      {} degenerate, {} duplicate",
            r.degenerate_faces, r.duplicate_faces
        );
        let _ = writeln!(
            s,
            "  orientation        {} (consistent: {}; winding {})",
            r.orientation.unwrap_or("none"),
            r.consistently_oriented,
            r.winding.unwrap_or("undetermined")
        );
        let _ = writeln!(
            s,
            "  shells             {} ({})",
            r.shells,
            count(r.cavities, "cavity", "cavities")
        );
        for (i, ShellReport(sh)) in r.shell_details.iter().enumerate().take(LISTED) {
            let role = if sh.cavity { "cavity" } else { "solid" };
            let parent = sh.parent.map(|p| format!(" inside shell {p}")).unwrap_or_default();
            let genus = sh.genus.map(|g| format!(", genus {g}")).unwrap_or_default();
            let _ = writeln!(
                s,
                "    shell {i}: {role}{parent}, {}, volume {}, {}{}, χ = {}{genus}",
                count(sh.faces, "face", "faces"),
                num(sh.volume, 10),
                if sh.closed { "closed" } else { "open" },
                if sh.orientable { "" } else { ", not orientable" },
                sh.euler_characteristic
            );
        }
        if r.shell_details.len() > LISTED {
            let _ = writeln!(s, "    ... and {} more (see --json)", r.shell_details.len() - LISTED);
        }
        if !r.overlapping_shells.is_empty() {
            let shown = &r.overlapping_shells[..r.overlapping_shells.len().min(LISTED)];
            let more = r.overlapping_shells.len() - shown.len();
            let more = if more > 0 { format!(" and {more} more") } else { String::new() };
            let _ = writeln!(s, "  overlapping shells {shown:?}{more}");
        }
        if !r.overlapping_objects.is_empty() {
            let shown = r.overlapping_objects.iter().take(LISTED).map(|o| {
                let how = if o.nested { "one inside the other" } else { "crossing" };
                format!("'{}' and '{}' ({how})", o.objects[0], o.objects[1])
            });
            let shown: Vec<String> = shown.collect();
            let more = r.overlapping_objects.len() - shown.len();
            let more = if more > 0 { format!(" and {more} more") } else { String::new() };
            let _ = writeln!(s, "  objects sharing volume {}{more}", shown.join(", "));
        }
        match r.self_intersections {
            Some(n) => {
                let _ = writeln!(s, "  self-intersections {n}");
            }
            None => {
                let _ = writeln!(s, "  self-intersections not checked");
            }
        }
        if !r.intersection_examples.is_empty() {
            let _ = writeln!(s, "  crossing faces     {:?}", r.intersection_examples);
        }
        let _ = writeln!(s, "  euler char.        {}", r.euler_characteristic);
        let _ = writeln!(
            s,
            "  volume             {} ± {} caps",
            num(r.solid_volume, 15),
            num(r.volume_uncertainty, 3)
        );
        s.push_str(&crate::units::units_text(&self.units, &self.mass));
        s
    }
}

impl Quantities for CheckReport {
    fn convert(&mut self, to: &Converter) {
        self.facts.convert(to);
    }

    fn mass_basis(&self) -> f64 {
        self.facts.solid_volume
    }

    crate::unit_slots!();
}
