//! Many files at once: `--format csv` (one row per file, the JSON keys as columns),
//! folders as inputs (`--recursive`, `--glob`), compressed inputs (.gz, .bz2, .zst, .zip;
//! bounded), `--slice` as a coordinate or an index, shell completions, the manual page,
//! and the examples in `--help`.

mod common;
use common::{box_obj, meshvol, p, write};
use serde_json::Value;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Output};

const TETRA: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/// Two tetrahedra as two OBJ objects (the report then has `objects`).
fn two_objects() -> String {
    let second = "v 3 0 0\nv 4 0 0\nv 3 1 0\nv 3 0 1\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n";
    format!("o a\n{TETRA}o b\n{second}")
}

fn text(out: &Output) -> (String, String) {
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `pandas.json_normalize(v, sep=".")`'s columns, written here from its definition.
fn normalize(prefix: &str, v: &Value, out: &mut Vec<(String, Value)>) {
    for (k, x) in v.as_object().unwrap() {
        let name = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
        match x {
            Value::Object(_) => normalize(&name, x, out),
            _ => out.push((name, x.clone())),
        }
    }
}

/// The JSON lines of a run.
fn json_lines(out: &Output) -> Vec<Value> {
    let (stdout, stderr) = text(out);
    stdout
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}\n{stderr}")))
        .collect()
}

/// Checks that a CSV run is the JSON run, flattened: the header is the union of the
/// lines' columns in the order first seen, each row its line's values (a string as
/// itself, null empty, anything else its JSON text), and cells of absent keys empty.
fn assert_csv_is_json(csv_run: &Output, json_run: &Output) {
    let lines = json_lines(json_run);
    let mut header: Vec<String> = Vec::new();
    let rows: Vec<Vec<(String, Value)>> = lines
        .iter()
        .map(|line| {
            let mut row = Vec::new();
            normalize("", line, &mut row);
            for (k, _) in &row {
                if !header.contains(k) {
                    header.push(k.clone());
                }
            }
            row
        })
        .collect();
    let (stdout, stderr) = text(csv_run);
    let mut reader = csv::Reader::from_reader(stdout.as_bytes());
    let got: Vec<String> = reader.headers().unwrap().iter().map(str::to_string).collect();
    assert_eq!(got, header, "{stderr}");
    let records: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!(records.len(), rows.len(), "{stdout}");
    for (record, row) in records.iter().zip(&rows) {
        for (i, column) in header.iter().enumerate() {
            let cell = &record[i];
            match row.iter().find(|(k, _)| k == column).map(|(_, v)| v) {
                None | Some(Value::Null) => assert_eq!(cell, "", "{column}"),
                Some(Value::String(s)) => assert_eq!(cell, s, "{column}"),
                Some(v) => {
                    let parsed: Value = serde_json::from_str(cell)
                        .unwrap_or_else(|e| panic!("{column}: {cell:?}: {e}"));
                    assert_eq!(&parsed, v, "{column}");
                }
            }
        }
    }
    assert_eq!(csv_run.status.code(), json_run.status.code());
}

