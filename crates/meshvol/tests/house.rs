//! The house rules ARCHITECTURE.md states, checked over every crate's sources: no source
//! or test file over 600 lines, and no import circle between files (a circle is
//! a set of files that reach each other by the paths they name).
//!
//! A path counts from where Rust resolves it: `crate::`, `super::`, `self::`, or a bare
//! first segment naming a child module of the file (`use connect::connect;` in a
//! `mod.rs`), in `use` trees with nested groups and in code. A name a module binds by
//! `use` (`pub use loops::Loop;`) is followed to the file that defines it, and a module's own
//! `pub use` of its descendants is its facade, not an import, unless the module also uses
//! the name itself. A module's `mod.rs` declaring its children is not an import either.
//! The crate root (`lib.rs`, `main.rs`) is a file like any other.

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

/// Each crate's folder named `name` (`src`, `tests`).
fn crate_dirs(name: &str) -> Vec<PathBuf> {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(crates)
        .unwrap()
        .map(|e| e.unwrap().path().join(name))
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

/// The code of a file: comments and the contents of string and character literals
/// blanked, and its `mod tests` block cut off.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]\nmod tests {").next().unwrap_or_default();
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            out.push(' ');
        } else if c == 'r'
            && matches!(next, Some('"' | '#'))
            && !(i > 0
                && ident(chars[i - 1])
                && !(chars[i - 1] == 'b' && (i < 2 || !ident(chars[i - 2]))))
            && chars[i + 1..].iter().find(|&&c| c != '#') == Some(&'"')
        {
            // A raw string: r"…", r#"…"#.
            let hashes = chars[i + 1..].iter().take_while(|&&c| c == '#').count();
            i += 2 + hashes;
            let end: String =
                std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
            let end: Vec<char> = end.chars().collect();
            while i < chars.len() && !chars[i..].starts_with(&end) {
                i += 1;
            }
            i += end.len();
            out.push_str("\"\"");
        } else if c == '"' {
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                i += if chars[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if c == '\'' && (next == Some('\\') || chars.get(i + 2) == Some(&'\'')) {
            // A character literal ('a', '\n', '\u{…}'); a lifetime ('a) has no closing quote.
            i += 1;
            while i < chars.len() && chars[i] != '\'' {
                i += if chars[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("' '");
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// What one file names.
#[derive(Debug, Default, PartialEq)]
struct Names {
    /// Every path it names, resolved to a path from the crate root.
    paths: Vec<Vec<String>>,
    /// Its `use` items: the name each binds in the module (which its children and, when
    /// public, other modules may name through it), and the path it names.
    bindings: Vec<(String, Vec<String>)>,
    /// The `pub use` items of paths below its own module that it does not use itself
    /// (its facade; `paths` leaves them out).
    facade: Vec<Vec<String>>,
}

/// The tokens of `code`: identifiers, `::`, and single punctuation characters.
fn tokens(code: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(c) = rest.chars().next() {
        let len = if c.is_alphanumeric() || c == '_' {
            rest.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(rest.len())
        } else if rest.starts_with("::") {
            2
        } else {
            c.len_utf8()
        };
        if !c.is_whitespace() {
            out.push(&rest[..len]);
        }
        rest = &rest[len..];
    }
    out
}

fn is_ident(token: &str) -> bool {
    token.chars().next().is_some_and(|c| c.is_alphabetic() || c == '_')
}

/// The items of the use tree starting at `tokens[*at]`, below `prefix`: each path and the
/// name it brings into scope (`None` for a glob).
fn use_tree(
    tokens: &[&str],
    at: &mut usize,
    prefix: &[String],
    out: &mut Vec<(Vec<String>, Option<String>)>,
) {
    let mut path = prefix.to_vec();
    if tokens.get(*at) == Some(&"::") {
        *at += 1; // `use ::extern_crate::…`; nothing of ours.
        path.push("::".into());
    }
    loop {
        match tokens.get(*at).copied() {
            Some("{") => {
                *at += 1;
                while !matches!(tokens.get(*at).copied(), Some("}") | None) {
                    use_tree(tokens, at, &path, out);
                    if tokens.get(*at) == Some(&",") {
                        *at += 1;
                    }
                }
                *at += 1;
                return;
            }
            Some("*") => {
                *at += 1;
                out.push((path, None));
                return;
            }
            Some(segment) if is_ident(segment) => {
                *at += 1;
                if tokens.get(*at) == Some(&"::") {
                    *at += 1;
                    path.push(segment.into());
                    continue;
                }
                let name = if segment == "self" {
                    path.last().cloned().unwrap_or_default()
                } else {
                    path.push(segment.into());
                    segment.into()
                };
                let name = if tokens.get(*at) == Some(&"as") {
                    *at += 2;
                    tokens[*at - 1].to_string()
                } else {
                    name
                };
                out.push((path, Some(name)));
                return;
            }
            _ => return,
        }
    }
}

/// `path` as written in module `module`, from the crate root; `None` for a path of
/// another crate (`::serde::…`, `std::…` is left as a child of `module` that no file is).
fn resolve(module: &[String], path: &[String]) -> Option<Vec<String>> {
    let mut out = module.to_vec();
    let mut segments = path.iter().peekable();
    match segments.peek().map(|s| s.as_str()) {
        Some("::" | "Self") | None => return None,
        Some("crate") => {
            out.clear();
            segments.next();
        }
        Some("self") => {
            segments.next();
        }
        _ => {}
    }
    while segments.peek().is_some_and(|s| *s == "super") {
        segments.next();
        out.pop()?;
    }
    out.extend(segments.filter(|s| *s != "self").cloned());
    Some(out)
}

/// What the code of module `module` names.
fn names(code: &str, module: &[String]) -> Names {
    let tokens = tokens(code);
    let mut names = Names::default();
    let mut used = vec![false; tokens.len()]; // the tokens of `use` items
    let mut items: Vec<(bool, Vec<String>, Option<String>)> = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        if tokens[i] == "use" && tokens.get(i.wrapping_sub(1)) != Some(&"::") {
            // `pub use`, `pub(crate) use`, `pub(in …) use`.
            let public = tokens[..i].last() == Some(&"pub")
                || tokens[..i].last() == Some(&")") && {
                    let open = tokens[..i].iter().rposition(|t| *t == "(").unwrap_or(0);
                    open > 0 && tokens[open - 1] == "pub"
                };
            let start = i;
            i += 1;
            let mut tree = Vec::new();
            use_tree(&tokens, &mut i, &[], &mut tree);
            while i < tokens.len() && tokens[i] != ";" {
                i += 1;
            }
            used[start..=i.min(tokens.len() - 1)].fill(true);
            items.extend(tree.into_iter().map(|(path, name)| (public, path, name)));
        }
        i += 1;
    }
    let rest: Vec<&str> = tokens.iter().zip(&used).filter(|(_, u)| !**u).map(|(t, _)| *t).collect();
    for (public, path, name) in items {
        let Some(path) = resolve(module, &path) else { continue };
        if let Some(name) = &name {
            names.bindings.push((name.clone(), path.clone()));
        }
        if public {
            let below = path.len() > module.len() && path.starts_with(module);
            let own_use = name.as_ref().is_some_and(|n| rest.contains(&n.as_str()));
            if below && !own_use {
                names.facade.push(path);
                continue;
            }
        }
        names.paths.push(path);
    }
    // Paths in code: `a::b…` not itself part of a longer path or a field access.
    let mut i = 0;
    while i < rest.len() {
        let starts = is_ident(rest[i])
            && rest.get(i + 1) == Some(&"::")
            && !(i > 0 && matches!(rest[i - 1], "::" | "." | "$"))
            || rest[i] == "crate" && i > 0 && rest[i - 1] == "$" && rest.get(i + 1) == Some(&"::");
        if !starts {
            i += 1;
            continue;
        }
        let mut path = vec![rest[i].to_string()];
        i += 1;
        while rest.get(i) == Some(&"::") && rest.get(i + 1).is_some_and(|t| is_ident(t)) {
            path.push(rest[i + 1].to_string());
            i += 2;
        }
        if let Some(path) = resolve(module, &path) {
            names.paths.push(path);
        }
    }
    names
}

/// The edges between the files of one crate: from each module (by its path, `a::b`, the
/// root "") to the modules whose files it names, given each module's code.
fn edges(files: &BTreeMap<Vec<String>, String>) -> BTreeMap<String, BTreeSet<String>> {
    edge_paths(files).into_iter().map(|(from, to)| (from, to.into_keys().collect())).collect()
}

/// [`edges`], each with the first path that makes it (`a::b::Thing`), to say why.
fn edge_paths(files: &BTreeMap<Vec<String>, String>) -> BTreeMap<String, BTreeMap<String, String>> {
    let names: BTreeMap<&Vec<String>, Names> =
        files.iter().map(|(module, code)| (module, names(code, module))).collect();
    // A path names the longest module that is a file; a name that file binds by `use` is
    // followed to where it comes from.
    let file_of = |path: &[String]| {
        let mut path = path.to_vec();
        for _ in 0..16 {
            let k = (0..=path.len()).rev().find(|&k| files.contains_key(&path[..k]))?;
            let next = path.get(k).cloned();
            let source = next.and_then(|n| {
                names[&path[..k].to_vec()]
                    .bindings
                    .iter()
                    .find(|(name, _)| *name == n)
                    .map(|(_, p)| p.clone())
            });
            match source {
                Some(source) if source != path[..=k] => {
                    path = [source, path[k + 1..].to_vec()].concat();
                }
                _ => return Some(path[..k].join("::")),
            }
        }
        None
    };
    names
        .iter()
        .map(|(module, names)| {
            let name = module.join("::");
            let mut to = BTreeMap::new();
            for p in &names.paths {
                match file_of(p) {
                    Some(m) if m != name => {
                        to.entry(m).or_insert_with(|| p.join("::"));
                    }
                    _ => {}
                }
            }
            (name, to)
        })
        .collect()
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
fn no_source_or_test_file_is_over_600_lines() {
    let mut long = Vec::new();
    for dir in crate_dirs("src").into_iter().chain(crate_dirs("tests")) {
        let mut files = Vec::new();
        rust_files(&dir, &mut files);
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
    for src in crate_dirs("src") {
        let crate_name = src.parent().unwrap().file_name().unwrap().to_string_lossy().into_owned();
        let mut files = Vec::new();
        rust_files(&src, &mut files);
        // A crate with both a lib.rs and a main.rs is two crates; the check takes the
        // library's files (main.rs names them through the crate's name, not `crate::`).
        let codes: BTreeMap<Vec<String>, String> = files
            .iter()
            .filter(|f| !(f.ends_with("main.rs") && src.join("lib.rs").is_file()))
            .map(|f| (module_of(&src, f), code(&std::fs::read_to_string(f).unwrap())))
            .collect();
        let paths = edge_paths(&codes);
        let named = |m: &String| if m.is_empty() { "(crate root)".to_string() } else { m.clone() };
        for circle in circles(&edges(&codes)) {
            let text = format!(
                "{crate_name}: {}",
                circle.iter().map(named).collect::<Vec<_>>().join(" ↔ ")
            );
            for from in &circle {
                for (to, path) in paths[from].iter().filter(|(to, _)| circle.contains(to)) {
                    eprintln!("{crate_name}: {} → {} (names {path})", named(from), named(to));
                }
            }
            found.push(text);
        }
    }
    assert!(
        found.is_empty(),
        "import circles (the edges that make them, and the path that makes each, are printed above; break each by moving what the files share down into a leaf): {found:#?}"
    );
}

fn module(m: &str) -> Vec<String> {
    m.split("::").filter(|s| !s.is_empty()).map(String::from).collect()
}

/// Every way of naming a path is read, from where it is written.
#[test]
fn paths_are_read_in_every_form() {
    let paths = |code_: &str, m: &str| names(&code(code_), &module(m)).paths;
    assert_eq!(paths("use crate::b::Thing;", "a"), vec![module("b::Thing")]);
    assert_eq!(
        paths("use super::a::{One, two::Three};", "x::b"),
        vec![module("x::a::One"), module("x::a::two::Three")]
    );
    assert_eq!(paths("let y = super::super::c::f(x);", "x::y::z"), vec![module("x::c::f")]);
    // Nested groups, `self` in a group, renames, globs.
    assert_eq!(
        paths("use crate::{a::{B, c::{D as E}}, f::{self, G}, h::*};", "z"),
        vec![module("a::B"), module("a::c::D"), module("f"), module("f::G"), module("h")]
    );
    // `self::` and a bare child path in a `mod.rs` (module `t`); `std::` becomes a path
    // under `t` that no file is, and `::ext::` is another crate's.
    assert_eq!(
        paths("use self::a::B;\nuse connect::connect;\nfn f() { loops::walk(); std::mem::take(x); ::ext::f(); }", "t"),
        vec![module("t::a::B"), module("t::connect::connect"), module("t::loops::walk"), module("t::std::mem::take")]
    );
    // Comments and strings are not code; `.method::<T>()` and `Self::` are not paths.
    assert_eq!(
        paths(
            "// crate::a::B\nlet s = \"super::c\"; /* self::d */ x.iter::<u8>(); Self::new();",
            "q"
        ),
        Vec::<Vec<String>>::new()
    );
    // A parent's `pub use` of its child is its facade unless it uses the name itself.
    let facade =
        names("pub use child::X;\npub(crate) use self::other::Y;\nfn f(y: Y) {}", &module("p"));
    assert_eq!(facade.facade, vec![module("p::child::X")]);
    assert_eq!(facade.paths, vec![module("p::other::Y")]);
    assert_eq!(
        facade.bindings,
        vec![("X".to_string(), module("p::child::X")), ("Y".to_string(), module("p::other::Y"))]
    );
}

/// The check finds a circle where there is one, through the crate root and child paths,
/// and none through a facade.
#[test]
fn a_circle_is_found_and_a_facade_is_not_one() {
    let edges_of = |files: &[(&str, &str)]| {
        edges(&files.iter().map(|(m, c)| (module(m), code(c))).collect::<BTreeMap<_, _>>())
    };
    let two = |a: &str, b: &str| vec![vec![a.to_string(), b.to_string()]];
    // Two files naming each other.
    let plain = edges_of(&[
        ("", "mod a; mod b;"),
        ("a", "use crate::b::Thing;"),
        ("b", "use super::a::f;"),
    ]);
    assert_eq!(circles(&plain), two("a", "b"));
    // A mod.rs using its child by a bare path, the child using the mod.rs's own item.
    let child =
        edges_of(&[("t", "mod c;\nuse c::walk;\npub struct E;"), ("t::c", "use super::E;")]);
    assert_eq!(circles(&child), two("t", "t::c"));
    // The crate root is a file: lib.rs using a child that uses lib.rs's own item.
    let root =
        edges_of(&[("", "mod q;\npub struct U;\nfn f() { q::g(); }"), ("q", "use crate::U;")]);
    assert_eq!(circles(&root), two("", "q"));
    // A facade: lib.rs re-exports from its children; a child naming the re-export is
    // followed to the file that defines it, and no circle runs through lib.rs.
    let facade = edges_of(&[
        ("", "mod q; mod u;\npub use u::U;\npub use q::g;"),
        ("q", "use crate::U;\npub fn g() {}"),
        ("u", "pub struct U;"),
    ]);
    assert_eq!(facade["q"], BTreeSet::from(["u".to_string()]));
    assert!(facade[""].is_empty());
    assert!(circles(&facade).is_empty());
    let edges = BTreeMap::from([
        ("a".to_string(), BTreeSet::from(["b".to_string()])),
        ("b".to_string(), BTreeSet::from(["a".to_string()])),
        ("c".to_string(), BTreeSet::from(["a".to_string()])),
    ]);
    assert_eq!(circles(&edges), two("a", "b"));
}

/// The command builds no report of its own (ARCHITECTURE.md, "every report goes through
/// `meshvol-report`"): no JSON object or serialized struct is made in its sources, so
/// every number it prints comes from a report struct.
#[test]
fn the_command_builds_no_report() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../meshvol-cli/src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut found = Vec::new();
    for file in files {
        let text = code(&std::fs::read_to_string(&file).unwrap());
        for marker in ["json!", "Serialize", "serde_json::Map", "serde_json::to_value"] {
            if text.contains(marker) {
                found.push(format!("{}: {marker}", file.display()));
            }
        }
    }
    assert!(found.is_empty(), "reports built in the command, not in meshvol-report: {found:#?}");
}
