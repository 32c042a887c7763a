//! The C headers: the checked-in `include/pqp/pqp.h` is exactly what build.rs generates from
//! src/capi, every declaration in it is documented, and every header compiles alone, warning-free,
//! in each language standard it supports.

mod c_toolchain;

use c_toolchain::{compile_header_alone, root};

/// What build.rs generated from src/capi for this build.
const GENERATED: &str = include_str!(concat!(env!("OUT_DIR"), "/pqp.h"));

fn checked_in() -> String {
    std::fs::read_to_string(root().join("include/pqp/pqp.h")).expect("include/pqp/pqp.h")
}

#[test]
fn checked_in_header_is_what_build_rs_generates() {
    let checked_in = checked_in();
    if checked_in != GENERATED {
        let line = checked_in
            .lines()
            .zip(GENERATED.lines())
            .position(|(a, b)| a != b)
            .map_or_else(|| "the end".to_string(), |n| format!("line {}", n + 1));
        panic!(
            "include/pqp/pqp.h differs from the header generated from src/capi (first at {line}).\n\
             Regenerate it with `PQP_UPDATE_HEADER=1 cargo build` and commit it."
        );
    }
}

#[test]
fn header_has_guards_and_includes() {
    let h = checked_in();
    assert!(h.contains("#ifndef PQP_PQP_H\n#define PQP_PQP_H\n"));
    assert!(h.trim_end().ends_with("#endif  /* PQP_PQP_H */"));
    assert!(h.contains("#include <stdint.h>"));
    assert!(h.contains("#ifdef __cplusplus\nextern \"C\" {\n"));
    // Negative constants are parenthesised, so that they are single operands wherever expanded.
    assert!(h.contains("#define PQP_ERR_INTERNAL (-10)\n"));
}

/// A function declaration of the header with the comment just above it.
struct Declaration {
    name: String,
    returns_void: bool,
    params: Vec<String>,
    doc: String,
}

/// Splits the header into function declarations with their doc comments (cbindgen puts each
/// comment right above its item).
fn declarations(header: &str) -> Vec<Declaration> {
    let mut out = Vec::new();
    let mut doc = String::new();
    let mut lines = header.lines().peekable();
    while let Some(line) = lines.next() {
        if line.trim_start().starts_with("/**") {
            doc.clear();
            doc.push_str(line);
            let mut l = line;
            while !l.contains("*/") {
                l = lines.next().expect("unterminated comment");
                doc.push('\n');
                doc.push_str(l);
            }
            continue;
        }
        let is_function = !line.starts_with('#')
            && !line.starts_with(' ')
            && !line.starts_with('}')
            && line.contains("pqp_")
            && line.contains('(');
        if is_function {
            let mut decl = line.to_string();
            while !decl.contains(");") {
                decl.push(' ');
                decl.push_str(lines.next().expect("unterminated declaration").trim());
            }
            let open = decl.find('(').unwrap();
            let head = &decl[..open];
            let name = head.rsplit([' ', '*']).next().unwrap().to_string();
            let inner = &decl[open + 1..decl.rfind(')').unwrap()];
            let params = if inner.trim() == "void" {
                Vec::new()
            } else {
                inner
                    .split(',')
                    .map(|p| p.trim().rsplit([' ', '*']).next().unwrap().to_string())
                    .collect()
            };
            out.push(Declaration {
                name,
                returns_void: head.starts_with("void "),
                params,
                doc: std::mem::take(&mut doc),
            });
        } else if !line.trim().is_empty() {
            doc.clear();
        }
    }
    out
}

/// The parameter names an "@param" line documents: "@param R1, T1  the pose" names R1 and T1.
fn documented_params(doc: &str) -> Vec<String> {
    let mut names = Vec::new();
    for line in doc.lines() {
        if let Some((_, rest)) = line.split_once("@param") {
            for word in rest.split_whitespace() {
                names.push(word.trim_end_matches(',').to_string());
                if !word.ends_with(',') {
                    break;
                }
            }
        }
    }
    names
}

