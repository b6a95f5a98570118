//! What a run came from (issue 30): `NAME.log` starts with the version,
//! commit, features, date, command line, cores and the case file's
//! SHA-256; `signorini --version` names the version, commit and features.

mod common;

use sha2::{Digest, Sha256};
use std::process::Command;

/// The commit `build.rs` finds: git's 12-digit `HEAD` of this checkout,
/// else `unknown`.
fn expected_commit() -> String {
    let root = env!("CARGO_MANIFEST_DIR");
    Command::new("git")
        .args(["rev-parse", "--short=12", "HEAD"])
        .current_dir(root)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map_or("unknown".into(), |o| {
            String::from_utf8_lossy(&o.stdout).trim().to_string()
        })
}

/// The features this test was built with (the binary's).
fn expected_features() -> &'static str {
    if cfg!(feature = "petsc") {
        "petsc"
    } else {
        "none"
    }
}

#[test]
fn version_names_the_version_commit_and_features() {
    let out = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .arg("--version")
        .output()
        .unwrap();
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        format!(
            "signorini {} (commit {}, features: {})\n",
            env!("CARGO_PKG_VERSION"),
            expected_commit(),
            expected_features()
        )
    );
}

/// The cube case run by the command line with 1 thread: its log's header
/// holds the SHA-256 of the case file's bytes (computed here), the
/// command line, the thread count and the build.
#[test]
fn the_log_header_identifies_the_run() {
    let (dir, case) = common::cube_folder(&common::cube_case());
    let out = dir.path().join("results");
    let status = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(["run", "--quiet", "--threads", "1", "--output"])
        .arg(&out)
        .arg(&case)
        .status()
        .unwrap();
    assert!(status.success());
    let log = std::fs::read_to_string(out.join("cube.log")).unwrap();
    let lines: Vec<&str> = log.lines().take(6).collect();
    let sha = Sha256::digest(std::fs::read(&case).unwrap())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect::<String>();
    assert_eq!(
        lines[0],
        format!(
            "signorini {} (commit {}, features: {})",
            env!("CARGO_PKG_VERSION"),
            expected_commit(),
            expected_features()
        )
    );
    assert!(lines[1].starts_with("date (UTC): 20") && lines[1].ends_with('Z'));
    assert!(
        lines[2].starts_with("command line: ")
            && lines[2].ends_with(&format!(
                "run --quiet --threads 1 --output {} {}",
                out.display(),
                case.display()
            )),
        "{}",
        lines[2]
    );
    assert!(
        lines[3].starts_with("cores: 1 worker threads ("),
        "{}",
        lines[3]
    );
    assert_eq!(lines[4], format!("case: {}", case.display()));
    assert_eq!(lines[5], format!("case sha256: {sha}"));
}
