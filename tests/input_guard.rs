//! The one input guard (issue 31 item 1), beside the bad-input catalogue
//! (`tests/bad_inputs.rs`): every file a `.inp` deck reads, its own and
//! each `*INCLUDE`, goes through `signorini::input` — a regular file (a
//! FIFO would block, `/dev/zero` never ends), text (not binary data),
//! within the size limit — its `GENERATE` lines are counted over the whole
//! deck rather than per line, and its coordinates are finite and within
//! ±1e100 as the Gmsh reader's are. Each input is run through `signorini
//! check` as a user meets it: exit code 1, the key words of the message,
//! no panic.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The 27-hexahedron cube as an Abaqus deck, with the case that runs on it.
const DECK: &str = include_str!("data/cube_hex.inp");
const CASE: &str = include_str!("data/cube_case.toml");

/// The case file of `tests/data/cube_case.toml` on `cube.inp`.
fn case_on_deck() -> String {
    CASE.replacen("file = \"cube.msh\"", "file = \"cube.inp\"", 1)
}

/// Runs `signorini check case.toml` in `dir`, killed after `limit` (a hang
/// guard: a FIFO that blocks must fail the test, not hang it); returns the
/// exit code and stderr.
fn check(dir: &Path, limit: Duration) -> (i32, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_signorini"))
        .args(["check", "case.toml"])
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > limit {
            child.kill().unwrap();
            child.wait().unwrap();
            panic!("signorini check did not end within {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "{stderr}");
    (out.status.code().unwrap_or(-1), stderr)
}

/// A folder with the case and the deck `deck`; `extra` files beside them.
fn folder(deck: &str, extra: &[(&str, &[u8])]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), case_on_deck()).unwrap();
    std::fs::write(dir.path().join("cube.inp"), deck).unwrap();
    for (name, bytes) in extra {
        std::fs::write(dir.path().join(name), bytes).unwrap();
    }
    dir
}

/// `check` refuses the folder with exit code 1 and every key word.
#[track_caller]
fn refused(dir: &Path, keywords: &[&str]) -> String {
    let (code, stderr) = check(dir, Duration::from_secs(60));
    assert_eq!(code, 1, "{stderr}");
    for k in keywords {
        assert!(stderr.contains(k), "'{k}' is not in:\n{stderr}");
    }
    stderr
}

/// The deck with `*INCLUDE, INPUT=name` in place of its `*Heading`.
fn including(name: &str) -> String {
    DECK.replacen("*Heading", &format!("*INCLUDE, INPUT={name}"), 1)
}

#[test]
fn the_deck_case_is_valid() {
    let dir = folder(DECK, &[]);
    let (code, stderr) = check(dir.path(), Duration::from_secs(60));
    assert_eq!(code, 0, "{stderr}");
}

/// Node 1 (0, 0, 1) is a node of the contact surface `contact` (x = 0,
/// against the wall at x = −0.01); at ±1e200 its tributary area overflows
/// (this panicked `check` and `run` in the contact set-up before the bound
/// was read from `.inp` decks too).
#[test]
fn a_contact_node_beyond_the_coordinate_bound_is_refused_where_it_is_read() {
    for x in ["-1e200", "1e200", "1d200", "nan", "inf"] {
        let deck = DECK.replacen("\n1, 0, 0, 1\n", &format!("\n1, {x}, 0, 1\n"), 1);
        assert_ne!(deck, DECK);
        let dir = folder(&deck, &[]);
        // the message names the file, its line (the 4th) and the node
        let keywords: &[&str] = if x.ends_with("200") {
            &[
                "cube.inp",
                "line 4",
                "x coordinate of node 1",
                "±1e100",
                "length unit",
            ]
        } else {
            &["cube.inp", "line 4", "expected a number"]
        };
        refused(dir.path(), keywords);
    }
}

#[cfg(unix)]
#[test]
fn a_fifo_include_is_refused_without_blocking() {
    let dir = folder(&including("pipe.inp"), &[]);
    let fifo = dir.path().join("pipe.inp");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    refused(
        dir.path(),
        &["cube.inp", "line 1", "pipe.inp", "not a regular file"],
    );
}

#[cfg(unix)]
#[test]
fn a_device_include_is_refused_unread() {
    let dir = folder(&including("/dev/zero"), &[]);
    refused(
        dir.path(),
        &["cube.inp", "line 1", "/dev/zero", "not a regular file"],
    );
}

#[test]
fn a_binary_include_is_refused() {
    let mut garbage = b"*NODE\n".to_vec();
    garbage.extend((0..4096u32).map(|i| (i.wrapping_mul(2654435761) >> 24) as u8));
    let dir = folder(&including("nodes.bin"), &[("nodes.bin", &garbage)]);
    refused(
        dir.path(),
        &["cube.inp", "line 1", "nodes.bin", "binary data, not text"],
    );
}