#[test]
fn csv_rows_are_the_json_lines_flattened() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "a.obj", TETRA);
    write(d, "b.obj", two_objects());
    write(d, "c.obj", box_obj([0.0; 3], [2.0, 3.0, 4.0], 1, true, false));
    write(d, "d.obj", "v 0 0 0\nf 1 2 3\n"); // a bad index: an error row
    write(d, "e, \"quoted\".obj", box_obj([0.0; 3], [1.0; 3], 1, true, true)); // open
    for (command, extra) in [
        ("volume", vec!["--units", "mm:cm"]),
        ("volume", vec![]),
        ("check", vec![]),
        ("below", vec!["--plane", "0,0,1,0.5"]),
    ] {
        let mut args = vec![command, p(d)];
        args.extend(extra.iter().copied());
        let csv_run = meshvol(&[&args[..], &["--format", "csv", "-q"]].concat());
        let json_run = meshvol(&[&args[..], &["--json", "-q"]].concat());
        assert_csv_is_json(&csv_run, &json_run);
        // The bad file fails the run, as with --json.
        assert_eq!(csv_run.status.code(), Some(1), "{command}");
        let (stdout, stderr) = text(&csv_run);
        assert!(stdout.lines().next().unwrap().ends_with(",error"), "{command}: {stdout}");
        assert!(stderr.contains("d.obj"), "{stderr}");
        let header = stdout.lines().next().unwrap();
        if command == "volume" {
            // Nested objects spread into columns; lists stay one cell.
            assert!(
                header.contains("bounds.min,bounds.max") && header.contains(",objects,"),
                "{header}"
            );
        }
        if extra.contains(&"mm:cm") {
            assert!(header.contains(",units.") && !header.contains(",units,"), "{header}");
        }
    }
    // --format json is --json; --format csv and --json do not go together.
    let a = d.join("a.obj");
    assert_eq!(
        meshvol(&["check", p(&a), "--format", "json"]).stdout,
        meshvol(&["check", p(&a), "--json"]).stdout
    );
    assert_eq!(meshvol(&["check", p(&a), "--format", "csv", "--json"]).status.code(), Some(2));
}

/// The `file` of each JSON line.
fn files(out: &Output) -> Vec<String> {
    json_lines(out).iter().map(|l| l["file"].as_str().unwrap().to_string()).collect()
}

#[test]
fn folders_give_their_mesh_files_sorted() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir_all(d.join("sub/deeper")).unwrap();
    std::fs::create_dir_all(d.join(".hidden")).unwrap();
    write(d, "b.obj", TETRA);
    write(d, "a.OBJ", box_obj([0.0; 3], [1.0, 2.0, 3.0], 1, true, false));
    write(d, "notes.txt", "not a mesh");
    write(d, ".hidden/h.obj", TETRA);
    write(d, ".dot.obj", TETRA);
    write(d, "sub/c.obj", TETRA);
    write(d, "sub/deeper/d.obj", TETRA);
    write(d, "e.obj.gz", gz(TETRA.as_bytes()));
    let name = |rel: &str| d.join(rel).display().to_string();
    let run = |extra: &[&str]| meshvol(&[&["volume", "--json", p(d)][..], extra].concat());

    let top = run(&[]);
    assert!(top.status.success(), "{}", text(&top).1);
    assert_eq!(files(&top), [name("a.OBJ"), name("b.obj"), name("e.obj.gz")]);
    let all = run(&["--recursive"]);
    assert_eq!(
        files(&all),
        [
            name("a.OBJ"),
            name("b.obj"),
            name("e.obj.gz"),
            name("sub/c.obj"),
            name("sub/deeper/d.obj")
        ]
    );
    // Each file measures as it does named alone.
    for line in json_lines(&all) {
        let alone = json_lines(&meshvol(&["volume", "--json", line["file"].as_str().unwrap()]));
        assert_eq!(line, alone[0]);
    }
    // Globs match in any case, as the extensions do: `*.obj` keeps `a.OBJ`.
    let globbed = run(&["-r", "--glob", "*.obj", "--glob", "!c*"]);
    assert_eq!(files(&globbed), [name("a.OBJ"), name("b.obj"), name("sub/deeper/d.obj")]);
    let by_path = run(&["-r", "-g", "sub/**/*.obj"]);
    assert_eq!(files(&by_path), [name("sub/c.obj"), name("sub/deeper/d.obj")]);
    // Files named as arguments are read whatever the globs.
    let named = meshvol(&["volume", "--json", p(&d.join("b.obj")), p(d), "-g", "*.gz"]);
    assert_eq!(files(&named), [name("b.obj"), name("e.obj.gz")]);

    // `hull` takes point files and meshes from a folder; `area` polygon files.
    let clouds = d.join("clouds");
    std::fs::create_dir(&clouds).unwrap();
    write(&clouds, "p.xyz", "0 0 0\n2 0 0\n0 2 0\n0 0 2\n");
    write(&clouds, "t.obj", TETRA);
    write(&clouds, "ring.wkt", "POLYGON((0 0,1 0,1 1,0 0))");
    let hulls = json_lines(&meshvol(&["hull", "--json", p(&clouds)]));
    let volumes: Vec<f64> = hulls.iter().map(|h| h["volume"].as_f64().unwrap()).collect();
    assert_eq!(volumes.len(), 2);
    assert!((volumes[0] - 8.0 / 6.0).abs() < 1e-14 && (volumes[1] - 1.0 / 6.0).abs() < 1e-15);
    let areas = json_lines(&meshvol(&["area", "--json", p(&clouds)]));
    assert_eq!((areas.len(), areas[0]["area"].as_f64()), (1, Some(0.5)));

    // A command over all its inputs together: the folder is its files.
    let grid = |inputs: &[&str]| {
        let out = meshvol(&[&["grid", "--cells", "2,2,2", "--json"][..], inputs].concat());
        json_lines(&out).remove(0)
    };
    let (a, b) = (name("a.OBJ"), name("b.obj"));
    let g1 = grid(&[p(d), "-g", "[ab].*"]);
    let g2 = grid(&[&a, &b]);
    assert_eq!(g1["files"], g2["files"]);
    assert_eq!(g1["total"], g2["total"]);

    // A folder without mesh files fails, naming it; the others are still measured.
    let empty = d.join("sub/empty");
    std::fs::create_dir(&empty).unwrap();
    let out = meshvol(&["volume", p(&empty), p(&d.join("b.obj"))]);
    let (stdout, stderr) = text(&out);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr.contains(&format!("{}: no mesh files in this folder", empty.display())),
        "{stderr}"
    );
    assert!(stdout.contains("b.obj"), "{stdout}");
    let out = meshvol(&["volume", p(d), "-g", "*.stl"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out).1.contains("matching --glob *.stl"), "{}", text(&out).1);
    let out = meshvol(&["grid", p(&empty), "--cells", "2,2,2"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out).1.contains("no mesh files"));
    // A bad pattern is a usage error.
    assert_eq!(meshvol(&["volume", p(d), "-g", "a[b"]).status.code(), Some(2));
}

