//! The command line's own commands and lines (issue 30): the shell
//! completion scripts and the man page name every subcommand and flag of
//! the clap definition, bash's script completes them when bash runs it,
//! and the run's last line and model line say what is true ("1 increment",
//! no contact multipliers where there is no contact).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The subcommands and, per subcommand, its long flags, as the README's
/// "Command line" lists them.
const SUBCOMMANDS: [(&str, &[&str]); 5] = [
    ("run", &["--output", "--threads", "--quiet", "--restart"]),
    ("check", &[]),
    ("convert", &["--output", "--force"]),
    ("completions", &[]),
    ("man", &[]),
];

fn signorini(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn stdout(output: &Output) -> String {
    assert!(
        output.status.success(),
        "exit {:?}: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout.clone()).unwrap()
}

fn here() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn every_shell_script_names_every_subcommand_and_flag() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let script = stdout(&signorini(&["completions", shell], &here()));
        for (sub, flags) in SUBCOMMANDS {
            assert!(script.contains(sub), "{shell}: no subcommand {sub}");
            for flag in flags {
                // fish names long flags without the dashes (`-l threads`)
                let bare = flag.trim_start_matches('-');
                assert!(script.contains(bare), "{shell}: no {flag} of {sub}");
            }
        }
    }
}

/// What bash's completion function offers for the words typed so far.
fn bash_completes(script: &Path, words: &[&str]) -> Vec<String> {
    let line = words.join(" ");
    let quoted: Vec<String> = words.iter().map(|w| format!("'{w}'")).collect();
    let program = format!(
        "source '{}'; COMP_WORDS=({}); COMP_CWORD={}; COMP_LINE='{line}'; COMP_POINT={}; \
         _signorini signorini '{}' '{}'; printf '%s\\n' \"${{COMPREPLY[@]}}\"",
        script.display(),
        quoted.join(" "),
        words.len() - 1,
        line.len(),
        words[words.len() - 1],
        words[words.len().saturating_sub(2)],
    );
    let output = Command::new("bash")
        .args(["--norc", "--noprofile", "-c", &program])
        .output()
        .expect("bash");
    stdout(&output).lines().map(str::to_string).collect()
}

#[test]
fn bash_completes_the_subcommands_and_the_flags_of_run() {
    if Command::new("bash").arg("--version").output().is_err() {
        eprintln!("skipped: no bash");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("signorini.bash");
    std::fs::write(
        &script,
        stdout(&signorini(&["completions", "bash"], &here())),
    )
    .unwrap();
    let subs = bash_completes(&script, &["signorini", ""]);
    for (sub, _) in SUBCOMMANDS {
        assert!(subs.iter().any(|s| s == sub), "no {sub} in {subs:?}");
    }
    assert_eq!(
        bash_completes(&script, &["signorini", "co"]),
        ["convert", "completions"]
    );
    let flags = bash_completes(&script, &["signorini", "run", "--"]);
    for flag in SUBCOMMANDS[0].1 {
        assert!(flags.iter().any(|f| f == flag), "no {flag} in {flags:?}");
    }
    assert!(
        !flags.iter().any(|f| f == "--force"),
        "--force is convert's: {flags:?}"
    );
}

#[test]
fn the_man_pages_name_the_subcommands_and_flags() {
    let page = stdout(&signorini(&["man"], &here()));
    assert!(
        page.starts_with(".ie") || page.contains(".TH signorini 1"),
        "{page}"
    );
    for (sub, _) in SUBCOMMANDS {
        assert!(page.contains(sub), "signorini(1): no {sub}");
    }
    let run = stdout(&signorini(&["man", "run"], &here()));
    assert!(run.contains(".TH signorini-run 1"), "{run}");
    let version = format!("\"signorini {}", env!("CARGO_PKG_VERSION"));
    assert!(
        run.lines()
            .any(|l| l.starts_with(".TH") && l.contains(&version)),
        "{run}"
    );
    for flag in SUBCOMMANDS[0].1 {
        // roff escapes the dashes: \-\-threads
        let escaped = flag.replace('-', "\\-");
        assert!(run.contains(&escaped), "signorini-run(1): no {flag}");
    }
    let wrong = signorini(&["man", "rnu"], &here());
    assert_eq!(wrong.status.code(), Some(2));
    let message = String::from_utf8_lossy(&wrong.stderr);
    assert!(
        message.contains("'rnu'") && message.contains("run, check, convert"),
        "{message}"
    );
}

/// A folder with `case.toml` = `text` beside the 27-hexahedron cube
/// (`tests/data/cube_hex_41_ascii.msh`: regions body, surfaces bottom,
/// top, contact).
fn cube_case(text: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), text).unwrap();
    let mesh = here().join("tests/data/cube_hex_41_ascii.msh");
    std::fs::copy(mesh, dir.path().join("cube.msh")).unwrap();
    dir
}

/// The cube held at its bottom, pressed on top, no contact, one step in
/// one increment (`initial_increment` defaults to the whole step).
const NO_CONTACT: &str = r#"
[mesh]
file = "cube.msh"
[[material]]
region = "body"
model = "linear_elastic"
youngs_modulus = 100.0
poisson_ratio = 0.3
[[displacement]]
surface = "bottom"
x = 0.0
y = 0.0
z = 0.0
[[pressure]]
surface = "top"
value = 1.0
[[step]]
name = "load"
end_time = 1.0
"#;

#[test]
fn one_increment_is_said_in_the_singular_and_no_multipliers_without_contact() {
    let dir = cube_case(NO_CONTACT);
    let output = signorini(&["run", "case.toml", "--threads", "1"], dir.path());
    let out = stdout(&output);
    // the model in words goes to the standard error, the last line to the output
    let err = String::from_utf8_lossy(&output.stderr);
    let model = err.lines().find(|l| l.starts_with("model:")).expect(&err);
    // 64 nodes × 3 dofs, the 16 bottom nodes' 48 prescribed
    assert!(model.contains("192 dofs (48 prescribed)"), "{model}");
    assert!(!model.contains("multipliers"), "{model}");
    let done = out.lines().find(|l| l.starts_with("done:")).expect(&out);
    assert!(done.starts_with("done: 1 increment, "), "{done}");
}

#[test]
fn contact_multipliers_are_counted_where_there_are_some() {
    // the bad-input catalogue's valid case: rockafellar contact (the
    // default method) on the face `contact`
    let dir = cube_case(include_str!("data/cube_case.toml"));
    let out = stdout(&signorini(&["check", "case.toml"], dir.path()));
    let line = |l: &&str| l.trim_start().starts_with("model:");
    let model = out.lines().find(line).expect(&out);
    // 192 dofs and a multiplier at each of the 16 nodes of `contact`
    assert!(
        model.contains("208 unknowns with the contact multipliers"),
        "{model}"
    );
}
