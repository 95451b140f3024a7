//! 3MF: objects, components, transforms, units, errors.

mod common;

use common::*;
use meshvol::surface::FaceRange;
use meshvol_io::{Budget, Format, LengthUnit, Limits, Location};

fn model(unit: &str, resources: &str, build: &str) -> String {
    format!(
        r##"<?xml version="1.0" encoding="UTF-8"?>
<model {unit} xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02" xmlns:m="http://schemas.microsoft.com/3dmanufacturing/material/2015/02" xmlns:s="http://schemas.microsoft.com/3dmanufacturing/slice/2015/07">
<resources>
<m:colorgroup id="90"><m:color color="#F00F"/></m:colorgroup>
<s:slicestack id="91" zbottom="0"><s:slice ztop="1"><s:vertices><s:vertex x="5" y="5"/></s:vertices></s:slice></s:slicestack>
{resources}
</resources>
<build>{build}</build>
</model>"##
    )
}

fn volumes(loaded: &meshvol_io::Loaded) -> Vec<(String, f64)> {
    loaded
        .objects
        .iter()
        .map(|o| (o.name.clone(), volume(&FaceRange::new(&loaded.surface, o.faces.clone()))))
        .collect()
}

#[test]
fn items_components_transforms_and_units() {
    let resources = format!(
        r#"<object id="1" name="box &amp; co" type="model">{}</object>
<object id="2"><components><component objectid="1"/><component objectid="1" transform="1 0 0 0 1 0 0 0 1 10 0 0"/></components></object>
<object id="3" name="nested"><components><component objectid="2" transform="2 0 0 0 2 0 0 0 2 0 0 0"/></components></object>
<object id="4" type="support">{}</object>"#,
        three_mf_box_mesh([0.0; 3], [1.0, 2.0, 3.0]),
        three_mf_box_mesh([0.0; 3], [1.0, 1.0, 1.0]),
    );
    // A plain item; an item placing the two-box object with a shift; the nested object
    // scaled by 2 (volume ×8) and mirrored by the item (winding reversed back); a
    // support item, skipped.
    let build = r#"<item objectid="1"/>
<item objectid="2" partnumber="pair" transform="1 0 0 0 1 0 0 0 1 0 0 100"/>
<item objectid="3" transform="-1 0 0 0 1 0 0 0 1 0 0 0"/>
<item objectid="4"/>"#;
    let bytes = three_mf(&model(r#"unit="inch""#, &resources, build));
    let loaded = read_as("part.3mf", bytes).unwrap();
    assert_eq!(loaded.format, Format::ThreeMf);
    assert_eq!(loaded.unit, Some(LengthUnit::Inch));
    assert_eq!(
        volumes(&loaded),
        [("box & co".to_string(), 6.0), ("pair".to_string(), 12.0), ("nested".to_string(), 96.0)]
    );
    assert_eq!(loaded.warnings, ["skipped 1 build items that are not solids: object 4 (support)"]);
    // The item's shift applies after the component's: the second box of "pair" starts
    // at (10, 0, 100).
    let pair = triangles(&FaceRange::new(&loaded.surface, loaded.objects[1].faces.clone()));
    assert!(pair[12..].iter().flatten().all(|p| p[0] >= 10.0 && p[2] >= 100.0));
    // Mirrored by the item: x ≤ 0.
    let nested = triangles(&FaceRange::new(&loaded.surface, loaded.objects[2].faces.clone()));
    assert!(nested.iter().flatten().all(|p| p[0] <= 0.0));
}

/// The limits of a read are checked before the build is expanded: this build places
/// 8 objects (item 1; item 2 and its 2 components; item 3, its component and that one's
/// 2), 60 triangles in all (five boxes of 12), in a model part of about 1.9 KB.
#[test]
fn limits_are_checked_before_the_build_is_expanded() {
    let resources = format!(
        r#"<object id="1">{}</object>
<object id="2"><components><component objectid="1"/><component objectid="1" transform="1 0 0 0 1 0 0 0 1 10 0 0"/></components></object>
<object id="3"><components><component objectid="2"/></components></object>"#,
        three_mf_box_mesh([0.0; 3], [1.0, 2.0, 3.0]),
    );
    let build = r#"<item objectid="1"/><item objectid="2"/><item objectid="3"/>"#;
    let bytes = three_mf(&model("", &resources, build));
    let within =
        Limits { inflated_bytes: 1 << 20, placements: 8, faces: 60, memory: None, checked: true };
    let read = |limits: Limits| {
        meshvol_io::read_bytes_within(std::path::Path::new("a.3mf"), bytes.clone(), &limits)
    };
    assert_eq!(read(within).unwrap().triangle_count(), 60);
    let e = read(Limits { placements: 7, ..within }).unwrap_err();
    assert_eq!(e.budget, Some(Budget::Placements), "{e}");
    let e = read(Limits { faces: 59, ..within }).unwrap_err();
    assert_eq!(e.budget, Some(Budget::Faces), "{e}");
    let e = read(Limits { inflated_bytes: 1000, ..within }).unwrap_err();
    assert_eq!(e.budget, Some(Budget::InflatedBytes), "{e}");
    // Damage is not a budget.
    let e = read_as("a.3mf", b"PK\x03\x04 not a zip".to_vec()).unwrap_err();
    assert_eq!(e.budget, None, "{e}");
}

#[test]
fn default_unit_and_one_object() {
    let resources =
        format!(r#"<object id="7">{}</object>"#, three_mf_box_mesh([1.0; 3], [2.0, 2.0, 2.0]));
    let loaded =
        read_as("m.3MF", three_mf(&model("", &resources, r#"<item objectid="7"/>"#))).unwrap();
    assert_eq!(loaded.unit, Some(LengthUnit::Millimetre));
    assert!(loaded.objects.is_empty(), "one object: no list");
    assert_eq!(volume(&loaded.surface), 8.0);
    for (name, unit) in [
        ("micron", LengthUnit::Micrometre),
        ("meter", LengthUnit::Metre),
        ("foot", LengthUnit::Foot),
        ("centimeter", LengthUnit::Centimetre),
    ] {
        let m = model(&format!(r#"unit="{name}""#), &resources, r#"<item objectid="7"/>"#);
        assert_eq!(read_as("m.3mf", three_mf(&m)).unwrap().unit, Some(unit));
    }
}

#[test]
fn errors_name_the_part_and_line() {
    let part = |line| Some(Location::PartLine { part: "3D/3dmodel.model".into(), line });
    let mesh = three_mf_box_mesh([0.0; 3], [1.0; 3]);
    let cases = [
        (
            format!(r#"<object id="1">{}</object>"#, mesh.replace(r#"v3="3""#, r#"v3="8""#)),
            r#"<item objectid="1"/>"#,
            6,
            "uses vertex 8, but the object has 8 vertices",
        ),
        (
            format!(r#"<object id="1">{mesh}</object>"#),
            "\n\n<item objectid=\"2\"/>",
            10,
            "object 2 is not defined",
        ),
        (
            r#"<object id="1"><components><component objectid="2"/></components></object>
<object id="2"><components><component objectid="1"/></components></object>"#
                .to_string(),
            r#"<item objectid="1"/>"#,
            7,
            "contains itself",
        ),
        (
            format!(r#"<object id="1">{}</object>"#, mesh.replace(r#"x="1""#, r#"x="nan""#)),
            "",
            6,
            "non-finite",
        ),
        (
            format!(r#"<object id="1">{mesh}</object>"#),
            r#"<item objectid="1" transform="1 0 0"/>"#,
            8,
            "expected 12 finite numbers",
        ),
        (
            format!(r#"<object id="1">{mesh}</object>"#),
            r#"<item xmlns:p="http://schemas.microsoft.com/3dmanufacturing/production/2015/06" p:path="/3D/other.model" objectid="1"/>"#,
            8,
            "p:path",
        ),
        (
            format!(r#"<object id="1">{mesh}</object><object id="1">{mesh}</object>"#),
            "",
            6,
            "defined twice",
        ),
    ];
    for (resources, build, line, message) in cases {
        let e = read_err("e.3mf", three_mf(&model("", &resources, build)));
        assert_eq!(e.location, part(line), "{message}: {e}");
        assert!(e.message.contains(message), "{e}");
    }
    let e = read_err("e.3mf", three_mf("<model><resources>"));
    assert!(e.message.contains("ends inside"), "{e}");
    let e = read_err("e.3mf", three_mf(&model(r#"unit="furlong""#, "", "")));
    assert!(e.message.contains("unknown unit 'furlong'"), "{e}");
    let e = read_err("e.3mf", b"PK\x03\x04 not really".to_vec());
    assert!(e.message.contains("zip"), "{e}");
}

#[test]
fn build_expansion_is_bounded_before_allocating() {
    // Each object holds its child ten times: 10^8 boxes.
    let mut resources =
        format!(r#"<object id="0">{}</object>"#, three_mf_box_mesh([0.0; 3], [1.0; 3]));
    for level in 1..=8 {
        resources += &format!(r#"<object id="{level}"><components>"#);
        for _ in 0..10 {
            resources += &format!(r#"<component objectid="{}"/>"#, level - 1);
        }
        resources += "</components></object>";
    }
    // Refused by the count of placements before any is made: expanding 10^8 boxes would
    // not come back with this error.
    let e = read_err("big.3mf", three_mf(&model("", &resources, r#"<item objectid="8"/>"#)));
    assert!(e.message.contains("placed objects"), "{e}");
}

/// Components placing one tetrahedron `rows × columns` times (two levels of components),
/// each copy moved by (2i, 2j, 0): the volume is exactly the copies' count over 6.
#[test]
fn many_placements_of_one_object_read_in_linear_time() {
    let (rows, columns) = (100, 1000);
    let mut model = String::from(
        r#"<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>
        <object id="1" type="model"><mesh><vertices>
        <vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/><vertex x="0" y="0" z="1"/>
        </vertices><triangles><triangle v1="0" v2="2" v3="1"/><triangle v1="0" v2="1" v3="3"/>
        <triangle v1="0" v2="3" v3="2"/><triangle v1="1" v2="2" v3="3"/></triangles></mesh></object>
        <object id="2" type="model"><components>"#,
    );
    for i in 0..columns {
        model +=
            &format!(r#"<component objectid="1" transform="1 0 0 0 1 0 0 0 1 {} 0 0"/>"#, 2 * i);
    }
    model += r#"</components></object><object id="3" type="model"><components>"#;
    for j in 0..rows {
        model +=
            &format!(r#"<component objectid="2" transform="1 0 0 0 1 0 0 0 1 0 {} 0"/>"#, 2 * j);
    }
    model += r#"</components></object></resources><build><item objectid="3"/></build></model>"#;
    let loaded = read_as("many.3mf", three_mf(&model)).unwrap();
    let copies = rows * columns;
    assert_eq!(loaded.face_count(), 4 * copies);
    // Exact: the correctly rounded volume of the whole is copies / 6 rounded once.
    let exact = meshvol::exact_signed_volume(&loaded.surface).unwrap();
    assert_eq!(exact, copies as f64 / 6.0);
}