fn gz(data: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    e.write_all(data).unwrap();
    e.finish().unwrap()
}

fn bz2(data: &[u8]) -> Vec<u8> {
    let mut e = bzip2::write::BzEncoder::new(Vec::new(), bzip2::Compression::default());
    e.write_all(data).unwrap();
    e.finish().unwrap()
}

fn zst(data: &[u8]) -> Vec<u8> {
    ruzstd::encoding::compress_to_vec(data, ruzstd::encoding::CompressionLevel::Fastest)
}

fn zip(members: &[(&str, &[u8])]) -> Vec<u8> {
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    for (name, data) in members {
        zip.start_file(*name, zip::write::SimpleFileOptions::default()).unwrap();
        zip.write_all(data).unwrap();
    }
    zip.finish().unwrap().into_inner()
}

/// The JSON report of `volume` with `file` left out.
fn measured(path: &Path, env: &[(&str, &str)]) -> (Option<i32>, Value, String) {
    let out = Command::new(common::bin())
        .args(["volume", "--json", p(path)])
        .envs(env.iter().copied())
        .output()
        .unwrap();
    let mut v = json_lines(&out).remove(0);
    v.as_object_mut().unwrap().remove("file");
    (out.status.code(), v, text(&out).1)
}

#[test]
fn compressed_files_measure_as_the_file_they_hold() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let sample = std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../samples/flanged-bushing.stl"),
    )
    .unwrap();
    let plain = write(d, "part.stl", &sample);
    let (_, expected, _) = measured(&plain, &[]);
    assert_eq!(expected["format"], "stl-binary");
    for (name, bytes) in [
        ("part.stl.gz", gz(&sample)),
        ("part.STL.BZ2", bz2(&sample)),
        ("part.stl.zst", zst(&sample)),
        (
            "part.zip",
            zip(&[
                ("readme.txt", b"hello"),
                ("__MACOSX/inner/._part.stl", b"fork"),
                ("inner/part.stl", &sample),
            ]),
        ),
    ] {
        let path = write(d, name, bytes);
        let (code, got, err) = measured(&path, &[]);
        assert_eq!(code, Some(0), "{name}: {err}");
        assert_eq!(got, expected, "{name}");
    }
    // A 3MF package named .zip is read as the 3MF it is.
    let model = r#"<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>
        <object id="1" type="model"><mesh><vertices>
        <vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/><vertex x="0" y="0" z="0.75"/>
        </vertices><triangles><triangle v1="0" v2="2" v3="1"/><triangle v1="0" v2="1" v3="3"/>
        <triangle v1="0" v2="3" v3="2"/><triangle v1="1" v2="2" v3="3"/></triangles></mesh></object>
        </resources><build><item objectid="1"/></build></model>"#;
    let (_, as_3mf, _) = measured(&write(d, "tet.3mf", common::three_mf(model)), &[]);
    let (code, as_zip, err) = measured(&write(d, "tet.zip", common::three_mf(model)), &[]);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!((as_zip, as_3mf["volume"].as_f64()), (as_3mf.clone(), Some(0.125)));
    // A gzip of two members (as `cat a.gz b.gz` makes) is both.
    let half = TETRA.len() / 2;
    let two = [gz(&TETRA.as_bytes()[..half]), gz(&TETRA.as_bytes()[half..])].concat();
    let (_, got, _) = measured(&write(d, "t.obj.gz", two), &[]);
    let (_, want, _) = measured(&write(d, "t.obj", TETRA), &[]);
    assert_eq!(got, want);
    // Points and polygons too.
    let xyz = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
    let out = meshvol(&["hull", "--json", p(&write(d, "c.xyz.bz2", bz2(xyz.as_bytes())))]);
    assert!((json_lines(&out)[0]["volume"].as_f64().unwrap() - 1.0 / 6.0).abs() < 1e-15);
    let out = meshvol(&[
        "area",
        "--json",
        p(&write(d, "sq.wkt.zst", zst(b"POLYGON((0 0,2 0,2 3,0 3,0 0))"))),
    ]);
    assert_eq!(json_lines(&out)[0]["area"], 6.0);
}

