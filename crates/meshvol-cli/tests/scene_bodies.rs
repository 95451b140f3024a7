//! Objects are bodies: a 3MF whose objects (items, or components of one item) lie one
//! inside another is measured as separate solids, their sum with a warning, and `union`
//! gives the union; one object holding the same shells keeps the cavity rule, and so do
//! an OBJ's groups. `union`'s `certified` says whether the interval is proven. Expected
//! values are the cubes' volumes; the corpus's `boolean.glb` is compared with trimesh's
//! and manifold3d's numbers.

mod common;
use common::{box_obj, f, meshvol, p, three_mf, write};

use serde_json::Value;
use std::path::Path;
use std::process::Output;

fn json(out: &Output) -> Value {
    assert!(out.status.success(), "stderr: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

/// The cube `min + [0, side]³` as 3MF `<vertex>` and `<triangle>` elements, the
/// vertices numbered from `base`: eight vertices, twelve outward triangles.
fn cube_xml(min: f64, side: f64, base: usize) -> (String, String) {
    let corner = |i: usize| [0, 1, 2].map(|k| min + side * (i >> k & 1) as f64);
    let quads =
        [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    let vertices = (0..8).map(|i| {
        let [x, y, z] = corner(i);
        format!(r#"<vertex x="{x}" y="{y}" z="{z}"/>"#)
    });
    let triangles = quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).map(|t| {
        let [a, b, c] = t.map(|v| v + base);
        format!(r#"<triangle v1="{a}" v2="{b}" v3="{c}"/>"#)
    });
    (vertices.collect(), triangles.collect())
}

/// A 3MF `<mesh>` of cubes `(min, side)`.
fn mesh_xml(cubes: &[(f64, f64)]) -> String {
    let parts: Vec<(String, String)> =
        cubes.iter().enumerate().map(|(k, &(min, side))| cube_xml(min, side, 8 * k)).collect();
    let (vertices, triangles): (Vec<String>, Vec<String>) = parts.into_iter().unzip();
    format!(
        "<mesh><vertices>{}</vertices><triangles>{}</triangles></mesh>",
        vertices.concat(),
        triangles.concat()
    )
}

/// A 3MF model part of `resources` and `build`.
fn model(resources: &str, build: &str) -> Vec<u8> {
    three_mf(&format!(
        r#"<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>{resources}</resources><build>{build}</build></model>"#
    ))
}

/// The packaging, a 4-cube [0, 4]³ (64), and the part, a unit cube [1, 2]³ (1) inside it.
const PACKAGING: (f64, f64) = (0.0, 4.0);
const PART: (f64, f64) = (1.0, 1.0);

/// The scene three ways: two build items, one item of two components, one object whose
/// mesh holds both shells (vertices 8..16 the part's).
fn scenes(dir: &Path) -> [std::path::PathBuf; 3] {
    let (big, small) = (mesh_xml(&[PACKAGING]), mesh_xml(&[PART]));
    let objects = format!(
        r#"<object id="1" name="packaging">{big}</object><object id="2" name="part">{small}</object>"#
    );
    let items = model(&objects, r#"<item objectid="1"/><item objectid="2"/>"#);
    let components = format!(
        r#"{objects}<object id="3" name="boxed"><components><component objectid="1"/><component objectid="2"/></components></object>"#
    );
    let components = model(&components, r#"<item objectid="3"/>"#);
    let one_mesh = mesh_xml(&[PACKAGING, PART]);
    let single = model(
        &format!(r#"<object id="1" name="hollow">{one_mesh}</object>"#),
        r#"<item objectid="1"/>"#,
    );
    [
        write(dir, "items.3mf", items),
        write(dir, "components.3mf", components),
        write(dir, "single.3mf", single),
    ]
}

#[test]
fn objects_inside_objects_are_summed_with_a_warning_and_unioned() {
    let dir = tempfile::tempdir().unwrap();
    let [items, components, single] = scenes(dir.path());
    let (outer, inner) = (PACKAGING.1.powi(3), PART.1.powi(3));
    for scene in [&items, &components] {
        let v = json(&meshvol(&["volume", "--json", p(scene)]));
        assert_eq!(f(&v["volume"]), outer + inner, "{scene:?}: {v}");
        assert_eq!(v["cavities"], 0);
        let warnings = v["warnings"].to_string();
        assert!(warnings.contains("'packaging' and 'part': one lies inside the other"), "{v}");
        assert!(warnings.contains("meshvol union"), "{v}");
        let pair = serde_json::json!([{"objects": ["packaging", "part"], "nested": true}]);
        assert_eq!(v["overlapping_objects"], pair);
        // `check` says the file does not bound one volume: exit 1.
        let out = meshvol(&["check", "--json", p(scene)]);
        assert_eq!(out.status.code(), Some(1));
        let c: Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(
            (&c["overlapping_objects"], &c["bounds_a_volume"]),
            (&pair, &Value::Bool(false))
        );
        let u = json(&meshvol(&["union", "--json", p(scene)]));
        assert_eq!(u["bodies"], 2);
        let names =
            [format!("{}, packaging (shell 0)", p(scene)), format!("{}, part (shell 1)", p(scene))];
        assert_eq!(u["body_names"], serde_json::json!(names));
        assert!(f(&u["lower"]) <= outer && outer <= f(&u["upper"]), "{u}");
        assert_eq!((&u["certified"], &u["uncertified_reason"]), (&Value::Bool(true), &Value::Null));
        let text = String::from_utf8(meshvol(&["union", p(scene)]).stdout).unwrap();
        assert!(text.contains("  certified        ["), "{text}");
    }
    // Written as one mesh, the objects become one body again: `repair` says so.
    let out = dir.path().join("repaired.stl");
    let r = json(&meshvol(&["repair", "--json", p(&items), "-o", p(&out)]));
    assert!(r["warnings"].to_string().contains("written as one object"), "{r}");
    // One object: the inner shell is a cavity, as slicers read it.
    let v = json(&meshvol(&["volume", "--json", p(&single)]));
    assert_eq!((f(&v["volume"]), &v["cavities"]), (outer - inner, &Value::from(1)));
    assert!(!v["warnings"].to_string().contains("share volume"), "{v}");
    assert_eq!(v["overlapping_objects"], serde_json::json!([]));
    let u = json(&meshvol(&["union", "--json", p(&single)]));
    assert!(f(&u["lower"]) <= outer - inner && outer - inner <= f(&u["upper"]), "{u}");
    assert_eq!(u["certified"], true);
}

#[test]
fn obj_groups_are_one_model_and_an_unchecked_union_is_not_certified() {
    let dir = tempfile::tempdir().unwrap();
    let obj = format!(
        "g packaging\n{}g part\n{}",
        box_obj([0.0; 3], [4.0; 3], 1, true, false),
        box_obj([1.0; 3], [2.0; 3], 9, true, false)
    );
    let obj = write(dir.path(), "groups.obj", obj);
    let v = json(&meshvol(&["volume", "--json", p(&obj)]));
    assert_eq!((f(&v["volume"]), &v["cavities"]), (63.0, &Value::from(1)));
    // Unchecked, the bodies are not known to be solids: the interval is not certified,
    // and the text says why beside it.
    let [items, ..] = scenes(dir.path());
    let u = json(&meshvol(&["union", "--json", "--no-check", p(&items)]));
    assert_eq!(u["certified"], false);
    assert!(u["uncertified_reason"].as_str().unwrap().contains("unchecked"), "{u}");
    let text = String::from_utf8(meshvol(&["union", "--no-check", p(&items)]).stdout).unwrap();
    assert!(!text.contains("certified        ["), "{text}");
    assert!(text.contains("not certified: measured unchecked"), "{text}");
}

/// The corpus's boolean.glb: 28 mesh instances (a base and 27 cutters), many inside
/// the base. Sum of the objects' volumes, 45.923614954679806: trimesh 5.2.0
/// (`sum(g.volume for g in trimesh.load(...).dump())`); the union, 38.27736872429054:
/// manifold3d 3.x (`Manifold.batch_boolean(..., OpType.Add).volume()`, float32).
#[test]
fn corpus_boolean_glb_sums_its_objects_and_contains_the_union() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/corpus/trimesh-models/boolean.glb");
    if !path.exists() {
        eprintln!("{} not found, skipping", path.display());
        return;
    }
    let (trimesh_sum, manifold_union) = (45.923614954679806, 38.27736872429054);
    // The sum again, exactly: each object's divergence sum over its own faces.
    let loaded = meshvol_io::read(&path).unwrap();
    assert_eq!(loaded.bodies.len(), 28);
    let exact: f64 = loaded
        .bodies
        .iter()
        .map(|b| {
            let faces = meshvol::surface::FaceRange::new(&loaded.surface, b.faces.clone());
            meshvol::exact_signed_volume(&faces).unwrap().abs()
        })
        .sum();
    assert!((exact - trimesh_sum).abs() <= 1e-9 * trimesh_sum, "{exact}");
    let v = json(&meshvol(&["volume", "--json", p(&path)]));
    assert!((f(&v["volume"]) - exact).abs() <= 1e-9 * exact, "{v}");
    assert!(v["warnings"].to_string().contains("share volume"), "{v}");
    let u = json(&meshvol(&["union", "--json", p(&path)]));
    assert_eq!(u["bodies"], 28);
    let (lower, upper) = (f(&u["lower"]), f(&u["upper"]));
    match u["certified"].as_bool() {
        Some(true) => assert!(lower <= manifold_union && manifold_union <= upper, "{u}"),
        _ => assert!(u["uncertified_reason"].is_string(), "{u}"),
    }
}
