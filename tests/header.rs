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

/// The sources of the C layer, `src/capi/*.rs`.
fn capi_sources() -> Vec<String> {
    let dir = root().join("src/capi");
    let mut out = Vec::new();
    for entry in std::fs::read_dir(&dir).expect("src/capi") {
        let path = entry.expect("entry").path();
        out.push(std::fs::read_to_string(&path).expect("source"));
    }
    out
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

#[test]
fn headers_compile_alone_in_every_cxx_standard() {
    for std in ["c++98", "c++11", "c++14", "c++17", "c++20"] {
        for header in [
            "pqp/pqp.h",
            "PQP.h",
            "PQP_Compile.h",
            "MatVec.h",
            "TriDist.h",
        ] {
            compile_header_alone(header, true, std);
        }
    }
}

/// Every exported function runs its body through the one boundary helper (`boundary`, or `status`
/// which wraps it), so that no panic can unwind into C.
#[test]
fn every_exported_function_goes_through_the_boundary() {
    let dir = root().join("src/capi");
    let mut exported = 0;
    for entry in std::fs::read_dir(&dir).expect("src/capi") {
        let path = entry.expect("entry").path();
        let src = std::fs::read_to_string(&path).expect("source");
        let mut rest = src.as_str();
        while let Some(at) = rest.find("extern \"C\" fn ") {
            let item = &rest[at..];
            let name: String = item["extern \"C\" fn ".len()..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            // The body: from the first '{' after the signature to its matching '}'.
            let open = item.find('{').expect("body");
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
            let body = &item[open + 1..end];
            // The body's last top-level expression (after any `let` of a closure) is the call.
            let last = last_expression(body);
            assert!(
                last.starts_with("boundary(") || last.starts_with("status("),
                "{}: {name} does not run its body through the boundary",
                path.display()
            );
            exported += 1;
            rest = &item[end..];
        }
    }
    assert_eq!(exported, exported_functions().len());
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
