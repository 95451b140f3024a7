//! CLI habits: a typo of a subcommand is not a file to measure; required arguments name
//! their alternatives; a warning names its file once; `±` says what it bounds; every
//! manual page at once, and a typo of a page's name suggests it; `intersect` prints CSV
//! as every command that prints one report per input does; bash completes with the
//! completion script.

mod common;
use common::{box_obj, f, meshvol, p, write};
use serde_json::Value;

#[test]
fn a_typo_of_a_subcommand_suggests_it() {
    let dir = tempfile::tempdir().unwrap();
    let part = write(dir.path(), "part.obj", box_obj([0.0; 3], [1.0; 3], 1, true, false));
    for (typo, meant) in [("chek", "check"), ("volme", "volume"), ("prfile", "profile")] {
        let out = meshvol(&[typo, p(&part)]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(&format!("did you mean `{meant}`?")), "{err}");
        assert!(out.stdout.is_empty());
    }
    // A file by that name is measured: `meshvol FILE` still means `meshvol volume FILE`.
    let chek = write(dir.path(), "chek", box_obj([0.0; 3], [1.0; 3], 1, true, false));
    let out = std::process::Command::new(common::bin())
        .arg("chek")
        .current_dir(chek.parent().unwrap())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn required_arguments_name_the_alternatives() {
    let dir = tempfile::tempdir().unwrap();
    let part = write(dir.path(), "part.obj", box_obj([0.0; 3], [1.0; 3], 1, true, false));
    for (command, a, b) in [
        ("grid", "--cells", "--pitch"),
        ("profile", "--levels", "--step"),
        ("below", "--plane", "--volume"),
    ] {
        let out = meshvol(&[command, p(&part)]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(a) && err.contains(b), "{command}: {err}");
    }
}

#[test]
fn plus_minus_is_labelled() {
    let dir = tempfile::tempdir().unwrap();
    let part = write(dir.path(), "part.obj", box_obj([0.0; 3], [1.0; 3], 1, true, false));
    let text = String::from_utf8_lossy(&meshvol(&["volume", p(&part)]).stdout).into_owned();
    assert!(text.contains(" rounding)"), "{text}");
    let text = String::from_utf8_lossy(&meshvol(&["check", p(&part)]).stdout).into_owned();
    assert!(text.contains(" caps"), "{text}");
}

#[test]
fn a_warning_names_its_file_once() {
    let dir = tempfile::tempdir().unwrap();
    // An open box: capped, with a warning.
    let part = write(dir.path(), "open.obj", box_obj([0.0; 3], [1.0; 3], 1, true, true));
    for args in [vec!["grid", p(&part), "--cells", "1,1,1"], vec!["union", p(&part)]] {
        let out = meshvol(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        let name = p(&part);
        assert!(err.contains(&format!("{name}: ")), "{err}");
        assert!(!err.contains(&format!("{name}: {name}")), "{args:?}: {err}");
        let mut json = args.clone();
        json.push("--json");
        let out = String::from_utf8_lossy(&meshvol(&json).stdout).into_owned();
        assert!(!out.contains(&format!("\"{name}: ")), "{out}");
    }
}

/// The subcommands, as `meshvol --help` lists them.
fn subcommands() -> Vec<String> {
    let help = String::from_utf8_lossy(&meshvol(&["--help"]).stdout).into_owned();
    let list = help.split("Commands:").nth(1).unwrap().split("Options:").next().unwrap();
    list.lines()
        .filter(|l| l.starts_with("  ") && !l.starts_with("   "))
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|n| n != "help")
        .collect()
}

#[test]
fn man_all_writes_the_pages_man_prints_one_by_one() {
    let dir = tempfile::tempdir().unwrap();
    let pages = dir.path().join("man1");
    let out = meshvol(&["man", "--all", p(&pages)]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let names = subcommands();
    let mut expected: Vec<String> = names.iter().map(|n| format!("meshvol-{n}.1")).collect();
    expected.push("meshvol.1".to_string());
    let mut written: Vec<String> = std::fs::read_dir(&pages)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    written.sort();
    expected.sort();
    assert_eq!(written, expected);
    // It says what it wrote, one path a line.
    let listed = String::from_utf8_lossy(&out.stdout).lines().count();
    assert_eq!(listed, expected.len());
    // Each page is the one `meshvol man [NAME]` prints.
    assert_eq!(std::fs::read(pages.join("meshvol.1")).unwrap(), meshvol(&["man"]).stdout);
    for name in &names {
        let page = std::fs::read(pages.join(format!("meshvol-{name}.1"))).unwrap();
        assert_eq!(page, meshvol(&["man", name]).stdout, "{name}");
    }
    // A folder that cannot be made is an error naming it.
    let file = write(dir.path(), "plain", "x");
    let out = meshvol(&["man", "--all", &format!("{}/sub", p(&file))]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains(p(&file)));
}

#[test]
fn a_mistyped_manual_page_suggests_the_nearest() {
    for (typo, meant) in [("gridd", "grid"), ("intresect", "intersect"), ("vol", "volume")] {
        let out = meshvol(&["man", typo]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(&format!("did you mean `{meant}`?")), "{err}");
        assert!(out.stdout.is_empty());
    }
    let err = String::from_utf8_lossy(&meshvol(&["man", "xyzzy"]).stderr).into_owned();
    assert!(!err.contains("did you mean") && err.contains("one of volume, check"), "{err}");
}

/// Parses CSV output into its header and rows.
fn csv_table(stdout: &[u8]) -> (Vec<String>, Vec<Vec<String>>) {
    let mut reader = csv::Reader::from_reader(stdout);
    let header = reader.headers().unwrap().iter().map(str::to_string).collect();
    let rows = reader.records().map(|r| r.unwrap().iter().map(str::to_string).collect());
    (header, rows.collect())
}

#[test]
fn intersect_prints_csv_for_a_pair_and_for_pairs() {
    let dir = tempfile::tempdir().unwrap();
    // A = [0, 2]³ and B = [1, 3]³ share [1, 2]³: |A∩B| = 1, IoU = 1 / (8 + 8 − 1);
    // C = [1.5, 2.5] × [0, 0.5]² shares 0.5³ with A and is apart from B, as D is from all.
    let a = write(dir.path(), "a.obj", box_obj([0.0; 3], [2.0; 3], 1, true, false));
    let b = write(dir.path(), "b.obj", box_obj([1.0; 3], [3.0; 3], 1, true, false));
    let c = write(dir.path(), "c.obj", box_obj([1.5, 0.0, 0.0], [2.5, 0.5, 0.5], 1, true, false));
    let d = write(dir.path(), "d.obj", box_obj([10.0; 3], [11.0; 3], 1, true, false));
    let out = meshvol(&["intersect", p(&a), p(&b), "--format", "csv"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (header, rows) = csv_table(&out.stdout);
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    assert_eq!(rows.len(), 1);
    let cell = |row: &[String], name: &str| row[column(name)].parse::<f64>().unwrap();
    assert!((cell(&rows[0], "volume") - 1.0).abs() < 1e-9);
    assert!((cell(&rows[0], "iou") - 1.0 / 15.0).abs() < 1e-9);
    assert_eq!(rows[0][column("file")], format!("{}, {}", p(&a), p(&b)));
    // The cells are the --json line's values (nested objects spread as `a.b`).
    let json: Value =
        serde_json::from_slice(&meshvol(&["intersect", p(&a), p(&b), "--json"]).stdout).unwrap();
    for key in ["volume", "lower", "upper", "iou", "dice", "volume_a", "union"] {
        assert_eq!(cell(&rows[0], key), f(&json[key]), "{key}");
    }
    let pairs = [p(&a), p(&b), p(&c), p(&d)];
    let out = meshvol(&[&["intersect", "--pairs"][..], &pairs, &["--format", "csv"]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (header, rows) = csv_table(&out.stdout);
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let found: Vec<(String, f64)> = rows
        .iter()
        .map(|r| (r[column("file")].clone(), r[column("volume")].parse::<f64>().unwrap()))
        .collect();
    let expected = [(p(&a), p(&b), 1.0), (p(&a), p(&c), 0.125)];
    assert_eq!(found.len(), expected.len(), "{found:?}");
    for ((file, volume), (x, y, v)) in found.iter().zip(expected) {
        assert_eq!(file, &format!("{x}, {y}"));
        assert!((volume - v).abs() < 1e-9, "{file}: {volume}");
    }
    // --format csv and --json do not go together.
    assert_eq!(
        meshvol(&["intersect", p(&a), p(&b), "--format", "csv", "--json"]).status.code(),
        Some(2)
    );
}

/// bash loads the completion script and completes with it: a subcommand from its first
/// letters, and `man`'s `--all`.
#[test]
fn bash_completes_with_the_script() {
    let script = meshvol(&["completions", "bash"]).stdout;
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "meshvol.bash", script);
    let complete = |words: &str| {
        let run = format!(
            "source {}; COMP_WORDS=({words}); COMP_CWORD=$((${{#COMP_WORDS[@]}} - 1)); \
             COMP_LINE='{words}'; COMP_POINT=${{#COMP_LINE}}; _meshvol meshvol; \
             printf '%s\\n' \"${{COMPREPLY[@]}}\"",
            p(&path)
        );
        let out = std::process::Command::new("bash").args(["-c", &run]).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stdout).lines().map(str::to_string).collect::<Vec<_>>()
    };
    assert!(complete("meshvol inter").contains(&"intersect".to_string()));
    assert!(complete("meshvol man --a").contains(&"--all".to_string()));
}
