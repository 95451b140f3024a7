//! What a check means for a measurement, in words: the winding's names, the one-line
//! verdict, the doubts every measurement of the solid carries, and the warnings a volume
//! report adds.

use super::report::{BodyOverlap, Check, Orientation};

impl Check {
    /// A one-line verdict, most important fact first: "closed, 2 shells, 1 cavity:
    /// volume is exact", or what stops the surface from bounding a volume.
    pub fn verdict(&self) -> String {
        let c = self;
        let shells = plural(c.shells.len(), "shell", "shells");
        let cavities = match c.cavities {
            0 => String::new(),
            n => format!(", {}", plural(n, "cavity", "cavities")),
        };
        if c.shells.is_empty() {
            return c.no_faces_left();
        }
        if c.bounds_a_volume() {
            let wound = match c.orientation {
                Some(Orientation::Outward) => "",
                Some(Orientation::Inward) => " (wound inward)",
                _ => " (shells wound inconsistently; corrected)",
            };
            return format!("closed, {shells}{cavities}: volume is exact{wound}");
        }
        let mut problems = Vec::new();
        if c.boundary_loops > 0 {
            let caps = if c.volume_uncertainty > 0.0 {
                format!("capped: volume ± {:.3e}", c.volume_uncertainty)
            } else {
                "flat, capped exactly".to_string()
            };
            problems.push(format!("open ({}, {caps})", plural(c.boundary_loops, "hole", "holes")));
        }
        if !c.overlapping_shells.is_empty() {
            problems.push(format!(
                "{} overlap (their common volume is counted twice: use `meshvol union`)",
                plural(c.overlapping_shells.len(), "pair of shells", "pairs of shells")
            ));
        }
        if !c.overlapping_bodies.is_empty() {
            problems.push(format!(
                "{} overlap or lie one inside another (their common volume is counted twice: \
                 use `meshvol union`)",
                plural(c.overlapping_bodies.len(), "pair of objects", "pairs of objects")
            ));
        }
        if let Some(n) = c.self_intersections.filter(|&n| n > 0) {
            problems.push(plural(n, "self-intersection", "self-intersections"));
        }
        if c.non_manifold_edges > 0 {
            problems.push(plural(c.non_manifold_edges, "non-manifold edge", "non-manifold edges"));
        }
        if c.shells.iter().any(|s| !s.orientable) {
            problems.push("not orientable (no inside and outside)".into());
        }
        format!("does not bound a volume: {}; {shells}{cavities}", problems.join(", "))
    }

