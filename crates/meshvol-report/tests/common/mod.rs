//! Helpers shared by the report crate's integration tests.

use std::path::PathBuf;

/// The corpus's real mesh files (../shared/corpus/trimesh-models beside the repository),
/// sorted; `None`, with a note on stderr, where a clone has no corpus beside it.
pub fn corpus_files() -> Option<Vec<PathBuf>> {
    let corpus =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus/trimesh-models");
    if !corpus.exists() {
        eprintln!("corpus not found at {}, skipping", corpus.display());
        return None;
    }
    let mut files: Vec<_> =
        std::fs::read_dir(&corpus).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    Some(files)
}
