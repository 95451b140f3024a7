//! Stages 3–5 in order, and what of stages 6 and 8 needs no triangles: edges and sheets,
//! shells and their orientation, caps over holes and each shell's volume, the nesting
//! candidates and the Euler counts (see the stage table in `mod.rs`).

use super::error::{enter, CheckError};
use super::loops::Loops;
use super::{edges, euler, holes, nesting, sheets, shells, weld};
use crate::progress::StageReport;
use crate::Surface;

/// What the check derives from how faces connect, by edges and vertices (stages 3–5,
/// and the candidates of stage 6 and the counts of stage 8 that need no triangles).
pub(super) struct Connected {
    pub vertices: edges::VertexCounts,
    pub edges: usize,
    pub edge_counts: edges::EdgeCounts,
    /// Faces left alone at non-manifold edges.
    pub unpaired: usize,
    pub shells: shells::Shells,
    pub caps: holes::Caps,
    /// Per shell: its volume as propagated from its first face, holes capped.
    pub shell_signed: Vec<f64>,
    pub candidates: nesting::Candidates,
    pub counts: Vec<euler::ShellCounts>,
}

/// Edges, shells, orientation, caps and per-shell volumes of the kept faces.
pub(super) fn connect<S: Surface + ?Sized>(
    surface: &S,
    loops: &Loops,
    welded: &weld::Welded,
    kept: &[bool],
    stage: StageReport<'_>,
) -> Result<Connected, CheckError> {
    enter(stage, "finding edges")?;
    let (mut edges, vertices) = edges::edges(loops, welded, kept);
    let unpaired = sheets::pair(&mut edges, loops, welded);
    let edge_counts = edges::count(&edges, kept.len());
    enter(stage, "finding shells")?;
    let shells = shells::shells(loops, kept, &edges);
    enter(stage, "capping holes")?;
    let caps = holes::caps(loops, welded, &edges, &shells);
    let shell_signed = holes::shell_volumes(surface, welded, kept, &shells, &caps);
    enter(stage, "counting shells")?;
    let candidates = nesting::candidates(loops, welded, kept, &shells, &caps);
    let counts = euler::per_shell(loops, welded, kept, &shells, &edges, vertices.used);
    Ok(Connected {
        vertices,
        edges: edges.len(),
        edge_counts,
        unpaired,
        shells,
        caps,
        shell_signed,
        candidates,
        counts,
    })
}