    /// Why no face is left to bound a volume.
    fn no_faces_left(&self) -> String {
        if self.double_wall_faces > 0 {
            "no usable faces: every face cancels with a twin wound the other way (a \
             double-sided surface), so nothing bounds a volume; measure it unchecked (as
             wound) instead"
                .into()
        } else {
            "no usable faces: nothing bounds a volume".into()
        }
    }

    /// Why the solid of [`Check::solid`] may not be the one the file means, one reason a
    /// line, empty when it is beyond doubt: holes capped, non-manifold edges, shells
    /// that cannot be oriented, overlapping shells, self-intersections, faces wound
    /// against their shell and duplicate faces left out. (Degenerate faces hold no
    /// volume and are not a doubt.) Every measurement of the solid carries these. Objects
    /// that overlap are named `object N`, numbered as the bodies given to the check.
    pub fn doubts(&self) -> Vec<String> {
        self.doubts_naming(&|b| format!("object {b}"))
    }

    /// [`Check::doubts`], naming each object (a body given to the check) by `object`.
    pub fn doubts_naming(&self, object: &dyn Fn(usize) -> String) -> Vec<String> {
        let mut doubts = Vec::new();
        if self.shells.is_empty() {
            doubts.push(self.no_faces_left());
            return doubts;
        }
        if self.boundary_loops > 0 {
            let holes = plural(self.boundary_loops, "hole", "holes");
            doubts.push(if self.volume_uncertainty > 0.0 {
                format!(
                    "open: {holes} capped, so the volume is uncertain by ± {:.3e}",
                    self.volume_uncertainty
                )
            } else {
                // A flat hole's cap is the one plane face that can close it.
                format!("open: {holes} capped; the holes are flat, so the caps are exact")
            });
        }
        if self.non_manifold_edges > 0 {
            let edges = plural(self.non_manifold_edges, "non-manifold edge", "non-manifold edges");
            doubts.push(match self.unpaired_at_non_manifold_edges {
                0 => format!(
                    "{edges} (more than two faces meet): the faces around each were paired \
                     by their order around it into closed sheets, a guess at the solid meant"
                ),
                n => format!(
                    "{edges} (more than two faces meet): the faces around each were paired \
                     by their order around it, {} left alone and capped; the solid is a guess",
                    plural(n, "face", "faces")
                ),
            });
        }
        let non_orientable = self.shells.iter().filter(|s| !s.orientable).count();
        if non_orientable > 0 {
            doubts.push(format!(
                "{} not orientable (no inside and outside)",
                plural(non_orientable, "shell is", "shells are")
            ));
        }
        if !self.overlapping_shells.is_empty() {
            doubts.push(format!(
                "{} overlap: their common volume is counted twice (the union counts it once)",
                plural(self.overlapping_shells.len(), "pair of shells", "pairs of shells")
            ));
        }
        if !self.overlapping_bodies.is_empty() {
            doubts.push(overlapping_objects(&self.overlapping_bodies, object));
        }
        if let Some(n) = self.self_intersections.filter(|&n| n > 0) {
            doubts.push(format!(
                "{}: the surface crosses itself, so some volume may count twice or with the wrong sign",
                plural(n, "self-intersecting face pair", "self-intersecting face pairs")
            ));
        }
        if !self.consistently_oriented {
            doubts.push(
                "faces are wound against their neighbours: they were turned to agree with their \
                 shells"
                    .to_string(),
            );
        } else if self.orientation == Some(Orientation::Mixed) {
            let against = self.shells.iter().filter(|s| s.wound_outward == Some(false)).count();
            doubts.push(format!(
                "{} wound against {} role (a cavity wound like a solid, or a solid like a \
                 cavity): turned to it",
                plural(against, "shell is", "shells are"),
                if against == 1 { "its" } else { "their" }
            ));
        }
        if self.duplicate_faces > 0 {
            doubts.push(format!(
                "{} left out (the same vertices as another face)",
                plural(self.duplicate_faces, "duplicate face", "duplicate faces")
            ));
        }
        doubts
    }
}

/// What a volume report must say about its numbers beyond the check's doubts: that the
/// measured solid encloses nothing, or that the file winds its faces inward (as wound,
/// or as the check found them). `as_wound` and `solid` are the mass properties of the
/// surface as wound and of the measured solid; `check` the check made, if any.
pub fn volume_warnings(
    check: Option<&Check>,
    as_wound: &crate::MassProperties,
    solid: &crate::MassProperties,
) -> Vec<String> {
    if solid.centroid.is_none() {
        return vec![
            "the volume is zero within rounding: the surface encloses no solid (flat, or \
                     open?); centroid and inertia are undefined"
                .to_string(),
        ];
    }
    let inward = check.is_none_or(|c| c.orientation == Some(Orientation::Inward));
    if as_wound.signed_volume < 0.0 && inward {
        return vec!["signed volume is negative: faces are wound inward (clockwise seen from \
                     outside, as OpenSCAD's polyhedron() expects); volume reports the solid's \
                     magnitude"
            .to_string()];
    }
    Vec::new()
}

/// The doubt of objects that share volume, naming the first few pairs.
fn overlapping_objects(pairs: &[BodyOverlap], object: &dyn Fn(usize) -> String) -> String {
    const NAMED: usize = 3;
    let mut named: Vec<String> = pairs
        .iter()
        .take(NAMED)
        .map(|p| {
            let (a, b) = (object(p.bodies[0]), object(p.bodies[1]));
            if p.nested {
                format!("{a} and {b}: one lies inside the other")
            } else {
                format!("{a} and {b} overlap")
            }
        })
        .collect();
    if pairs.len() > NAMED {
        named.push(format!("{} more", plural(pairs.len() - NAMED, "pair", "pairs")));
    }
    format!(
        "{} of separate objects share volume ({}): the volume is their sum, counting the \
         common volume twice; `meshvol union` gives the union",
        plural(pairs.len(), "pair", "pairs"),
        named.join("; ")
    )
}

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}