#[test]
fn bad_or_oversized_archives_are_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let fail = |path: &Path, env: &[(&str, &str)], says: &str| {
        let out = Command::new(common::bin())
            .args(["volume", p(path)])
            .envs(env.iter().copied())
            .output()
            .unwrap();
        let err = text(&out).1;
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(err.starts_with("meshvol: error: ") && !err.contains("panicked"), "{err}");
        assert!(err.contains(&path.display().to_string()) && err.contains(says), "{says}: {err}");
    };
    fail(&write(d, "x.stl.gz", b"not gzip at all"), &[], "gzip");
    fail(&write(d, "x.stl.bz2", b"BZh9 broken"), &[], "bzip2");
    fail(&write(d, "x.stl.zst", b"\x28\xb5\x2f\xfd broken"), &[], "Zstandard");
    fail(&write(d, "x.zip", b"PK\x03\x04 broken"), &[], "zip");
    let truncated = gz(TETRA.as_bytes());
    fail(&write(d, "cut.obj.gz", &truncated[..truncated.len() / 2]), &[], "gzip");
    // A zip must hold exactly one mesh: the error lists what it holds.
    fail(
        &write(d, "two.zip", zip(&[("a.stl", b"x"), ("b.obj", TETRA.as_bytes())])),
        &[],
        "2 files meshvol reads (a.stl, b.obj)",
    );
    fail(
        &write(d, "none.zip", zip(&[("notes.txt", b"x")])),
        &[],
        "no file meshvol reads here (its files: notes.txt)",
    );
    // A damaged member is named inside its archive.
    let bad = write(d, "bad.zip", zip(&[("in/bad.obj", b"v 0 0 0\nf 1 2 3\n")]));
    fail(&bad, &[], "bad.zip/in/bad.obj");

    // Bombs: a few kilobytes that inflate past the limit are refused, for each form.
    let limit = [("MESHVOL_MAX_STREAM_BYTES", "1000000")];
    let mut huge = b"solid bomb\n".to_vec();
    huge.resize(4_000_000, b' ');
    for (name, bytes) in [
        ("bomb.stl.gz", gz(&huge)),
        ("bomb.stl.bz2", bz2(&huge)),
        ("bomb.stl.zst", zst(&huge)),
        ("bomb.zip", zip(&[("bomb.stl", &huge)])),
    ] {
        assert!(bytes.len() < 200_000, "{name}: {}", bytes.len());
        fail(&write(d, name, bytes), &limit, "decompresses to more than 1000000 bytes");
    }
    // Under the limit, the same limit reads a small file.
    let (code, v, err) = measured(&write(d, "small.obj.gz", gz(TETRA.as_bytes())), &limit);
    assert_eq!(code, Some(0), "{err}");
    assert!((v["volume"].as_f64().unwrap() - 1.0 / 6.0).abs() < 1e-15);
}

