//! Keeps the module graph one-way (docs/architecture.md): reads every `use` and every
//! `crate::`/`super::`/`self::` path in `src/` (comments and `mod tests` blocks left out), maps
//! each to the module (file) it names, and checks that
//! - the layers depend downwards only: C ABI -> queries -> model -> hierarchy -> bounding volumes
//!   -> geometry -> math;
//! - among the modules of one parent (the files of `query/`, of `query/search/`, of
//!   `bounding_volume/`, ...) no two import each other, directly or round a longer cycle.
//!
//! A module and its own parent may use each other (a parent re-exports its children's items, a
//! child uses its parent's traits), so such edges are not counted.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The layers, highest first: a layer may use only the layers after it.
const LAYERS: [&str; 7] = [
    "capi",
    "query",
    "model",
    "bvh",
    "bounding_volume",
    "geometry",
    "math",
];

/// Every module of the crate (a file), as its path below the crate root, with its code.
fn modules(dir: &Path, at: &[String], out: &mut BTreeMap<Vec<String>, String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_str().unwrap().to_string();
        if path.is_dir() {
            let mut sub = at.to_vec();
            sub.push(name);
            modules(&path, &sub, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let mut m = at.to_vec();
            if name != "mod" && name != "lib" {
                m.push(name);
            }
            out.insert(m, code_of(&std::fs::read_to_string(&path).unwrap()));
        }
    }
}

/// The text without comments, cut before a `#[cfg(test)] mod tests` block (whose `super` is the
/// file's own module).
fn code_of(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = String::new();
    for (i, line) in lines.iter().enumerate() {
        let t = line.trim();
        if t == "#[cfg(test)]" && lines.get(i + 1).is_some_and(|n| n.trim() == "mod tests {") {
            break;
        }
        let code = t.split("//").next().unwrap();
        out.push_str(code);
        out.push('\n');
    }
    out
}

/// The paths a `use` tree names, e.g. `super::{a, b::{c, d}}` gives `super::a`, `super::b::c`,
/// `super::b::d`.
fn expand_use(tree: &str) -> Vec<String> {
    let tree: String = tree.chars().filter(|c| !c.is_whitespace()).collect();
    let Some(open) = tree.find('{') else {
        return vec![tree];
    };
    let (prefix, inner) = (&tree[..open], &tree[open + 1..tree.len() - 1]);
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    parts
        .into_iter()
        .filter(|p| !p.is_empty())
        .flat_map(|p| expand_use(&format!("{prefix}{p}")))
        .collect()
}

/// Every path the code names from `crate`, `super` or `self`.
fn paths_in(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    // `use` statements, braces and all.
    while let Some(i) = rest.find("use ") {
        let before = rest[..i].chars().last();
        let after = &rest[i + 4..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            rest = after;
            continue;
        }
        let end = after.find(';').unwrap_or(after.len());
        out.extend(expand_use(&after[..end]));
        rest = &after[end..];
    }
    // Paths in expressions and types.
    let bytes = code.as_bytes();
    for start in ["crate::", "super::", "self::"] {
        for (i, _) in code.match_indices(start) {
            if i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_') {
                continue;
            }
            let len = code[i..]
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .unwrap_or(code.len() - i);
            out.push(code[i..i + len].to_string());
        }
    }
    out
}

/// The module a path names from module `at`: the longest known module its segments lead to.
fn target(at: &[String], path: &str, known: &BTreeSet<Vec<String>>) -> Option<Vec<String>> {
    let mut segs = path.split("::").filter(|s| !s.is_empty());
    let mut m: Vec<String> = match segs.next()? {
        "crate" => Vec::new(),
        "self" => at.to_vec(),
        "super" => at[..at.len().checked_sub(1)?].to_vec(),
        _ => return None,
    };
    let mut found = m.clone();
    for s in segs {
        if s == "super" {
            m.pop();
            found = m.clone();
            continue;
        }
        m.push(s.to_string());
        if known.contains(&m) {
            found = m.clone();
        } else {
            break;
        }
    }
    Some(found)
}

/// The module graph's edges between siblings: for a use of `to` by `from`, the children of their
/// deepest common ancestor that hold each (none when one holds the other).
fn sibling_edges() -> BTreeSet<(Vec<String>, Vec<String>)> {
    let mut mods = BTreeMap::new();
    modules(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        &[],
        &mut mods,
    );
    let known: BTreeSet<Vec<String>> = mods.keys().cloned().collect();
    let mut edges = BTreeSet::new();
    for (from, code) in &mods {
        for path in paths_in(code) {
            let Some(to) = target(from, &path, &known) else {
                continue;
            };
            let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
            if common < from.len() && common < to.len() {
                edges.insert((from[..=common].to_vec(), to[..=common].to_vec()));
            }
        }
    }
    edges
}

#[test]
fn layers_depend_downwards_only() {
    let rank = |m: &[String]| LAYERS.iter().position(|l| m.len() == 1 && m[0] == *l);
    for (from, to) in sibling_edges() {
        if let (Some(f), Some(t)) = (rank(&from), rank(&to)) {
            assert!(f < t, "{} uses {}, a layer above it", from[0], to[0]);
        }
    }
}

#[test]
fn sibling_modules_import_one_way() {
    let edges = sibling_edges();
    let nodes: BTreeSet<&Vec<String>> = edges.iter().flat_map(|(a, b)| [a, b]).collect();
    // Kahn's algorithm: whatever cannot be ordered lies on a cycle.
    let mut left: BTreeSet<&Vec<String>> = nodes;
    loop {
        let sink = left
            .iter()
            .find(|n| !edges.iter().any(|(a, b)| a == **n && left.contains(b)))
            .copied();
        match sink {
            Some(n) => {
                left.remove(n);
            }
            None => break,
        }
    }
    let on_cycles: Vec<String> = left.iter().map(|m| m.join("::")).collect();
    assert!(
        on_cycles.is_empty(),
        "modules on, or above, an import cycle: {on_cycles:?}"
    );
}

#[test]
fn the_reader_sees_the_imports() {
    // The parser itself: a nested `use` tree, and a cycle it must catch.
    assert_eq!(
        expand_use("super::{a, b::{c, d}}"),
        ["super::a", "super::b::c", "super::b::d"]
    );
    let edges = sibling_edges();
    let has = |a: &str, b: &str| {
        let split = |s: &str| s.split("::").map(String::from).collect::<Vec<_>>();
        edges.contains(&(split(a), split(b)))
    };
    assert!(has("query", "bvh"));
    assert!(has("bounding_volume::pss", "bounding_volume::ssv"));
    assert!(has("query::search::visit", "query::search::bounds"));
}
