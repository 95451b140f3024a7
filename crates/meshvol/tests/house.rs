//! The house rules ARCHITECTURE.md states, checked over every crate's sources: no source
//! file over 600 lines, and no import circle between files (a file names another by
//! `crate::…` or `super::…`; a circle is a set of files that reach each other that way).
//! A module's `mod.rs` declaring its children is not an import.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The longest a source file may be.
const MAX_LINES: usize = 600;

/// Every `.rs` file under `dir`, recursively.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Each crate's `src/`.
fn crate_sources() -> Vec<PathBuf> {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(crates)
        .unwrap()
        .map(|e| e.unwrap().path().join("src"))
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    dirs
}

/// The module path of `file` under `src` (`grid::union::frames`; the crate root is "").
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let relative = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> =
        relative.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib" | "main")) {
        parts.pop();
    }
    parts
}

/// The code of a file without comments, string contents and its `mod tests` block.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]\nmod tests {").next().unwrap_or_default();
    text.lines()
        .map(|line| match line.find("//") {
            Some(i) => &line[..i],
            None => line,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The paths named from `crate::` or `super::` in `code` (of module `module`), each as a
/// module path, one per name in a `{…}` group.
fn named_paths(code: &str, module: &[String]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let bytes = code.as_bytes();
    for (start, prefix) in [("crate::", 0usize), ("super::", 1)] {
        let mut from = 0;
        while let Some(i) = code[from..].find(start) {
            let at = from + i;
            from = at + start.len();
            // Part of a longer name, or the second `super` of `super::super::`.
            let before = &bytes[..at];
            if before.last().is_some_and(|&c| c.is_ascii_alphanumeric() || c == b'_' || c == b':') {
                continue;
            }
            // `super` is the module holding this one (a `mod.rs`'s module path has no
            // `mod` in it, so that is one up for every file).
            let base: Vec<String> = if prefix == 0 {
                Vec::new()
            } else {
                module[..module.len().saturating_sub(1)].to_vec()
            };
            let rest = &code[from..];
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':' || c == '{'))
                .unwrap_or(rest.len());
            let path = &rest[..end];
            if let Some(group) = path.find('{') {
                let head = &path[..group];
                let close = rest.find('}').unwrap_or(rest.len());
                for item in rest[group + 1..close].split(',') {
                    let item = item.trim().split(" as ").next().unwrap_or_default();
                    let item = item.split("::{").next().unwrap_or_default();
                    out.push(join(&base, &format!("{head}{item}")));
                }
            } else {
                out.push(join(&base, path));
            }
        }
    }
    out
}

/// `path` (`a::b`, `super::a`) from module `base`.
fn join(base: &[String], path: &str) -> Vec<String> {
    let mut out = base.to_vec();
    for segment in path.split("::").filter(|s| !s.is_empty() && *s != "self") {
        if segment == "super" {
            out.pop();
        } else {
            out.push(segment.to_string());
        }
    }
    out
}

/// The circles (strongly connected sets of two or more files) of `edges`.
fn circles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    // Kosaraju: reachability both ways.
    let reach = |from: &String, forward: bool| {
        let mut seen = BTreeSet::from([from.clone()]);
        let mut stack = vec![from.clone()];
        while let Some(v) = stack.pop() {
            let next: Vec<String> = if forward {
                edges[&v].iter().cloned().collect()
            } else {
                edges.iter().filter(|(_, to)| to.contains(&v)).map(|(k, _)| k.clone()).collect()
            };
            for w in next {
                if seen.insert(w.clone()) {
                    stack.push(w);
                }
            }
        }
        seen
    };
    let mut done = BTreeSet::new();
    let mut out = Vec::new();
    for v in edges.keys() {
        if done.contains(v) {
            continue;
        }
        let both: Vec<String> = reach(v, true).intersection(&reach(v, false)).cloned().collect();
        done.extend(both.iter().cloned());
        if both.len() > 1 {
            out.push(both);
        }
    }
    out
}

#[test]
fn no_source_file_is_over_600_lines() {
    let mut long = Vec::new();
    for src in crate_sources() {
        let mut files = Vec::new();
        rust_files(&src, &mut files);
        for file in files {
            let lines = std::fs::read_to_string(&file).unwrap().lines().count();
            if lines > MAX_LINES {
                long.push(format!("{} ({lines} lines)", file.display()));
            }
        }
    }
    assert!(long.is_empty(), "over {MAX_LINES} lines: {long:#?}");
}

#[test]
fn no_import_circle_between_files() {
    let mut found = Vec::new();
    for src in crate_sources() {
        let mut files = Vec::new();
        rust_files(&src, &mut files);
        let modules: BTreeMap<String, (PathBuf, Vec<String>)> = files
            .iter()
            .map(|f| {
                let m = module_of(&src, f);
                (m.join("::"), (f.clone(), m))
            })
            .collect();
        // A path names the longest module that is a file.
        let file_of = |path: &[String]| {
            (0..=path.len()).rev().map(|k| path[..k].join("::")).find(|m| modules.contains_key(m))
        };
        let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (name, (file, module)) in &modules {
            let text = std::fs::read_to_string(file).unwrap();
            let to: BTreeSet<String> = named_paths(&code(&text), module)
                .iter()
                .filter_map(|p| file_of(p))
                .filter(|m| m != name && !m.is_empty())
                .collect();
            edges.insert(name.clone(), to);
        }
        for circle in circles(&edges) {
            found.push(format!("{}: {}", src.display(), circle.join(" ↔ ")));
        }
    }
    assert!(found.is_empty(), "import circles: {found:#?}");
}

/// The check finds a circle where there is one: two files naming each other.
#[test]
fn a_circle_of_two_files_is_found() {
    let module = |m: &str| m.split("::").map(String::from).collect::<Vec<_>>();
    let a = named_paths("use crate::b::Thing;", &module("a"));
    let b = named_paths("use super::a::{One, two::Three};", &module("x::b"));
    let c = named_paths("let y = super::super::c::f(x);", &module("x::y::z"));
    assert_eq!(a, vec![module("b::Thing")]);
    assert_eq!(b, vec![module("x::a::One"), module("x::a::two::Three")]);
    assert_eq!(c, vec![module("x::c::f")]);
    let edges = BTreeMap::from([
        ("a".to_string(), BTreeSet::from(["b".to_string()])),
        ("b".to_string(), BTreeSet::from(["a".to_string()])),
        ("c".to_string(), BTreeSet::from(["a".to_string()])),
    ]);
    assert_eq!(circles(&edges), vec![vec!["a".to_string(), "b".to_string()]]);
}
