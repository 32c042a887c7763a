//! Every C and C++ code block of README.md is a complete program: each is compiled with the
//! system compiler and the project's warnings against the library cargo built for these tests,
//! run from the system's temporary directory, and must exit 0 without writing to stderr. (The
//! README's Rust blocks run as doc tests: src/lib.rs includes the README under `cfg(doctest)`.)

mod c_toolchain;

use c_toolchain::{build_program, root, run, scratch};
use std::process::Command;

/// The fenced code blocks of `text` whose info string is one of `langs`: (line, language, code).
fn code_blocks(text: &str, langs: &[&str]) -> Vec<(usize, String, String)> {
    let mut blocks = Vec::new();
    let mut open: Option<(usize, String, String)> = None;
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        match open.take() {
            None => {
                if let Some(info) = trimmed.strip_prefix("```") {
                    open = Some((i + 1, info.trim().to_string(), String::new()));
                }
            }
            Some((start, lang, mut code)) => {
                if trimmed.starts_with("```") {
                    if langs.contains(&lang.as_str()) {
                        blocks.push((start, lang, code));
                    }
                } else {
                    code.push_str(line);
                    code.push('\n');
                    open = Some((start, lang, code));
                }
            }
        }
    }
    assert!(open.is_none(), "an unclosed code block");
    blocks
}

#[test]
fn the_block_reader_finds_blocks_and_their_languages() {
    let text = "a\n```c\nint x;\n```\n```sh\nls\n```\n  ```cpp\nint y;\n  ```\n";
    let blocks = code_blocks(text, &["c", "cpp"]);
    assert_eq!(
        blocks,
        vec![
            (2, "c".to_string(), "int x;\n".to_string()),
            (8, "cpp".to_string(), "int y;\n".to_string()),
        ]
    );
}

#[test]
fn readme_c_and_cpp_blocks_compile_and_run() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README.md");
    let blocks = code_blocks(&readme, &["c", "cpp"]);
    let langs: Vec<&str> = blocks.iter().map(|b| b.1.as_str()).collect();
    assert!(
        langs.contains(&"c") && langs.contains(&"cpp"),
        "README.md should show C and C++: {langs:?}"
    );
    // Run outside the repository: examples must not depend on the working directory.
    let elsewhere = std::env::temp_dir();
    for (line, lang, code) in blocks {
        let (ext, std) = if lang == "c" {
            ("c", "c99")
        } else {
            ("cpp", "c++98")
        };
        let name = format!("readme_line{line}");
        let source = scratch("readme").join(format!("{name}.{ext}"));
        std::fs::write(&source, code).expect("write the block");
        let exe = build_program(&source, std, &name);
        let mut cmd = Command::new(&exe);
        cmd.current_dir(&elsewhere);
        let out = run(cmd, &format!("README.md line {line}"));
        assert!(
            out.stderr.is_empty(),
            "README.md line {line} wrote to stderr: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
