//! What a run would cost, refused by `check` before it starts (issue 31
//! item 3): a step that takes at least `⌈length / max_increment⌉` more
//! increments than `[[step]] max_increments` (default 10⁵), or a run that
//! would keep more VTU bytes than `[output] max_bytes` (default 100 GiB),
//! with the numbers and the key that raises the limit.

use std::path::Path;
use std::process::Command;

/// `signorini check` on examples/press-pull with its text changed by
/// `edit`: the exit code and stderr.
fn check(edit: impl Fn(String) -> String) -> (i32, String) {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/press-pull");
    let text = std::fs::read_to_string(example.join("case.toml"))
        .unwrap()
        .replacen(
            "file = \"block.msh\"",
            &format!("file = {:?}", example.join("block.msh")),
            1,
        );
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), edit(text)).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(["check", "case.toml"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "{stderr}");
    (out.status.code().unwrap_or(-1), stderr)
}

/// The pull step (length 1) with increments of at most 1e-7.
fn tiny_pull(text: String) -> String {
    text.replacen(
        "initial_increment = 0.25",
        "initial_increment = 1e-7\nmax_increment = 1e-7",
        1,
    )
}

#[track_caller]
fn refused(result: (i32, String), keywords: &[&str]) {
    let (code, stderr) = result;
    assert_eq!(code, 1, "{stderr}");
    for k in keywords {
        assert!(stderr.contains(k), "'{k}' is not in:\n{stderr}");
    }
}

#[test]
fn a_step_of_too_many_increments_is_refused_until_the_limits_are_raised() {
    // 1 / 1e-7 = 10⁷ increments: more than 10⁵
    refused(
        check(tiny_pull),
        &[
            "step[1].max_increment = 1e-7",
            "at least 10000000 increments",
            "100000 allowed",
            "max_increments = 10000000",
        ],
    );
    // raised: then 10⁷ VTU files of the block are more than 100 GiB
    let raised = |t: String| {
        tiny_pull(t).replacen(
            "max_increment = 1e-7",
            "max_increment = 1e-7\nmax_increments = 10000000",
            1,
        )
    };
    refused(
        check(raised),
        &[
            "step[1]",
            "10000001 increments so far",
            "[output] every",
            "max_bytes =",
        ],
    );
    // a VTU file every 10⁶ increments: 12 files, within the limit
    let (code, stderr) =
        check(|t| raised(t).replacen("[output]\n", "[output]\nevery = 1000000\n", 1));
    assert_eq!(code, 0, "{stderr}");
}

#[test]
fn the_examples_steps_are_within_the_limits() {
    let (code, stderr) = check(|t| t);
    assert_eq!(code, 0, "{stderr}");
}