#[test]
fn slice_takes_a_coordinate_or_a_cell_index() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // z from 0 to 1 in 4 layers: [0, 0.25), [0.25, 0.5), [0.5, 0.75), [0.75, 1].
    let mesh = write(d, "box.obj", box_obj([0.0; 3], [1.0, 1.0, 1.0], 1, true, false));
    let png = |slice: &str| {
        let out_path = d.join(format!("{slice}.png"));
        let out = meshvol(&[
            "grid",
            p(&mesh),
            "--cells",
            "2,3,4",
            "--png",
            p(&out_path),
            "--slice",
            slice,
        ]);
        assert!(out.status.success(), "{slice}: {}", text(&out).1);
        std::fs::read(out_path).unwrap()
    };
    // The picture's title names the layer (its centre and index), so pictures of the same
    // layer are the same bytes and pictures of other layers differ.
    let layers: Vec<Vec<u8>> = (0..4).map(|k| png(&format!("k={k}"))).collect();
    for (coordinate, k) in [
        ("z=0", 0),
        ("z=0.1", 0),
        ("z=0.25", 1),
        ("z=0.49", 1),
        ("z=0.5", 2),
        ("z=0.8", 3),
        ("z=1", 3),
    ] {
        assert_eq!(png(coordinate), layers[k], "{coordinate} is in layer {k}");
    }
    assert_ne!(layers[1], layers[2]);
    // x and i, y and j name the same layers.
    assert_eq!(png("x=0.5"), png("i=1"));
    assert_eq!(png("y=0.4"), png("j=1"));
    for (slice, says, code) in [
        ("z=1.5", "--slice z=1.5 is outside the grid (z from 0 to 1)", 1),
        ("k=4", "--slice k=4 is outside the grid (k from 0 to 3)", 1),
        ("k=0.5", "a cell index must be a whole number", 2),
        ("w=1", "expected x=X, y=Y or z=Z (a coordinate) or i=I, j=J or k=K", 2),
    ] {
        let out = meshvol(&[
            "grid",
            p(&mesh),
            "--cells",
            "2,3,4",
            "--png",
            p(&d.join("x.png")),
            "--slice",
            slice,
        ]);
        assert_eq!(out.status.code(), Some(code), "{slice}");
        assert!(text(&out).1.contains(says), "{slice}: {}", text(&out).1);
    }
}

