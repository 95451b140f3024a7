//! The path test matrix: one solid through every sink the command writes (text, JSON,
//! CSV, the grid files `.npy`, `.npz`, `.vti`, `.csv` and `.zarr`, and the robot formats
//! URDF, SDF and MJCF), under every units (none, `mm:cm`, `in:mL`, `mm:m`) and density
//! (none, `kg/m3`, `g/cm3`, `lb/ft3`). Every number is checked against the box's closed
//! form converted by hand with the factors written out below, and every quantity that
//! two sinks share must agree. (Python's side of the matrix is
//! crates/meshvol-py/tests/test_sinks.py; `/api/check` against the command,
//! serve_api.rs.)

mod common;
use common::{box_obj, f, meshvol, p, read_npy, read_npz, read_vti, read_zarr, write};

use serde_json::Value;
use std::path::Path;

/// The box, in the file's units: [1, 11] × [2, 22] × [3, 33].
const LO: [f64; 3] = [1.0, 2.0, 3.0];
const HI: [f64; 3] = [11.0, 22.0, 33.0];
const VOLUME: f64 = 10.0 * 20.0 * 30.0;
const AREA: f64 = 2.0 * (10.0 * 20.0 + 10.0 * 30.0 + 20.0 * 30.0);
const CENTROID: [f64; 3] = [6.0, 12.0, 18.0];

/// `--units`, metres per file length, and reported lengths per file length.
const UNITS: [(Option<&str>, f64, f64); 4] = [
    (None, f64::NAN, 1.0),
    (Some("mm:cm"), 1e-3, 0.1),
    (Some("in:mL"), 0.0254, 2.54), // mL: lengths in cm
    (Some("mm:m"), 1e-3, 1e-3),
];

/// `--density`, its value in kg/m³, and mass units per kilogram.
const DENSITIES: [(Option<&str>, f64, f64); 4] = [
    (None, f64::NAN, f64::NAN),
    (Some("7850kg/m3"), 7850.0, 1.0),
    (Some("7.85g/cm3"), 7850.0, 1000.0),
    (Some("490lb/ft3"), 490.0 * 0.45359237 / (0.3048 * 0.3048 * 0.3048), 1.0 / 0.45359237),
];

#[track_caller]
fn near(got: f64, want: f64, what: &str) {
    assert!((got - want).abs() <= 1e-11 * want.abs().max(1e-300), "{what}: {got} ≠ {want}");
}

fn run(args: &[&str]) -> std::process::Output {
    meshvol(args)
}

