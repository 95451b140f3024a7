//! The docs are tests: every ```` ```console ```` block of README.md and docs/*.md is run
//! by `trycmd` and its output compared, so an example whose output drifts fails
//! `cargo test` (and CI).
//!
//! A console block is a sequence of `$ meshvol ...` lines (`> ` continues a command,
//! `? failed` or `? 1` expects a failure) each followed by what the command prints,
//! stdout and stderr together. In the expected output `[..]` matches the rest of a line
//! and a line `...` any number of lines: use them only for what legitimately varies
//! (timings, thread counts, absolute paths). Blocks that are not runnable (installs,
//! builds, pipelines from other tools) are ```` ```sh ````; output fragments and usage
//! synopses are ```` ```text ````: the harness skips both. A bare ```` ``` ```` fence
//! would be read as a console block, so every block names its language.
//!
//! The commands run in a scratch folder holding a copy of `samples/`, so the docs name
//! the sample files as `samples/NAME` (as they are named from the repository root) and
//! whatever an example writes (`--out cells.npy`) lands in the scratch folder.
//!
//! To refresh the expected outputs after a deliberate change:
//! `TRYCMD=overwrite cargo test -p meshvol-cli --test docs`, then read the diff and put
//! back the `[..]` of timings (overwrite writes the output as it came). trycmd compares the
//! output's final newline too: a block shows it as an empty line before the next `$` or
//! the closing fence.

mod common;

use std::path::{Path, PathBuf};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().expect("the repository root")
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// The Markdown files whose examples are tests.
fn pages(root: &Path) -> Vec<PathBuf> {
    let mut pages = vec![root.join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    pages
}

/// Every fence that opens a block names its language: trycmd reads a bare fence as a
/// console block, and a page with no console block at all would pass unseen.
#[test]
fn every_block_names_its_language() {
    let root = repo_root();
    let mut bare = Vec::new();
    for page in pages(&root) {
        let text = std::fs::read_to_string(&page).unwrap();
        let mut open = false;
        for (n, line) in text.lines().enumerate() {
            if let Some(rest) = line.trim_start().strip_prefix("```") {
                if !open && rest.trim().is_empty() {
                    bare.push(format!("{}:{}", page.display(), n + 1));
                }
                open = !open;
            }
        }
        assert!(!open, "{}: a code block is not closed", page.display());
    }
    assert!(
        bare.is_empty(),
        "code blocks without a language (```console, ```sh, ```text, ...): {bare:?}"
    );
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    assert!(
        readme.contains("```console\n$ meshvol samples/flanged-bushing.stl\n"),
        "README's first example is a console block the harness runs"
    );
}

#[test]
fn docs_examples_print_what_they_say() {
    let root = repo_root();
    let scratch = tempfile::tempdir().unwrap();
    copy_dir(&root.join("samples"), &scratch.path().join("samples"));
    // trycmd runs each page's commands in the current directory.
    std::env::set_current_dir(scratch.path()).unwrap();

    let cases = trycmd::TestCases::new();
    cases
        .register_bin("meshvol", common::bin())
        .register_bin("cat", Path::new("/bin/cat"))
        // The same output on any machine: no progress bar, whatever the terminal.
        .env("MESHVOL_PROGRESS_DELAY_MS", "3600000")
        .env("NO_COLOR", "1");
    for page in pages(&root) {
        cases.case(page);
    }
    cases.run();
}