/// The subcommands, as `meshvol --help` lists them.
fn subcommands() -> Vec<String> {
    let help = text(&meshvol(&["--help"])).0;
    let list = help.split("Commands:").nth(1).unwrap().split("Options:").next().unwrap();
    let names: Vec<String> = list
        .lines()
        .filter(|l| l.starts_with("  ") && !l.starts_with("   "))
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|n| n != "help")
        .collect();
    assert!(names.len() >= 14 && names.contains(&"completions".to_string()), "{names:?}");
    names
}

#[test]
fn completions_and_the_manual_page_name_every_subcommand() {
    let names = subcommands();
    for shell in ["bash", "zsh", "fish", "powershell", "elvish"] {
        let out = meshvol(&["completions", shell]);
        let (script, err) = text(&out);
        assert!(out.status.success() && script.len() > 1000, "{shell}: {err}");
        for name in &names {
            assert!(script.contains(name.as_str()), "{shell} completions lack {name}");
        }
        assert!(script.contains("recursive") && script.contains("glob"), "{shell}");
    }
    assert_eq!(meshvol(&["completions", "tcsh"]).status.code(), Some(2));
    let (page, _) = text(&meshvol(&["man"]));
    assert!(page.starts_with(".ie") || page.contains(".TH meshvol 1"), "{page}");
    for name in &names {
        assert!(
            page.contains(&format!("meshvol\\-{name}")) || page.contains(name.as_str()),
            "man lacks {name}"
        );
    }
    let (volume, _) = text(&meshvol(&["man", "volume"]));
    assert!(volume.contains(".TH meshvol-volume 1") && volume.contains("\\-\\-format"), "{volume}");
    let out = meshvol(&["man", "nope"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out).1.contains("volume, check"));
}

/// Every command's `--help` ends with examples of it; those that read only the sample
/// run as shown (from a folder holding `samples/`, outputs written there) and succeed.
#[test]
fn help_examples_run() {
    let bin = common::bin();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("samples")).unwrap();
    std::fs::copy(
        root.join("samples/flanged-bushing.stl"),
        dir.path().join("samples/flanged-bushing.stl"),
    )
    .unwrap();
    // The command under test as `meshvol` on the PATH (MESHVOL_BIN may name it otherwise).
    let on_path = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(bin, on_path.path().join("meshvol")).unwrap();
    let path =
        format!("{}:{}", on_path.path().display(), std::env::var("PATH").unwrap_or_default());
    let mut ran = 0;
    for name in subcommands() {
        let (help, _) = text(&meshvol(&[&name, "--help"]));
        let examples: Vec<&str> = help
            .split("Examples:\n")
            .nth(1)
            .unwrap_or_else(|| panic!("{name} --help has no examples"))
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect();
        assert!(examples.len() >= 2, "{name}: {examples:?}");
        for example in examples {
            assert!(
                example.contains(&format!("meshvol {name}"))
                    || example.contains(&format!("| meshvol {name}")),
                "{example}"
            );
            let command = example.split("  #").next().unwrap();
            let words: Vec<&str> = command.split_whitespace().collect();
            let reads_only_samples = command.contains("samples/")
                && words
                    .iter()
                    .filter(|w| {
                        w.contains('.')
                            && !w.starts_with([
                                '-', '0', '1', '2', '3', '4', '5', '6', '7', '8', '9',
                            ])
                            && !w.contains('=')
                    })
                    .all(|w| {
                        w.starts_with("samples/")
                            || w.starts_with('\'')
                            || [".npy", ".png", ".ply", ".csv"].iter().any(|e| w.ends_with(e))
                    });
            if !reads_only_samples || name == "completions" {
                continue;
            }
            let out = Command::new("sh")
                .args(["-c", command])
                .current_dir(dir.path())
                .env("PATH", &path)
                .output()
                .unwrap();
            assert!(out.status.success(), "{command}: {}", text(&out).1);
            ran += 1;
        }
    }
    assert!(ran >= 15, "{ran} examples ran");
}
