//! The C ABI as C and C++ programs see it: builds the programs of c_api_tests/ with the system
//! compiler against the library cargo built for these tests, runs them, and requires them to pass
//! without printing anything to stderr (the library never prints). The same programs also run
//! under AddressSanitizer and UBSan in the CMake build (ctest).

mod c_toolchain;

use c_toolchain::{build_program, build_program_with, build_static_program, root, run_program};

fn c_program(name: &str) {
    let exe = build_program(&root().join(format!("c_api_tests/{name}.c")), "c99", name);
    let out = run_program(&exe);
    assert!(out.contains("all checks passed"), "{name}: {out}");
}

#[test]
fn error_paths_return_their_documented_codes() {
    c_program("errors");
}

#[test]
fn answers_on_known_geometry() {
    c_program("answers");
}

#[test]
fn create_destroy_loops_and_result_lifetimes() {
    c_program("lifecycle");
}

#[test]
fn convex_polyhedra_error_paths_and_answers() {
    c_program("convex");
}

#[test]
fn ray_casting() {
    c_program("ray");
}

/// The ray casting example builds warning-free and renders the bunny.
#[test]
fn ray_cast_example_runs() {
    let exe = build_program(&root().join("examples/ray_cast.c"), "c99", "ray_cast.c");
    let mut cmd = std::process::Command::new(&exe);
    cmd.arg(root().join("examples/models/bunny.tris"));
    let out = c_toolchain::run(cmd, "ray_cast.c");
    assert!(String::from_utf8_lossy(&out.stdout).contains('#'));
}

#[test]
fn threads_share_models() {
    c_program("threads");
}

#[test]
fn refit_and_self_collision_from_c() {
    c_program("motion");
}

#[test]
fn point_queries_from_c() {
    c_program("point");
}

#[test]
fn primitives_from_c() {
    c_program("primitives");
}

#[test]
fn batch_queries_from_c() {
    c_program("batch");
}

#[test]
fn saved_models_from_c() {
    c_program("saved");
}

#[test]
fn pqp_view_of_a_model_from_c() {
    c_program("legacy_view");
}

/// PQP 1.3 code through PQP.h compiles warning-free and answers correctly in every C++ standard.
#[test]
fn legacy_cxx_program_in_every_standard() {
    for std in ["c++98", "c++11", "c++14", "c++17", "c++20"] {
        let name = format!("legacy_boxes_{}", std.replace('+', "x"));
        let exe = build_program(&root().join("c_api_tests/legacy_boxes.cpp"), std, &name);
        let out = run_program(&exe);
        assert!(out.contains("all checks passed"), "{name}: {out}");
    }
}

/// PQP.h beyond PQP 1.3: codes for bad arguments, moves, containers, the C handles.
#[test]
fn pqp_h_extensions() {
    let exe = build_program(
        &root().join("c_api_tests/pqp_h_extras.cpp"),
        "c++11",
        "pqp_h_extras",
    );
    let out = run_program(&exe);
    assert!(out.contains("all checks passed"), "{out}");
}

/// PQP 1.3 programs, one per pattern real PQP code uses (scope-qualified names, result members, model
/// internals, copies, build codes, float PQP_REAL, every public member), each in the C++ standards
/// `c_api_tests/pqp13/programs.txt` lists for it.
#[test]
fn pqp13_programs_in_their_standards() {
    let dir = root().join("c_api_tests/pqp13");
    let manifest = std::fs::read_to_string(dir.join("programs.txt")).expect("programs.txt");
    let mut built = 0;
    for line in manifest
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let mut words = line.split_whitespace();
        let name = words.next().expect("a program name");
        let (stds, flags): (Vec<&str>, Vec<&str>) = words.partition(|w| !w.starts_with('-'));
        let mut extra: Vec<String> = flags.iter().map(|f| f.to_string()).collect();
        extra.push(format!("-I{}", root().join("c_tests/harness").display()));
        for std in stds {
            let out = format!("pqp13_{name}_cxx{std}");
            let exe = build_program_with(
                &dir.join(format!("{name}.cpp")),
                &format!("c++{std}"),
                &out,
                &extra,
            );
            let stdout = run_program(&exe);
            assert!(stdout.contains("all checks passed"), "{out}: {stdout}");
            built += 1;
        }
    }
    assert!(built >= 7, "programs.txt lists {built} builds");
}

/// PQP 1.3's MatVec.h and TriDist.h: every MatVec.h helper against reference arithmetic, TriDist
/// and SegPoints against a long double reference on thousands of random pairs, with PQP_REAL
/// double (as C++98 and C++17) and float (matvec_tridist_float.cpp).
#[test]
fn matvec_and_tridist_headers() {
    for (source, std) in [
        ("matvec_tridist.cpp", "c++98"),
        ("matvec_tridist.cpp", "c++17"),
        ("matvec_tridist_float.cpp", "c++11"),
    ] {
        let name = format!(
            "{}_{}",
            source.trim_end_matches(".cpp"),
            std.replace('+', "x")
        );
        let exe = build_program(&root().join("c_api_tests").join(source), std, &name);
        let out = run_program(&exe);
        assert!(out.contains("all checks passed"), "{name}: {out}");
    }
}

/// The static library links with exactly the system libraries pqp.pc lists as private.
#[test]
fn static_library_links_with_the_documented_libraries() {
    let exe = build_static_program(&root().join("c_api_tests/errors.c"), "errors_static");
    let out = run_program(&exe);
    assert!(out.contains("all checks passed"), "{out}");
}

/// The demos build warning-free and run on the example models.
#[test]
fn demos_run() {
    let models = root().join("examples/models");
    for (src, std) in [("demo_c.c", "c99"), ("demo_legacy.cpp", "c++11")] {
        let exe = build_program(&root().join("examples").join(src), std, src);
        let mut cmd = std::process::Command::new(&exe);
        cmd.arg(models.join("bunny.tris"))
            .arg(models.join("torus.tris"));
        let out = c_toolchain::run(cmd, src);
        assert!(!out.stdout.is_empty());
    }
    // The point-query example, on its own cube and on the bunny.
    let exe = build_program(
        &root().join("examples/closest_point.c"),
        "c99",
        "closest_point",
    );
    for args in [vec![], vec![models.join("bunny.tris")]] {
        let mut cmd = std::process::Command::new(&exe);
        cmd.args(&args);
        let out = c_toolchain::run(cmd, "closest_point");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("signed distance"), "{text}");
    }
}

/// The primitives example builds warning-free and runs.
#[test]
fn primitives_example_runs() {
    let exe = build_program(&root().join("examples/primitives.c"), "c99", "primitives.c");
    let out = c_toolchain::run(std::process::Command::new(&exe), "primitives.c");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("capsule r 0.05") && text.contains("not a triangle mesh"),
        "{text}"
    );
}

#[test]
fn time_of_contact_from_c() {
    c_program("contact_time");
}
