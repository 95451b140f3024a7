//! The OBJ reader's unit tests.

use super::*;

#[test]
fn statements() {
    let kind = |line: &[u8]| classify(line, text::skip_blank(line, 0));
    assert_eq!(kind(b"  v 1 2 3"), (Statement::Vertex, 3));
    assert_eq!(kind(b"vt 1 2").0, Statement::Skip);
    assert_eq!(kind(b"o part").0, Statement::Object);
    assert_eq!(kind(b"g\n").0, Statement::Group);
    assert_eq!(kind(b"\tf 1 2 3\r\n").0, Statement::Face);
    assert_eq!(kind(b"f\r\n").0, Statement::Face);
    assert_eq!(kind(b"#v 1 2 3").0, Statement::Skip);
    assert_eq!(kind(b"\r\n").0, Statement::Skip);
    assert_eq!(kind(b"curv 0 1 2"), (Statement::Unknown, 4));
    assert_eq!(kind(b"1 2 3").0, Statement::Invalid);
    assert_eq!(kind(b"v1 2 3").0, Statement::Unknown);
}

#[test]
fn continued_lines() {
    assert_eq!(skip_line(b"a \\\r\nb\nc", 0), 7);
    assert_eq!(skip_line(b"a\n", 1), 2);
    assert_eq!(skip_blank_continued(b" \\ \r\n  7", 0), 7);
    assert_eq!(skip_blank_continued(b" \\x", 0), 1);
}

#[test]
fn chunked_negative_indices_resolve_across_chunks() {
    let mut file = String::new();
    for i in 0..200 {
        file += &format!("v {i} 0 0\nv {i} 1 0\nv {i} 0 1\nf -3 -2 -1\n");
    }
    let bytes = file.as_bytes();
    let (mesh, _) = read_chunked(bytes, &mut vec![], 100).unwrap();
    let bounds = line_boundaries(bytes, 0, 100);
    assert!(bounds.len() > 10);
    assert_eq!(mesh.face_count(), 200);
    for f in 0..200 {
        assert_eq!(mesh.face(f), &[3 * f as u32, 3 * f as u32 + 1, 3 * f as u32 + 2]);
    }
}

/// Any chunking gives what one sequential pass gives.
#[test]
fn chunking_does_not_change_the_result() {
    use crate::text::mutate::{assert_chunking_invisible, outcome};
    let mut file = String::from("# test\nv 0 0 0\nv 1 0 0\n");
    for i in 0..12 {
        file += &format!("v {i} 1 0 1 0 0\nf -1 -2 -3\nvt 0 0\nf 1/1 2//1 {} 3\n", i + 3);
        if i % 4 == 0 {
            file += "l 1 2\nf 1 2 \\\n 3\r\n";
        }
    }
    file += "f 12 13 14\n";
    let pieces: &[&[u8]] = &[
        b"\nf ",
        b"\nv ",
        b" -1",
        b" -9",
        b" 0",
        b" 99",
        b"/",
        b"//",
        b"\\",
        b"\\\n",
        b"\n",
        b" ",
        b"#",
        b"nan",
        b"l",
        b"p 1\n",
        b"curv 1\n",
        b"1",
        b"\no part\n",
        b"\ng group\n",
    ];
    let run = |bytes: &[u8], chunk: usize| {
        outcome(|w| {
            read_chunked(bytes, w, chunk)
                .map(|(m, objects)| (m.positions().to_vec(), m.faces().clone(), objects))
        })
    };
    let (ok, err) =
        assert_chunking_invisible(file.as_bytes(), pieces, 11, 3000, &[1, 20, 100], run);
    assert!(ok > 100 && err > 100, "{ok} {err}");
}
