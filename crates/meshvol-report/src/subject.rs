//! What is measured: a surface, what is known of where it came from, and the check that
//! makes the solid every command measures by default; and the rule that turns inputs into
//! the bodies of a union.

use meshvol::surface::{connected_parts, FaceSubset};
use meshvol::topology::{Check, CheckOptions, Measured, Weld};
use meshvol::Surface;
use meshvol_io::{LengthUnit, Loaded, Object};

/// The check `--weld-tolerance T` (`None`: not given) and `--no-intersections` (when
/// `intersections` is false) ask for: the command's and the page's (`meshvol serve`).
pub fn check_options(weld_tolerance: Option<f64>, intersections: bool) -> CheckOptions {
    CheckOptions {
        weld: match weld_tolerance {
            None => Weld::Auto,
            Some(0.0) => Weld::Exact,
            Some(t) => Weld::Tolerance(t),
        },
        intersections,
        ..CheckOptions::default()
    }
}

/// Where a surface came from: a file as the readers found it, or arrays (all `None`).
#[derive(Clone, Debug, Default)]
pub struct Source {
    /// The file as named (`-` for standard input); `None` for arrays.
    pub file: Option<String>,
    /// The format's name (`stl-binary`, `obj`, ...).
    pub format: Option<&'static str>,
    /// `extension` or `content`: what decided the format.
    pub format_source: Option<&'static str>,
    /// Vertices as read (three per triangle for STL).
    pub vertices: usize,
    /// The length unit the file declares (3MF, glTF).
    pub unit: Option<LengthUnit>,
    /// The file's objects when it has two or more.
    pub objects: Vec<Object>,
    /// The file's separate bodies (3MF, glTF objects) when it has two or more: the check
    /// nests shells within each only.
    pub bodies: Vec<Object>,
    /// What the reader read but did not use, or had to guess.
    pub warnings: Vec<String>,
}

impl Source {
    /// What `loaded`, read from the file named `file`, says about itself.
    pub fn of(file: &str, loaded: &Loaded) -> Source {
        Source {
            file: Some(file.to_string()),
            format: Some(loaded.format.name()),
            format_source: Some(loaded.format_source.name()),
            vertices: loaded.vertex_count(),
            unit: loaded.unit,
            objects: loaded.objects.clone(),
            bodies: loaded.bodies.clone(),
            warnings: loaded.warnings.clone(),
        }
    }

    /// A surface built from arrays of `vertices` points.
    pub fn arrays(vertices: usize) -> Source {
        Source { vertices, ..Source::default() }
    }

    /// The faces of each of [`Source::bodies`], as the check takes them.
    pub fn body_faces(&self) -> Vec<std::ops::Range<usize>> {
        self.bodies.iter().map(|b| b.faces.clone()).collect()
    }

    /// The name of body `b` (of [`Source::bodies`], as the check numbers them): the
    /// file's name for it, else `object N`.
    pub fn body_name(&self, b: usize) -> String {
        match self.bodies.get(b) {
            Some(o) if !o.name.is_empty() => o.name.clone(),
            _ => format!("object {b}"),
        }
    }

    /// The name messages use: the file, or `mesh` for arrays.
    pub fn name(&self) -> &str {
        self.file.as_deref().unwrap_or("mesh")
    }
}

/// One input to measure: its surface as wound, its source, and its check (`None`: the
/// surface is measured as wound, `--no-check` / `check=False`).
pub struct Subject<'a, S> {
    pub source: &'a Source,
    pub surface: &'a S,
    pub check: Option<&'a Check>,
}

impl<S> Clone for Subject<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S> Copy for Subject<'_, S> {}

/// One body of a union: a whole input, or one outermost shell of a single input with
/// what is nested in it.
pub struct Body<'a, S: Surface> {
    /// `FILE`, `FILE, shell N` (shells numbered as `check` numbers them), or `FILE,
    /// OBJECT (shell N)` for an object of a file whose objects are bodies.
    pub name: String,
    pub surface: FaceSubset<Measured<'a, S>>,
}

impl<'a, S: Surface> Subject<'a, S> {
    /// What is measured: the checked solid, or the surface as wound.
    pub fn measured(&self) -> Measured<'a, S> {
        match self.check {
            Some(check) => Measured::Solid(check.solid(self.surface)),
            None => Measured::AsWound(self.surface),
        }
    }

    /// The reader's warnings, then the reasons to doubt the solid.
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings = self.source.warnings.clone();
        if let Some(check) = self.check {
            let object = |b: usize| format!("'{}'", self.source.body_name(b));
            warnings.extend(check.doubts_naming(&object));
        }
        warnings
    }

    /// How far the caps on holes could put the volume off (0 when closed or unchecked).
    pub fn volume_uncertainty(&self) -> f64 {
        self.check.map_or(0.0, |c| c.volume_uncertainty)
    }

    /// The input's bodies: the checked solid's outermost shells of each object, each
    /// with its cavities; unchecked, the surface's connected parts.
    pub fn bodies(&self) -> Vec<Body<'a, S>> {
        let surface = self.measured();
        let file = self.source.name();
        let named = |shell: usize, object: Option<usize>| match object
            .and_then(|o| self.source.bodies.get(o))
        {
            Some(o) => format!("{file}, {} (shell {shell})", o.name),
            None => format!("{file}, shell {shell}"),
        };
        let parts: Vec<(String, Vec<usize>)> = match self.check {
            Some(check) => {
                check.bodies().into_iter().map(|b| (named(b.shell, b.object), b.faces)).collect()
            }
            None => connected_parts(self.surface)
                .into_iter()
                .enumerate()
                .map(|(shell, faces)| (named(shell, None), faces))
                .collect(),
        };
        parts
            .into_iter()
            .map(|(name, faces)| Body { name, surface: FaceSubset::new(surface, faces) })
            .collect()
    }

    /// The whole input as one body.
    pub fn whole(&self) -> Body<'a, S> {
        Body { name: self.source.name().to_string(), surface: FaceSubset::all(self.measured()) }
    }
}

/// The bodies of a union: a single input's bodies, or each of several inputs whole.
pub fn union_bodies<'a, S: Surface>(subjects: &[Subject<'a, S>]) -> Vec<Body<'a, S>> {
    match subjects {
        [one] => one.bodies(),
        many => many.iter().map(Subject::whole).collect(),
    }
}

/// The warnings of inputs measured together, naming each file once: a single input's as
/// they are (the report names its file), several inputs' each after its file's name.
pub fn input_warnings<S: Surface>(subjects: &[Subject<'_, S>]) -> Vec<String> {
    match subjects {
        [one] => one.warnings(),
        many => many
            .iter()
            .flat_map(|s| s.warnings().into_iter().map(|w| format!("{}: {w}", s.source.name())))
            .collect(),
    }
}

/// The names of several inputs as one `file` value: joined by `, `.
pub fn joined_names<S>(subjects: &[Subject<'_, S>]) -> String {
    subjects.iter().map(|s| s.source.name()).collect::<Vec<_>>().join(", ")
}
