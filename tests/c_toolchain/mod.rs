//! Compiling and running C and C++ programs from the tests (tests/c_api.rs, tests/header.rs), with
//! the system compiler found by the cc crate, against the library cargo built for these tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

/// Warnings every C and C++ program of the project builds clean with.
pub const WARNINGS: &[&str] = &["-Wall", "-Wextra", "-pedantic", "-Werror"];

/// The repository root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A scratch directory for one test's outputs (inside cargo's target directory).
pub fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("c_programs")
        .join(name);
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

/// The C (or C++) compiler, as a command with cc's default flags for this target.
pub fn compiler(cpp: bool) -> Command {
    let target = env!("PQP_TEST_TARGET");
    cc::Build::new()
        .cpp(cpp)
        .target(target)
        .host(target)
        .opt_level(1)
        .debug(false)
        .cargo_metadata(false)
        .cargo_warnings(false)
        .get_compiler()
        .to_command()
}

/// Runs a command, failing the test with its output if it fails.
pub fn run(mut cmd: Command, what: &str) -> Output {
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot run {cmd:?}: {e}"));
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{cmd:?}\n--- stdout\n{}\n--- stderr\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// The directory holding the libpqp.so and libpqp.a cargo built for this test run: the test
/// executable's own directory (target/<profile>/deps). Cargo builds every crate type of the library
/// there; the copies in target/<profile> are only refreshed by `cargo build`.
fn cargo_lib_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    let dir = exe.parent().expect("target directory").to_path_buf();
    for lib in ["libpqp.so", "libpqp.a"] {
        assert!(
            dir.join(lib).exists(),
            "{} not found: cargo builds it with the tests (crate-type cdylib, staticlib)",
            dir.join(lib).display()
        );
    }
    dir
}

/// A directory to link and run against: libpqp.so.1 (the soname programs look for) and libpqp.so
/// lead to cargo's libpqp.so; libpqp.a is cargo's static library.
pub fn lib_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let cargo = cargo_lib_dir();
        let dir = scratch("lib");
        for (name, target) in [
            ("libpqp.so.1", "libpqp.so"),
            ("libpqp.so", "libpqp.so"),
            ("libpqp.a", "libpqp.a"),
        ] {
            let link = dir.join(name);
            let _ = std::fs::remove_file(&link);
            std::os::unix::fs::symlink(cargo.join(target), &link).expect("symlink to the library");
        }
        dir
    })
}

/// The repository's include directory.
pub fn include_dir() -> PathBuf {
    root().join("include")
}

/// Compiles `source` (C if it ends in .c, else C++) with `std` and the project's warnings into an
/// executable linked with the shared library, and returns its path.
pub fn build_program(source: &Path, std: &str, out_name: &str) -> PathBuf {
    build_program_with(source, std, out_name, &[])
}

/// [`build_program`] with extra compiler arguments (include directories, definitions).
pub fn build_program_with(source: &Path, std: &str, out_name: &str, extra: &[String]) -> PathBuf {
    let cpp = !matches!(source.extension().and_then(|e| e.to_str()), Some("c"));
    let out = scratch("bin").join(out_name);
    let lib = lib_dir();
    let mut cmd = compiler(cpp);
    cmd.arg(format!("-std={std}"))
        .args(WARNINGS)
        .args(extra)
        .arg("-I")
        .arg(include_dir())
        .arg(source)
        .arg("-o")
        .arg(&out)
        .arg(format!("-L{}", lib.display()))
        .arg(format!("-Wl,-rpath,{}", lib.display()))
        .arg("-lpqp")
        .arg("-pthread")
        .arg("-lm");
    run(cmd, &format!("compiling {}", source.display()));
    out
}

/// Compiles `source` (C) statically against libpqp.a plus the libraries pqp.pc names as private.
pub fn build_static_program(source: &Path, out_name: &str) -> PathBuf {
    let out = scratch("bin").join(out_name);
    let mut cmd = compiler(false);
    cmd.arg("-std=c99")
        .args(WARNINGS)
        .arg("-I")
        .arg(include_dir())
        .arg(source)
        .arg("-o")
        .arg(&out)
        .arg(lib_dir().join("libpqp.a"))
        .args(["-lpthread", "-ldl", "-lm"]);
    run(cmd, &format!("compiling {} statically", source.display()));
    out
}

/// Runs a test program; it must exit 0 and print nothing to stderr.
pub fn run_program(exe: &Path) -> String {
    let out = run(Command::new(exe), &format!("running {}", exe.display()));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.is_empty(),
        "{} wrote to stderr:\n{stderr}",
        exe.display()
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Compiles a translation unit that only includes `header`, as C (`cpp` false) or C++ with `std`.
pub fn compile_header_alone(header: &str, cpp: bool, std: &str) {
    let name = format!(
        "{}_{}",
        header.replace(['/', '.'], "_"),
        std.replace('+', "x")
    );
    let dir = scratch("headers");
    let src = dir.join(if cpp {
        format!("{name}.cpp")
    } else {
        format!("{name}.c")
    });
    std::fs::write(&src, format!("#include <{header}>\n")).expect("write source");
    let mut cmd = compiler(cpp);
    cmd.arg(format!("-std={std}"))
        .args(WARNINGS)
        .arg("-I")
        .arg(include_dir())
        .arg("-c")
        .arg(&src)
        .arg("-o")
        .arg(dir.join(format!("{name}.o")));
    run(cmd, &format!("compiling {header} alone as {std}"));
}