#[test]
fn every_function_is_documented() {
    let decls = declarations(&checked_in());
    // The header declares every function the C layer exports, and nothing else.
    let mut declared: Vec<&str> = decls.iter().map(|d| d.name.as_str()).collect();
    let mut exported = exported_functions();
    declared.sort_unstable();
    exported.sort_unstable();
    assert_eq!(declared, exported);
    for d in &decls {
        assert!(!d.doc.is_empty(), "{} has no doc comment", d.name);
        assert!(
            d.doc.contains("Thread safety:"),
            "{}: doc comment says nothing about thread safety",
            d.name
        );
        if !d.returns_void {
            assert!(d.doc.contains("@return"), "{}: no @return", d.name);
        }
        for p in &d.params {
            let documented = documented_params(&d.doc).iter().any(|n| n == p);
            assert!(documented, "{}: parameter {p} is not documented", d.name);
        }
        // A function returning a status code names the codes it can return.
        if d.doc.contains("@return PQP_OK") {
            assert!(
                d.doc.contains("PQP_ERR_"),
                "{}: no error codes named",
                d.name
            );
            if !d.params.is_empty() {
                assert!(
                    d.doc.contains("PQP_ERR_NULL_POINTER"),
                    "{}: NULL handling not documented",
                    d.name
                );
            }
        }
    }
}

#[test]
fn every_constant_is_documented() {
    let h = checked_in();
    let lines: Vec<&str> = h.lines().collect();
    let mut count = 0;
    for (i, line) in lines.iter().enumerate() {
        if line.starts_with("#define PQP_") && !line.starts_with("#define PQP_PQP_H") {
            count += 1;
            assert!(
                i > 0 && lines[i - 1].trim_end().ends_with("*/"),
                "{line} has no doc comment"
            );
        }
    }
    // Every constant of the C layer, and nothing else.
    let defined = capi_sources()
        .iter()
        .map(|src| src.matches("pub const PQP_").count())
        .sum::<usize>();
    assert_eq!(count, defined);
}

/// The sources of the C layer: every `.rs` file under `src/capi`, with its path.
fn capi_files() -> Vec<(std::path::PathBuf, String)> {
    let mut out = Vec::new();
    let mut dirs = vec![root().join("src/capi")];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).expect("src/capi") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let src = std::fs::read_to_string(&path).expect("source");
                out.push((path, src));
            }
        }
    }
    out
}

/// The sources of the C layer.
fn capi_sources() -> Vec<String> {
    capi_files().into_iter().map(|(_, src)| src).collect()
}