/// 1 000 lines of 10⁸ ids each (a 19 KB deck): each line alone is within
/// the limit of 10⁸, together they list 10¹¹; the count over the deck
/// refuses the second line before listing it, so `check` ends at once (it
/// took minutes when the limit was per line). The 10 s is a hang guard, not
/// a timing.
#[test]
fn generate_lines_are_counted_over_the_deck_not_per_line() {
    let lines: String = (0..1000).map(|_| "1, 100000000\n").collect();
    let deck = format!("{DECK}*NSET, NSET=HUGE, GENERATE\n{lines}");
    let dir = folder(&deck, &[]);
    let (code, stderr) = check(dir.path(), Duration::from_secs(10));
    assert_eq!(code, 1, "{stderr}");
    // the second GENERATE line (the deck's line 129) is the one refused,
    // with the total, the line's own count, the limit and the key to raise it
    let at = DECK.lines().count() + 3;
    for k in [
        format!("line {at}"),
        "200000000 ids".into(),
        "this one's 100000000".into(),
        "100000000 allowed".into(),
        "[mesh] max_generated_ids".into(),
    ] {
        assert!(stderr.contains(&k), "'{k}' is not in:\n{stderr}");
    }
    // the same lines across includes count together
    let half = "1, 60000000\n";
    let deck = format!("{DECK}*INCLUDE, INPUT=a.inp\n*INCLUDE, INPUT=b.inp\n");
    let set = format!("*NSET, NSET=HUGE, GENERATE\n{half}");
    let dir = folder(
        &deck,
        &[("a.inp", set.as_bytes()), ("b.inp", set.as_bytes())],
    );
    refused(dir.path(), &["b.inp", "line 2", "120000000 ids"]);
}

/// A set named 1 000 times in a set is copied 1 000 times: such copies
/// count with the `GENERATE` ranges, or a few lines (`S2` = 1 000 × `S1`
/// = 10⁶ × `S0`, …) would ask for 1 000ⁿ ids. With the limit set to
/// 100 000: S0 (64 ids) and S1 (64 000) pass, the second `S1` named in `S2`
/// crosses it.
#[test]
fn sets_named_in_sets_count_with_the_generated_ids() {
    let names = |set: &str| vec![set; 1000].join(", ");
    let deck = format!(
        "{DECK}*NSET, NSET=S0, GENERATE\n1, 64\n*NSET, NSET=S1\n{}\n*NSET, NSET=S2\n{}\n",
        names("S0"),
        names("S1")
    );
    let dir = folder(&deck, &[]);
    let case = case_on_deck().replacen(
        "file = \"cube.inp\"",
        "file = \"cube.inp\"\nmax_generated_ids = 100000",
        1,
    );
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let at = DECK.lines().count() + 6;
    refused(
        dir.path(),
        &[
            &format!("line {at}"),
            "128064 ids with this one's 64000",
            "100000 allowed",
            "sets named in other sets",
        ],
    );
}

#[test]
fn the_generate_limit_is_raised_by_a_case_key() {
    // 2 lines of 10⁸: refused by default, read with the limit raised
    let deck = format!("{DECK}*NSET, NSET=ALL, GENERATE\n1, 100000000, 1\n1, 10, 1\n");
    let dir = folder(&deck, &[]);
    refused(dir.path(), &["100000010 ids", "max_generated_ids"]);
    let case = case_on_deck().replacen(
        "file = \"cube.inp\"",
        "file = \"cube.inp\"\nmax_generated_ids = 100000010",
        1,
    );
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let (code, stderr) = check(dir.path(), Duration::from_secs(120));
    assert_eq!(code, 0, "{stderr}");
}

/// The contact set-up returns an error, not a panic, when a surface's
/// element size is not a positive finite length: a mesh given as arrays
/// (no file, no reader's bound) with nodes at x = 1e200 and y = 1e200,
/// whose triangle's area (1e400/2) overflows.
#[test]
fn the_contact_set_up_refuses_degenerate_geometry() {
    use signorini::contact::interface::ContactInterface;
    use signorini::contact::laws::NormalLaw;
    use signorini::contact::setup::{Enforcement, Method, SetupError};
    use signorini::contact::RigidObstacle;
    use signorini::mesh::{ElementKind, Mesh};
    let mut nodes = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    nodes[1][0] = 1e200;
    nodes[2][1] = 1e200;
    let mesh = Mesh::from_arrays(
        nodes,
        vec![(ElementKind::Tet4, vec![0, 1, 2, 3])],
        Vec::new(),
        vec![("bottom".into(), vec![vec![0, 1, 2]])],
    )
    .unwrap();
    let enforcement = Enforcement {
        youngs_modulus: 100.0,
        ..Enforcement::from(NormalLaw::Penalty { epsilon: 1.0 })
    };
    let enforcement = Enforcement {
        method: Method::Rockafellar,
        penalty: None,
        scaling: None,
        ..enforcement
    };
    let plane = RigidObstacle::plane([0.0, 0.0, -0.1].into(), [0.0, 0.0, 1.0].into()).unwrap();
    match ContactInterface::rigid(&mesh, "bottom", plane, &enforcement) {
        Err(SetupError::Degenerate {
            surface,
            element_size,
        }) => {
            assert_eq!(surface, "bottom");
            assert!(!element_size.is_finite(), "{element_size}");
        }
        Err(e) => panic!("another error: {e:?}"),
        Ok(_) => panic!("a contact interface with an infinite element size"),
    }
}
