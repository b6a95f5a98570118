//! What a run's results came from: the build (version, commit, features,
//! set by `build.rs`), the case file's SHA-256, the date, the command line
//! and the cores, written at the top of `NAME.log` ([`RunHeader`]) and
//! printed by `signorini --version` ([`VERSION_LINE`]).

use std::path::Path;

use sha2::{Digest, Sha256};

/// The crate's version, e.g. `0.1.0`.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The git commit the binary was built from (12 hex digits), `unknown`
/// when it was built outside a git checkout.
pub const COMMIT: &str = env!("SIGNORINI_COMMIT");

/// The enabled cargo features, comma-separated (`petsc`), or `none`.
pub const FEATURES: &str = env!("SIGNORINI_FEATURES");

/// `0.1.0 (commit 0123456789ab, features: none)`: what `signorini
/// --version` prints after the program's name.
pub const VERSION_LINE: &str = concat!(
    env!("CARGO_PKG_VERSION"),
    " (commit ",
    env!("SIGNORINI_COMMIT"),
    ", features: ",
    env!("SIGNORINI_FEATURES"),
    ")"
);

/// The SHA-256 of `bytes` (FIPS 180-4) in lower-case hex, as `sha256sum`
/// prints it.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// The lines at the top of `NAME.log` that identify a run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunHeader {
    /// The case file, as the run names it.
    pub case: String,
    /// [`sha256_hex`] of the case file's bytes (of the text given, for a
    /// case built in code).
    pub case_sha256: String,
    /// The start in UTC, RFC 3339 (`2026-11-27T10:04:05Z`).
    pub date: String,
    /// The program's arguments, quoted where they hold a space.
    pub command_line: String,
    /// Worker threads of the run, and the cores available to the process.
    pub threads: usize,
    pub cores: usize,
}

impl RunHeader {
    /// The header of a run of `case` (its SHA-256 `case_sha256`) starting
    /// now in this process with `threads` worker threads.
    pub fn now(case: &Path, case_sha256: String, threads: usize) -> Self {
        RunHeader {
            case: case.display().to_string(),
            case_sha256,
            date: humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
            command_line: command_line(std::env::args_os().map(|a| a.to_string_lossy().into())),
            threads,
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
        }
    }

    /// The header's lines: `signorini VERSION (commit …, features: …)`,
    /// then `key: value` lines.
    pub fn lines(&self) -> Vec<String> {
        vec![
            format!("signorini {VERSION_LINE}"),
            format!("date (UTC): {}", self.date),
            format!("command line: {}", self.command_line),
            format!(
                "cores: {} worker threads ({} cores available)",
                self.threads, self.cores
            ),
            format!("case: {}", self.case),
            format!("case sha256: {}", self.case_sha256),
        ]
    }
}

/// `args` joined by spaces, an argument that is empty or holds a space,
/// a quote or a control character written as a quoted string.
fn command_line(args: impl Iterator<Item = String>) -> String {
    args.map(|a| {
        if a.is_empty()
            || a.chars()
                .any(|c| c.is_whitespace() || c.is_control() || "'\"".contains(c))
        {
            format!("{a:?}")
        } else {
            a
        }
    })
    .collect::<Vec<_>>()
    .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The test vectors of FIPS 180-2, appendix B.1 and B.2.
    #[test]
    fn sha256_matches_the_standard_vectors() {
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        assert_eq!(
            sha256_hex(b"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"
        );
    }

    #[test]
    fn header_lines_and_quoting() {
        let header = RunHeader {
            case: "examples/hertz/case.toml".into(),
            case_sha256: "ab".repeat(32),
            date: "2026-11-27T10:00:00Z".into(),
            command_line: command_line(
                ["signorini", "run", "my case.toml", ""]
                    .into_iter()
                    .map(String::from),
            ),
            threads: 2,
            cores: 4,
        };
        let lines = header.lines();
        assert_eq!(
            lines[0],
            format!("signorini {VERSION} (commit {COMMIT}, features: {FEATURES})")
        );
        assert_eq!(lines[2], r#"command line: signorini run "my case.toml" """#);
        assert_eq!(lines[3], "cores: 2 worker threads (4 cores available)");
        assert_eq!(lines[5], format!("case sha256: {}", "ab".repeat(32)));
    }

    #[test]
    fn the_date_is_utc_rfc3339() {
        let date = RunHeader::now(Path::new("c.toml"), String::new(), 1).date;
        // 2026-11-27T10:00:00Z
        assert_eq!(date.len(), 20, "{date}");
        assert!(date.ends_with('Z') && date.as_bytes()[10] == b'T', "{date}");
    }
}