/// The names of the functions the C layer exports (`extern "C" fn` in `src/capi`).
fn exported_functions() -> Vec<String> {
    let mut names = Vec::new();
    for src in capi_sources() {
        for (at, _) in src.match_indices("extern \"C\" fn ") {
            let name: String = src[at + "extern \"C\" fn ".len()..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            names.push(name);
        }
    }
    names
}

#[test]
fn c_header_compiles_alone_in_c99_and_c11() {
    compile_header_alone("pqp/pqp.h", false, "c99");
    compile_header_alone("pqp/pqp.h", false, "c11");
}

/// The C++ headers: PQP 1.3's five, the two its programs also include, and the C interface.
const CXX_HEADERS: [&str; 9] = [
    "pqp/pqp.h",
    "pqp/pqp_cxx.h",
    "PQP.h",
    "PQP_Compile.h",
    "PQP_Internal.h",
    "Tri.h",
    "BV.h",
    "MatVec.h",
    "TriDist.h",
];

#[test]
fn headers_compile_alone_in_every_cxx_standard() {
    for std in ["c++98", "c++11", "c++14", "c++17", "c++20"] {
        for header in CXX_HEADERS {
            compile_header_alone(header, true, std);
        }
    }
}

/// PQP 1.3 code needs the status codes and contact flags as `const int` variables in C++:
/// pqp/pqp_cxx.h must turn every one of pqp.h's macros for them into a constant (a code added to the
/// C layer and forgotten there would stay a macro, and `::PQP_ERR_NEW` would not compile).
#[test]
fn cxx_header_declares_every_code_and_flag_as_a_constant() {
    let cxx = std::fs::read_to_string(root().join("include/pqp/pqp_cxx.h")).expect("pqp_cxx.h");
    let mut checked = 0;
    for line in checked_in().lines() {
        let Some(rest) = line.strip_prefix("#define ") else {
            continue;
        };
        let name = rest.split_whitespace().next().unwrap_or("");
        let is_code = name == "PQP_OK" || name.starts_with("PQP_ERR_");
        if !(is_code || name.ends_with("_CONTACTS") || name.ends_with("_CONTACT")) {
            continue;
        }
        assert!(
            cxx.contains(&format!("#undef {name}\n")),
            "pqp_cxx.h does not #undef {name}"
        );
        assert!(
            cxx.contains(&format!("const int {name} = ")),
            "pqp_cxx.h does not declare const int {name}"
        );
        checked += 1;
    }
    assert!(
        checked >= 15,
        "only {checked} codes and flags found in pqp.h"
    );
}

/// Every exported function runs its body through the one boundary helper (`boundary`), directly
/// or through helpers of the C layer that do (`status`, `getter`, ...), so that no panic can
/// unwind into C.
#[test]
fn every_exported_function_goes_through_the_boundary() {
    // Every function of the C layer: its name, whether it is exported, and the call it ends in.
    let mut functions = Vec::new();
    for (path, src) in capi_files() {
        let mut rest = src.as_str();
        while let Some(at) = rest.find("fn ") {
            let item = &rest[at..];
            let exported = rest[..at].ends_with("extern \"C\" ");
            let word_start =
                at == 0 || !rest[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_');
            let name: String = item["fn ".len()..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            let Some(open) = item.find('{') else { break };
            if !word_start || name.is_empty() || item[..open].contains(';') {
                rest = &item["fn ".len()..];
                continue;
            }
            // The body: from the first '{' after the signature to its matching '}'.
            let mut depth = 0;
            let mut end = open;
            for (i, c) in item[open..].char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => {
                        depth -= 1;
                        if depth == 0 {
                            end = open + i;
                            break;
                        }
                    }
                    _ => {}
                }
            }
            let call = final_call(&item[open + 1..end]);
            functions.push((path.clone(), name, exported, call));
            rest = &item[end..];
        }
    }
    // The helpers that run the boundary: `boundary` itself, and any function ending in a call
    // of one of them.
    let mut helpers = vec!["boundary".to_string()];
    loop {
        let more: Vec<String> = functions
            .iter()
            .filter(|(_, name, _, call)| {
                !helpers.contains(name)
                    && helpers.iter().any(|h| {
                        call.starts_with(&format!("{h}(")) || call.starts_with(&format!("{h}::<"))
                    })
            })
            .map(|(_, name, _, _)| name.clone())
            .collect();
        if more.is_empty() {
            break;
        }
        helpers.extend(more);
    }
    let mut exported = 0;
    for (path, name, _, _) in functions.iter().filter(|f| f.2) {
        assert!(
            helpers.contains(name),
            "{}: {name} does not run its body through the boundary",
            path.display()
        );
        exported += 1;
    }
    assert_eq!(exported, exported_functions().len());
}

/// The call a function body ends in: its last top-level expression, without comments and without
/// `unsafe { }` around it.
fn final_call(body: &str) -> String {
    let code: String = body
        .lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    let mut last = last_expression(&code).to_string();
    while let Some(inner) = last.strip_prefix("unsafe") {
        let inner = inner.trim();
        let Some(inner) = inner.strip_prefix('{').and_then(|i| i.strip_suffix('}')) else {
            break;
        };
        last = last_expression(inner).to_string();
    }
    last
}

/// The text after the last `;` that is outside every bracket of `body`.
fn last_expression(body: &str) -> &str {
    let mut depth = 0i32;
    let mut start = 0;
    for (i, c) in body.char_indices() {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ';' if depth == 0 => start = i + 1,
            _ => {}
        }
    }
    body[start..].trim()
}
