//! The crate's declared minimum Rust (`rust-version` in Cargo.toml) is true: no locked dependency
//! needs a newer one, and it is at least what the crate's edition needs. Only one toolchain is
//! installed where the tests run, so this reads the requirements instead of building with the
//! oldest compiler.

use serde_json::Value;
use std::process::Command;

/// The first release of Rust that accepts each edition.
const EDITION_MINIMUM: &[(&str, (u64, u64, u64))] = &[
    ("2015", (1, 0, 0)),
    ("2018", (1, 31, 0)),
    ("2021", (1, 56, 0)),
    ("2024", (1, 85, 0)),
];

/// `cargo metadata` for this package and its locked dependencies, without touching the network
/// when the packages are already downloaded, and without changing the lock file.
fn metadata() -> Value {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let run = |extra: &[&str]| {
        Command::new(&cargo)
            .args(["metadata", "--format-version", "1", "--locked"])
            .args(extra)
            .arg("--manifest-path")
            .arg(concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml"))
            .output()
            .expect("cargo runs")
    };
    // Offline first; the packages of other platforms may not be downloaded yet on a fresh machine.
    let mut out = run(&["--offline"]);
    if !out.status.success() {
        out = run(&[]);
    }
    assert!(
        out.status.success(),
        "cargo metadata failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("cargo metadata prints JSON")
}

/// "1.89" or "1.89.0" as (1, 89, 0).
fn version(s: &str) -> (u64, u64, u64) {
    let mut parts = s
        .split('.')
        .map(|p| p.parse::<u64>().expect("a numeric version"));
    let major = parts.next().expect("a major version");
    (major, parts.next().unwrap_or(0), parts.next().unwrap_or(0))
}

#[test]
fn declared_rust_version_covers_the_dependencies_and_the_edition() {
    let meta = metadata();
    let packages = meta["packages"].as_array().expect("a package list");
    let ours = packages
        .iter()
        .find(|p| p["name"] == env!("CARGO_PKG_NAME"))
        .expect("this package is listed");
    let declared = ours["rust_version"]
        .as_str()
        .expect("Cargo.toml declares rust-version");
    let declared_v = version(declared);

    let edition = ours["edition"].as_str().expect("an edition");
    let (_, needed) = EDITION_MINIMUM
        .iter()
        .find(|(e, _)| *e == edition)
        .expect("a known edition");
    assert!(
        declared_v >= *needed,
        "rust-version {declared} is older than edition {edition} allows ({needed:?})"
    );

    let too_new: Vec<String> = packages
        .iter()
        .filter(|p| p["name"] != env!("CARGO_PKG_NAME"))
        .filter_map(|p| {
            let (name, at) = (p["name"].as_str()?, p["version"].as_str()?);
            let v = p["rust_version"].as_str()?;
            (version(v) > declared_v).then(|| format!("{name} {at} needs {v}"))
        })
        .collect();
    assert!(
        too_new.is_empty(),
        "rust-version {declared} in Cargo.toml is older than locked dependencies need: {}",
        too_new.join(", ")
    );
}

#[test]
fn versions_parse() {
    assert_eq!(version("1.89"), (1, 89, 0));
    assert_eq!(version("1.85.1"), (1, 85, 1));
    assert!(version("1.89.0") > version("1.85"));
}
