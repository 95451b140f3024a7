//! Stage 8, Euler characteristic: χ = V − E + F per shell, and the genus (2 − χ)/2 of a
//! closed orientable one (a sphere 0, a torus 1).
//!
//! F counts the shell's kept faces, E its edges (an edge belongs to each shell that
//! has a sheet there), V its vertices: a vertex belongs to each shell one of whose kept
//! faces uses it, once (a vertex is shared by shells only at non-manifold points), in
//! whatever order the faces come.

use super::edges::Edges;
use super::loops::Loops;
use super::shells::Shells;
use super::weld::Welded;

/// One shell's counts.
pub(super) struct ShellCounts {
    pub faces: usize,
    pub euler_characteristic: i64,
}

/// The counts of each of `shells`, from the `kept` faces of `loops` and the `edges`
/// (each its uses).
pub(super) fn per_shell(
    loops: &Loops,
    welded: &Welded,
    kept: &[bool],
    shells: &Shells,
    edges: &Edges,
) -> Vec<ShellCounts> {
    let shell_of_face = &shells.of_face;
    let mut faces = vec![0usize; shells.count];
    for f in (0..kept.len()).filter(|&f| kept[f]) {
        faces[shell_of_face[f] as usize] += 1;
    }
    // An edge counts once in each shell that has a sheet there (a non-manifold edge
    // between two bodies is an edge of each).
    let mut edges_in = vec![0usize; shells.count];
    let mut here = Vec::new();
    for g in edges.iter() {
        here.clear();
        here.extend(g.chunks(2).map(|sheet| shell_of_face[sheet[0].face() as usize]));
        here.sort_unstable();
        here.dedup();
        for &s in &here {
            edges_in[s as usize] += 1;
        }
    }
    // Each vertex counts in the first shell that uses it; the (vertex, shell) pairs of
    // the other shells using it (non-manifold points only, so few) once each.
    let mut vertices = vec![0i64; shells.count];
    let mut first_shell_of_vertex = vec![u32::MAX; welded.positions.len()];
    let mut shared: Vec<(u32, u32)> = Vec::new();
    for f in (0..kept.len()).filter(|&f| kept[f]) {
        let s = shell_of_face[f];
        for c in loops.face(f) {
            let v = welded.corner_vertex[c];
            match first_shell_of_vertex[v as usize] {
                u32::MAX => {
                    first_shell_of_vertex[v as usize] = s;
                    vertices[s as usize] += 1;
                }
                first if first == s => {}
                _ => shared.push((v, s)),
            }
        }
    }
    shared.sort_unstable();
    shared.dedup();
    for &(_, s) in &shared {
        vertices[s as usize] += 1;
    }
    (0..shells.count)
        .map(|s| ShellCounts {
            faces: faces[s],
            euler_characteristic: vertices[s] - edges_in[s] as i64 + faces[s] as i64,
        })
        .collect()
}

/// (2 − χ)/2 for a closed orientable shell.
pub(super) fn genus(closed: bool, orientable: bool, euler_characteristic: i64) -> Option<i64> {
    let chi = euler_characteristic;
    (closed && orientable && chi % 2 == 0).then_some((2 - chi) / 2)
}