fn json(args: &[&str]) -> Value {
    let out = run(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

/// One combination of the matrix: its flags and what the closed form gives in them.
struct Case {
    flags: Vec<String>,
    /// Reported lengths per file length.
    length: f64,
    /// Metres per file length (NaN when unknown).
    metres: f64,
    /// The mass in the density's unit, and in kilograms (None without a density).
    mass: Option<(f64, f64)>,
    /// Whether a density with a unit and no file unit makes the run an error.
    refused: bool,
}

fn cases() -> Vec<Case> {
    let mut cases = Vec::new();
    for (units, metres, length) in UNITS {
        for (density, kg_per_m3, unit_per_kg) in DENSITIES {
            let mut flags = Vec::new();
            units.inspect(|u| flags.extend(["--units".to_string(), u.to_string()]));
            density.inspect(|d| flags.extend(["--density".to_string(), d.to_string()]));
            let kilograms = kg_per_m3 * VOLUME * metres.powi(3);
            let mass = density.map(|_| (kilograms * unit_per_kg, kilograms));
            let refused = density.is_some() && units.is_none();
            cases.push(Case { flags, length, metres, mass, refused });
        }
    }
    cases
}

fn args<'a>(head: &[&'a str], case: &'a Case) -> Vec<&'a str> {
    head.iter().copied().chain(case.flags.iter().map(String::as_str)).collect()
}

#[test]
fn json_text_and_csv_give_the_closed_form_in_every_unit() {
    let dir = tempfile::tempdir().unwrap();
    let solid = write(dir.path(), "box.obj", box_obj(LO, HI, 1, true, false));
    for case in cases() {
        let what = format!("{:?}", case.flags);
        let head = ["volume", p(&solid), "--json"];
        if case.refused {
            let out = run(&args(&head, &case));
            assert_eq!(out.status.code(), Some(1), "{what}");
            assert!(String::from_utf8_lossy(&out.stderr).contains("--units"), "{what}");
            continue;
        }
        let v = json(&args(&head, &case));
        let l = case.length;
        near(f(&v["volume"]), VOLUME * l.powi(3), &what);
        near(f(&v["area"]), AREA * l * l, &what);
        for a in 0..3 {
            near(f(&v["centroid"][a]), CENTROID[a] * l, &what);
            near(f(&v["bounds"]["min"][a]), LO[a] * l, &what);
        }
        if let Some((mass, _)) = case.mass {
            near(f(&v["mass"]), mass, &what);
        }
        // CSV: the JSON's numbers, the same bits.
        let head = ["volume", p(&solid), "--format", "csv"];
        let out = run(&args(&head, &case));
        let text = String::from_utf8(out.stdout).unwrap();
        let mut lines = text.lines();
        let columns: Vec<&str> = lines.next().unwrap().split(',').collect();
        let row = lines.next().unwrap();
        // The plain columns come before the first quoted (list) one.
        let plain: Vec<&str> = row.split(",\"").next().unwrap().split(',').collect();
        for key in ["volume", "area", "signed_volume"] {
            let at = columns.iter().position(|c| *c == key).unwrap();
            let csv: f64 = plain[at].parse().unwrap();
            assert_eq!(csv, f(&v[key]), "{key} in CSV and JSON, {what}");
        }
        // Text: the volume as JSON has it (15 significant digits) and the unit's name.
        let head = ["volume", p(&solid)];
        let text = String::from_utf8(run(&args(&head, &case)).stdout).unwrap();
        let line = text.lines().find(|l| l.trim_start().starts_with("volume")).unwrap();
        let shown: f64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
        assert!((shown - f(&v["volume"])).abs() <= 1e-14 * shown.abs(), "{what}: {line}");
        if let Some(u) = v["units"]["volume"].as_str() {
            assert!(line.contains(u), "{what}: {line}");
        }
    }
}

/// The numbers of attribute `key` in an XML element.
fn attribute(text: &str, key: &str) -> Vec<f64> {
    let at = text.find(&format!(" {key}=\"")).unwrap_or_else(|| panic!("{key} in {text}"));
    let rest = &text[at + key.len() + 3..];
    rest[..rest.find('"').unwrap()].split_whitespace().map(|x| x.parse().unwrap()).collect()
}

#[test]
fn robot_formats_are_si_whatever_the_units_and_density() {
    let dir = tempfile::tempdir().unwrap();
    let solid = write(dir.path(), "box.obj", box_obj(LO, HI, 1, true, false));
    for case in cases() {
        let what = format!("{:?}", case.flags);
        let reports_metres = case.flags.iter().any(|f| f == "mm:m");
        let out = run(&args(&["volume", p(&solid), "--format", "urdf"], &case));
        let text = String::from_utf8_lossy(&out.stdout);
        match case.mass {
            // A density with its unit: kg, m, kg·m², from any units.
            Some((_, kilograms)) if !case.refused => {
                assert!(out.status.success(), "{what}: {}", String::from_utf8_lossy(&out.stderr));
                near(attribute(&text, "value")[0], kilograms, &what);
                let xyz = attribute(&text, "xyz");
                for a in 0..3 {
                    near(xyz[a], CENTROID[a] * case.metres, &what);
                }
                // A cuboid about its centre: ixx = m (b² + c²) / 12, sides in metres.
                let [a, b, c] = [10.0, 20.0, 30.0].map(|s| s * case.metres);
                near(attribute(&text, "ixx")[0], kilograms * (b * b + c * c) / 12.0, &what);
                near(attribute(&text, "izz")[0], kilograms * (a * a + b * b) / 12.0, &what);
            }
            Some(_) => assert_eq!(out.status.code(), Some(1), "{what}"),
            // No density: a number per reported volume, kilograms only in metres.
            None if reports_metres => assert!(out.status.success(), "{what}"),
            None if case.flags.is_empty() => {
                assert_eq!(out.status.code(), Some(1), "{what}");
                assert!(String::from_utf8_lossy(&out.stderr).contains("--units"), "{what}");
            }
            None => {
                // Refused before reading: exit 2, naming the unit needed.
                assert_eq!(out.status.code(), Some(2), "{what}");
                assert!(String::from_utf8_lossy(&out.stderr).contains("kg/m3"), "{what}");
                assert!(text.is_empty(), "{what}: nothing written");
            }
        }
    }
}

/// The sum of a grid file's cell values, its origin and its cell size, as written.
fn grid_file(path: &Path, name: &str) -> (f64, [f64; 3], [f64; 3]) {
    let ext = path.extension().unwrap().to_str().unwrap();
    let three = |v: &[f64]| [v[0], v[1], v[2]];
    match ext {
        "npz" => {
            let a = read_npz(path);
            (a[name].1.iter().sum(), three(&a["origin"].1), three(&a["cell_size"].1))
        }
        "vti" => {
            let v = read_vti(path);
            (v.array(name).iter().sum(), three(&v.origin), three(&v.spacing))
        }
        "zarr" => {
            let group: serde_json::Value =
                serde_json::from_slice(&std::fs::read(path.join("zarr.json")).unwrap()).unwrap();
            let attrs = &group["attributes"];
            // The one array, named after what it holds (`volume`, or `mass` alone).
            let (_, values) = read_zarr(&path.join(attrs["values"].as_str().unwrap()));
            let at = |k: &str| [0, 1, 2].map(|a| f(&attrs[k][a]));
            (values.iter().sum(), at("origin"), at("cell_size"))
        }
        "csv" => {
            let text = std::fs::read_to_string(path).unwrap();
            let mut lines = text.lines();
            let header: Vec<&str> = lines.next().unwrap().split(',').collect();
            let column = header.iter().position(|h| *h == name).unwrap();
            let sum = lines.map(|l| l.split(',').nth(column).unwrap().parse::<f64>().unwrap());
            (sum.sum(), [f64::NAN; 3], [f64::NAN; 3])
        }
        _ => (read_npy(path).1.iter().sum(), [f64::NAN; 3], [f64::NAN; 3]),
    }
}

#[test]
fn grid_files_hold_the_summary_in_its_units() {
    let dir = tempfile::tempdir().unwrap();
    let solid = write(dir.path(), "box.obj", box_obj(LO, HI, 1, true, false));
    for case in cases().iter().filter(|c| !c.refused) {
        let what = format!("{:?}", case.flags);
        let l = case.length;
        for ext in ["npy", "npz", "vti", "csv", "zarr"] {
            let out = dir.path().join(format!("cells.{ext}"));
            let head = ["grid", p(&solid), "--pitch", "2.5", "--json", "--out", p(&out)];
            let v = json(&args(&head, case));
            let what = format!("{what} .{ext}");
            // 4 × 8 × 12 full cells of 2.5³.
            near(f(&v["total"]), VOLUME * l.powi(3), &what);
            near(f(&v["cell_size"][0]), 2.5 * l, &what);
            let (sum, origin, cell) = grid_file(&out, "volume");
            let one_array = matches!(ext, "npy" | "zarr");
            match case.mass {
                Some((mass, _)) => {
                    near(f(&v["mass"]), mass, &what);
                    // Masses alone in a one-array file, beside the volumes in the others.
                    if one_array {
                        near(sum, mass, &what);
                    } else {
                        near(sum, f(&v["total"]), &what);
                        near(grid_file(&out, "mass").0, mass, &what);
                    }
                }
                None => near(sum, f(&v["total"]), &what),
            }
            if origin[0].is_finite() {
                for a in 0..3 {
                    near(origin[a], LO[a] * l, &what);
                    near(cell[a], 2.5 * l, &what);
                }
            }
        }
        // The cut cells: every array by its dimension.
        let out = dir.path().join("cut.npz");
        let head = ["grid", p(&solid), "--pitch", "2.5", "--moments", "--out", p(&out)];
        assert!(run(&args(&head, case)).status.success());
        let a = read_npz(&out);
        near(a["volume"].1.iter().sum(), VOLUME * l.powi(3), &what);
        near(a["boundary_area"].1.iter().sum(), AREA * l * l, &what);
        near(a["fraction"].1.iter().sum(), 4.0 * 8.0 * 12.0, &what);
        let first_centroid: Vec<f64> = a["centroid"].1[..3].to_vec();
        for k in 0..3 {
            near(first_centroid[k], (LO[k] + 1.25) * l, &what);
        }
    }
}

#[test]
fn cut_and_fill_cells_are_in_the_units_of_the_report() {
    let dir = tempfile::tempdir().unwrap();
    // A flat ground at z = 3 (the box's floor) against the level z = 5: fill 2 over 10×20.
    let ground = "v 1 2 3\nv 11 2 3\nv 11 22 3\nv 1 22 3\nf 1 2 3 4\n";
    let ground = write(dir.path(), "ground.obj", ground);
    let out = dir.path().join("cells.npy");
    let base = ["cutfill", p(&ground), "--level", "5", "--cells", "2,2", "--json", "--out"];
    let raw = json(&[&base[..], &[p(&out)]].concat());
    let raw_cells: f64 = read_npy(&out).1.iter().sum();
    let cm = json(&[&base[..], &[p(&out), "--units", "mm:cm"]].concat());
    let cm_cells: f64 = read_npy(&out).1.iter().sum();
    near(raw_cells, 400.0, "cut + fill of the cells, mm³");
    near(cm_cells, 0.4, "cut + fill of the cells, cm³");
    let total = |v: &Value| f(&v["cut"]) + f(&v["fill"]);
    near(total(&raw), raw_cells, "report and cells, mm³");
    near(total(&cm), cm_cells, "report and cells, cm³");
}

/// The shoelace area of the rings of a GeoJSON (Multi)Polygon's coordinates: exterior
/// minus holes, whatever their winding.
fn geojson_area(geometry: &Value) -> f64 {
    let ring = |r: &Value| {
        let pts: Vec<[f64; 2]> =
            r.as_array().unwrap().iter().map(|p| [f(&p[0]), f(&p[1])]).collect();
        let twice: f64 = pts.windows(2).map(|w| w[0][0] * w[1][1] - w[1][0] * w[0][1]).sum();
        twice.abs() / 2.0
    };
    let polygon = |rings: &Value| {
        let rings = rings.as_array().unwrap();
        ring(&rings[0]) - rings[1..].iter().map(ring).sum::<f64>()
    };
    match geometry["type"].as_str().unwrap() {
        "Polygon" => polygon(&geometry["coordinates"]),
        _ => geometry["coordinates"].as_array().unwrap().iter().map(polygon).sum(),
    }
}

#[test]
fn a_sections_outline_is_in_the_units_of_its_area() {
    let dir = tempfile::tempdir().unwrap();
    let solid = write(dir.path(), "box.obj", box_obj(LO, HI, 1, true, false));
    for (units, _, l) in UNITS {
        let out = dir.path().join("section.geojson");
        let mut a = vec!["section", p(&solid), "--plane", "z=18", "--json", "--out", p(&out)];
        a.extend(units.iter().flat_map(|u| ["--units", u]));
        let v = json(&a);
        let what = format!("{units:?}");
        // A 10 × 20 rectangle.
        near(f(&v["area"]), 200.0 * l * l, &what);
        let feature: Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
        near(f(&feature["properties"]["area"]), f(&v["area"]), &what);
        near(geojson_area(&feature["geometry"]), f(&v["area"]), &what);
    }
}

#[test]
fn check_and_volume_report_one_set_of_facts_in_every_unit() {
    let dir = tempfile::tempdir().unwrap();
    let solid = write(dir.path(), "box.obj", box_obj(LO, HI, 1, true, false));
    for (units, _, l) in UNITS {
        let flags: Vec<&str> = units.iter().flat_map(|u| ["--units", u]).collect();
        let tolerance = ["--weld-tolerance", "0.5"];
        let check = json(&[&["check", p(&solid), "--json"], &tolerance[..], &flags].concat());
        let volume = json(&[&["volume", p(&solid), "--json"], &tolerance[..], &flags].concat());
        let what = format!("{units:?}");
        // The weld tolerance is a length, the solid's volume a volume, in both.
        near(f(&check["weld_tolerance"]), 0.5 * l, &what);
        near(f(&volume["weld_tolerance"]), 0.5 * l, &what);
        near(f(&check["solid_volume"]), VOLUME * l.powi(3), &what);
        assert_eq!(f(&check["solid_volume"]), f(&volume["solid_volume"]), "{what}");
        assert_eq!(check["units"], volume["units"], "{what}");
    }
}

#[test]
fn a_certified_interval_converted_still_holds_the_volume() {
    // Two 2-unit cubes overlapping in a unit cube (samples/a.obj, b.obj): union 15,
    // intersection 1, in the file's units.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../samples");
    let (a, b) = (dir.join("a.obj"), dir.join("b.obj"));
    for (units, _, l) in UNITS {
        let flags: Vec<&str> = units.iter().flat_map(|u| ["--units", u]).collect();
        let what = format!("{units:?}");
        let union = json(&[&["union", p(&a), p(&b), "--json"], &flags[..]].concat());
        let both = json(&[&["intersect", p(&a), p(&b), "--json"], &flags[..]].concat());
        for (v, lower, upper, exact) in [
            (&union, "lower", "upper", 15.0),
            (&both, "lower", "upper", 1.0),
            (&both, "union_lower", "union_upper", 15.0),
        ] {
            let want = exact * l.powi(3);
            assert!(f(&v[lower]) <= want && want <= f(&v[upper]), "{what} {lower}: {v}");
        }
        assert_eq!(union["certified"], true, "{what}");
        near(f(&both["contact_area"]), 6.0 * l * l, &what);
    }
}

/// The JSON lines of `args`, one a file (failed files have `error`).
fn lines(args: &[&str]) -> Vec<Value> {
    let out = run(args);
    let text = String::from_utf8(out.stdout).unwrap();
    text.lines().map(|l| serde_json::from_str(l).unwrap()).collect()
}

#[test]
fn the_corpus_gives_one_number_in_every_unit_and_sink() {
    let corpus =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus/trimesh-models");
    if !corpus.exists() {
        eprintln!("corpus not found at {}, skipping", corpus.display());
        return;
    }
    // The files a run reads in seconds (the large scans are the invariance suite's).
    let mut files: Vec<String> = std::fs::read_dir(&corpus)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file() && p.metadata().unwrap().len() < 1 << 20)
        .map(|p| p.to_str().unwrap().to_string())
        .collect();
    files.sort();
    let names: Vec<&str> = files.iter().map(String::as_str).collect();
    let plain = lines(&[&["volume", "--json", "-q", "--units", "mm"], &names[..]].concat());
    let cm = ["--units", "mm:cm", "--density", "490lb/ft3"];
    let converted = lines(&[&["volume", "--json", "-q"], &cm[..], &names[..]].concat());
    let checked = lines(&[&["check", "--json", "-q"], &cm[..], &names[..]].concat());
    assert_eq!(
        (plain.len(), converted.len(), checked.len()),
        (files.len(), files.len(), files.len())
    );
    // 490 lb/ft³ in lb/cm³, written out: 490 / 30.48³.
    let rho = 490.0 / (30.48 * 30.48 * 30.48);
    let mut measured = 0;
    for ((p, c), k) in plain.iter().zip(&converted).zip(&checked) {
        let what = p["file"].as_str().unwrap();
        assert_eq!(p.get("error").is_some(), c.get("error").is_some(), "{what}");
        if p.get("error").is_some() {
            continue;
        }
        measured += 1;
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-300);
        assert!(close(f(&c["volume"]), f(&p["volume"]) * 1e-3), "{what}");
        assert!(close(f(&c["area"]), f(&p["area"]) * 1e-2), "{what}");
        assert!(close(f(&c["mass"]), f(&c["volume"]) * rho), "{what}");
        assert_eq!(c["mass_unit"], "lb", "{what}");
        // check and volume: one solid, one set of facts.
        assert_eq!(k["solid_volume"], c["solid_volume"], "{what}");
        assert_eq!(k["units"], c["units"], "{what}");
        assert!(close(f(&k["mass"]), f(&k["solid_volume"]) * rho), "{what}");
    }
    assert!(measured > 50, "{measured} corpus files measured");
}
