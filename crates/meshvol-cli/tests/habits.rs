//! CLI habits: a typo of a subcommand is not a file to measure; required arguments name
//! their alternatives; a warning names its file once; `±` says what it bounds.

mod common;
use common::{box_obj, meshvol, p, write};

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
