//! A mutation fuzzer on stable Rust (issue 14 item 6) over the Gmsh reader,
//! the STL reader, the case-file parser, `check` (the case validated
//! against a mesh, as `signorini check` does) and `check` of Abaqus decks
//! with an `*INCLUDE` (issue 31 item 1), in process.
//!
//! The corpus is the small meshes and STL files of `tests/data`, the
//! examples' case files and a case on the cube mesh that uses every table.
//! Each execution takes a corpus entry, applies 1 to 8 random mutations
//! (byte flips, insertions, deletions, duplicated or swapped chunks,
//! truncation, and splices of tokens that break readers: `nan`, `-1e155`,
//! `$EndNodes`, `]`, huge counts, …) and runs one target under
//! `catch_unwind`. Any panic is saved to `target/fuzz-crashes/` and fails
//! the run; every crash found becomes an entry of `tests/bad_inputs.rs`.
//!
//! Run for N seconds on T threads (see FUZZING.md for the figures):
//!
//! ```text
//! FUZZ_SECONDS=600 FUZZ_THREADS=2 cargo test --release --test fuzz -- --ignored --nocapture
//! ```
//!
//! The non-ignored test runs a fixed, seeded 3000 executions, so the
//! harness is always built and working.

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use signorini::case::{parse, Case};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// What one execution feeds its input to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Target {
    Msh,
    Stl,
    CaseParse,
    Check,
    /// A mutated mesh read and checked with the cube case (contact
    /// parameters, element geometry, groups).
    MeshCheck,
    /// A mutated Abaqus deck and the file it includes (`*INCLUDE`),
    /// checked as `signorini check` does: the mesh of the cube case, or a
    /// deck run as it is ([`split_deck`]).
    Inp,
}

const TARGETS: [Target; 6] = [
    Target::Msh,
    Target::Stl,
    Target::CaseParse,
    Target::Check,
    Target::MeshCheck,
    Target::Inp,
];

/// Tokens spliced into inputs: values and keywords that readers must reject
/// or survive.
const DICTIONARY: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "-1e155",
    "1e308",
    "1e-320",
    "0",
    "-1",
    "-0",
    "4294967295",
    "18446744073709551615",
    "99999999999999999999",
    "2147483648",
    "\"\"",
    "\"",
    "[",
    "]",
    "[[",
    "]]",
    "=",
    "{",
    "}",
    ".",
    "..",
    "/",
    "\n",
    " ",
    "\t",
    "\0",
    "$Nodes",
    "$EndNodes",
    "$Elements",
    "$EndElements",
    "$PhysicalNames",
    "$EndPhysicalNames",
    "$Entities",
    "$EndEntities",
    "$MeshFormat",
    "$EndMeshFormat",
    "4.1 0 8",
    "2.2 1 8",
    "solid ",
    "facet normal",
    "vertex",
    "endloop",
    "endsolid",
    "[[step]]",
    "[[material]]",
    "[[obstacle]]",
    "[[contact]]",
    "[output]",
    "[[output.profile]]",
    "[[output.history]]",
    "shape = \"sphere\"",
    "model = \"ogden\"",
    "radius = ",
    "two_pass = true",
    "method = \"slack\"",
    "amplitude = ",
    "[1, 2, 3]",
    "[nan, 0, 0]",
    "name = \"../x\"",
    "primary = \"contact\"",
    "*INCLUDE, INPUT=",
    "*INCLUDE, INPUT=nodes.inp",
    "*INCLUDE, INPUT=main.inp",
    "*INCLUDE, INPUT=fifo.inp",
    "*INCLUDE, INPUT=/dev/zero",
    "*INCLUDE, INPUT=cube.msh",
    "*NODE",
    "*NODE, NSET=",
    "*ELEMENT, TYPE=C3D8, ELSET=",
    "*ELEMENT, TYPE=C3D10",
    "*ELEMENT, TYPE=S4",
    "*ELSET, ELSET=",
    "*NSET, NSET=",
    ", GENERATE",
    "1, 100000000, 1",
    "*SURFACE, NAME=",
    ", S7",
    "*PART, NAME=p",
    "*END PART",
    "*INSTANCE, NAME=i, PART=p",
    "*END INSTANCE",
    "*STEP",
    "*END STEP",
    "*CLOAD",
    "*BOUNDARY",
    "-1e200",
    "1e200",
];

/// Between the deck and its included file in a [`Target::Inp`] input:
/// the text before is `main.inp`, the text after `nodes.inp`.
const INCLUDED: &str = "\n** ---- nodes.inp ----\n";

/// The first line of a [`Target::Inp`] deck that is the mesh of the cube
/// case (`inp_case.toml`); any other deck is checked as a deck run as it is.
const CASE_MESH: &str = "** the mesh of inp_case.toml\n";

/// `main.inp` and `nodes.inp` of a [`Target::Inp`] input.
fn split_deck(input: &[u8]) -> (&[u8], &[u8]) {
    let marker = INCLUDED.as_bytes();
    match input.windows(marker.len()).position(|w| w == marker) {
        Some(at) => (&input[..at], &input[at + marker.len()..]),
        None => (input, &[]),
    }
}

/// A case on `cube.msh` using every table (the base case of
/// `tests/bad_inputs.rs`).
const CUBE_CASE: &str = include_str!("data/cube_case.toml");

/// Tables appended to `CUBE_CASE` for a second seed: a moving sphere, an
/// Uzawa interface, friction and a gap history.
const MORE_TABLES: &str = r#"
[[obstacle]]
name = "ball"
shape = "sphere"
center = [0.5, 0.5, 3.0]
radius = 1.0
motion = [0.0, 0.0, -1.0]

[[contact]]
surface = "top"
obstacle = "ball"
method = "uzawa"
friction_coefficient = 0.2

[[output.history]]
name = "gap"
point = [0.0, 0.5, 0.5]
quantity = "gap"
interface = "contact"
"#;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The seed inputs of each target.
struct Corpus {
    msh: Vec<Vec<u8>>,
    stl: Vec<Vec<u8>>,
    cases: Vec<Vec<u8>>,
    /// The valid decks, then the refused ones ([`include_seeds`]).
    decks: Vec<Vec<u8>>,
    valid_decks: usize,
}

/// The seeds of [`Target::Inp`]: `tests/data/cube_hex.inp` with its
/// `*NODE` block moved into the included file (the mesh of the cube case),
/// and `tests/data/inp/block.inp` with its included nodes (a deck with its
/// physics).
fn deck_seeds() -> Vec<Vec<u8>> {
    let data = |n: &str| std::fs::read_to_string(root().join("tests/data").join(n)).unwrap();
    let cube = data("cube_hex.inp");
    let nodes_end = cube.find("******* E L E M E N T S").unwrap();
    let nodes_start = cube.find("*NODE").unwrap();
    let cube = format!(
        "{CASE_MESH}{}*INCLUDE, INPUT=nodes.inp\n{}{INCLUDED}{}",
        &cube[..nodes_start],
        &cube[nodes_end..],
        &cube[nodes_start..nodes_end]
    );
    let block = data("inp/block.inp").replace("INPUT=block_nodes.inp", "INPUT=nodes.inp");
    let block = format!("{block}{INCLUDED}{}", data("inp/block_nodes.inp"));
    vec![cube.into_bytes(), block.into_bytes()]
}

/// The fixture's third deck file, `more.inp`: the cube's last eight nodes,
/// which the nested seed of [`include_seeds`] includes from `nodes.inp`.
fn more_nodes() -> String {
    let cube = std::fs::read_to_string(root().join("tests/data/cube_hex.inp")).unwrap();
    let nodes: Vec<&str> = cube.lines().skip(3).take(64).collect();
    format!("*NODE\n{}\n", nodes[56..].join("\n"))
}

/// Seeds of [`Target::Inp`] whose `*INCLUDE` is one of the input guard's
/// cases (issue 31 item 1), so that every mutation of them starts there:
/// the cube deck's nodes included in two levels (`main.inp` → `nodes.inp`
/// → `more.inp`, a valid deck), and the cube deck with one more include of
/// the FIFO `fifo.inp`, of `/dev/zero`, of a binary mesh `cube_bin.msh`,
/// of itself and of a missing file (each refused). Returns the valid
/// seeds, then the refused ones.
fn include_seeds(cube: &[u8]) -> (Vec<Vec<u8>>, Vec<Vec<u8>>) {
    let cube = std::str::from_utf8(cube).unwrap();
    let (main, included) = cube.split_once(INCLUDED).unwrap();
    let nodes: Vec<&str> = included.lines().collect();
    // `*NODE` and 56 of the 64 nodes here, the last 8 in more.inp
    let nested = format!(
        "{main}{INCLUDED}{}\n*INCLUDE, INPUT=more.inp\n",
        nodes[..57].join("\n")
    );
    let refused = [
        "fifo.inp",
        "/dev/zero",
        "cube_bin.msh",
        "main.inp",
        "absent.inp",
    ]
    .iter()
    .map(|file| {
        let main = main.replacen(
            "*INCLUDE, INPUT=nodes.inp\n",
            &format!("*INCLUDE, INPUT=nodes.inp\n*INCLUDE, INPUT={file}\n"),
            1,
        );
        format!("{main}{INCLUDED}{included}").into_bytes()
    })
    .collect();
    (vec![nested.into_bytes()], refused)
}

fn corpus() -> Corpus {
    let data = |n: &str| std::fs::read(root().join("tests/data").join(n)).unwrap();
    let msh = [
        "cube_hex_41_ascii.msh",
        "cube_hex_41_bin.msh",
        "cube_hex_22_ascii.msh",
        "cube_hex_22_bin.msh",
    ]
    .iter()
    .map(|n| data(n))
    .collect();
    let stl = ["tetrahedron_ascii.stl", "tetrahedron_binary.stl"]
        .iter()
        .map(|n| data(n))
        .collect();
    let mut cases = vec![
        CUBE_CASE.as_bytes().to_vec(),
        format!("{CUBE_CASE}{MORE_TABLES}").into_bytes(),
    ];
    let mut examples: Vec<PathBuf> = std::fs::read_dir(root().join("examples"))
        .unwrap()
        .map(|e| e.unwrap().path().join("case.toml"))
        .filter(|p| p.exists())
        .collect();
    examples.sort();
    for p in examples {
        // the examples' meshes are large: point them at the cube
        let text = std::fs::read_to_string(p).unwrap();
        let text: String = text
            .lines()
            .map(|l| {
                if l.starts_with("file = ") && l.ends_with(".msh\"") {
                    "file = \"cube.msh\"".to_string()
                } else {
                    l.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("\n");
        cases.push(text.into_bytes());
    }
    let mut decks = deck_seeds();
    let (nested, refused) = include_seeds(&decks[0]);
    decks.extend(nested);
    let valid_decks = decks.len();
    decks.extend(refused);
    Corpus {
        msh,
        stl,
        cases,
        decks,
        valid_decks,
    }
}

/// One random mutation of `d`.
fn mutate(d: &mut Vec<u8>, rng: &mut StdRng) {
    let len = d.len();
    let at = |rng: &mut StdRng| if len == 0 { 0 } else { rng.gen_range(0..len) };
    match rng.gen_range(0..9) {
        0 if len > 0 => {
            let i = at(rng);
            d[i] ^= 1 << rng.gen_range(0..8);
        }
        1 if len > 0 => {
            let i = at(rng);
            d[i] = rng.gen();
        }
        2 => {
            let i = at(rng);
            let n = rng.gen_range(1..8);
            for _ in 0..n {
                d.insert(i, rng.gen());
            }
        }
        3 if len > 0 => {
            let i = at(rng);
            let n = rng.gen_range(1..=16).min(len - i);
            d.drain(i..i + n);
        }
        4 if len > 0 => {
            // duplicate a chunk
            let i = at(rng);
            let n = rng.gen_range(1..=64).min(len - i);
            let chunk: Vec<u8> = d[i..i + n].to_vec();
            let j = at(rng);
            d.splice(j..j, chunk);
        }
        5 if len > 0 => {
            d.truncate(at(rng));
        }
        6 | 7 => {
            // splice a dictionary token, replacing a token of the input
            let token = DICTIONARY[rng.gen_range(0..DICTIONARY.len())].as_bytes();
            let i = at(rng);
            // a token ends at white space or TOML punctuation, so that a
            // number in `[0.0, 1.0]` is replaced and the array stays
            let end = d[i..]
                .iter()
                .position(|c| c.is_ascii_whitespace() || b",[]=\"".contains(c))
                .map_or(len, |p| i + p);
            if rng.gen_bool(0.5) {
                d.splice(i..end, token.iter().copied());
            } else {
                d.splice(i..i, token.iter().copied());
            }
        }
        _ if len > 0 => {
            // overwrite 4 or 8 bytes with an extreme binary value
            let values: [[u8; 8]; 6] = [
                f64::NAN.to_le_bytes(),
                f64::INFINITY.to_le_bytes(),
                (-1e155f64).to_le_bytes(),
                u64::MAX.to_le_bytes(),
                (i32::MAX as u64).to_le_bytes(),
                0u64.to_le_bytes(),
            ];
            let v = values[rng.gen_range(0..values.len())];
            let n = if rng.gen_bool(0.5) { 4 } else { 8 };
            let i = at(rng);
            let n = n.min(len - i);
            d[i..i + n].copy_from_slice(&v[..n]);
        }
        _ => d.push(rng.gen()),
    }
}

/// The fixed state `check` runs against: the cube mesh, and a folder with
/// the files cases may name (the cube mesh, the case of the decks' cube
/// mesh `inp_case.toml`, a FIFO `fifo.inp`, the third file of a nested
/// include `more.inp`, a binary mesh `cube_bin.msh`), where
/// [`Target::Inp`] writes its deck.
struct Fixture {
    mesh: Arc<signorini::mesh::Mesh>,
    case_path: PathBuf,
    _dir: tempfile::TempDir,
}

fn fixture() -> Fixture {
    let dir = tempfile::tempdir().unwrap();
    let cube = root().join("tests/data/cube_hex_41_ascii.msh");
    std::fs::copy(&cube, dir.path().join("cube.msh")).unwrap();
    let inp_case = CUBE_CASE.replacen("file = \"cube.msh\"", "file = \"main.inp\"", 1);
    std::fs::write(dir.path().join("inp_case.toml"), inp_case).unwrap();
    let fifo = std::process::Command::new("mkfifo")
        .arg(dir.path().join("fifo.inp"))
        .status();
    assert!(fifo.is_ok_and(|s| s.success()), "mkfifo");
    std::fs::write(dir.path().join("more.inp"), more_nodes()).unwrap();
    let binary = root().join("tests/data/cube_hex_41_bin.msh");
    std::fs::copy(&binary, dir.path().join("cube_bin.msh")).unwrap();
    Fixture {
        mesh: Arc::new(signorini::mesh::gmsh::read_msh(&cube).unwrap()),
        case_path: dir.path().join("case.toml"),
        _dir: dir,
    }
}

/// Run `target` on `input`; the library may return any error, not panic.
/// Returns whether the input was accepted (read, or for `Check` parsed
/// and validated), which tells how deep the fuzzing goes.
fn execute(target: Target, input: &[u8], f: &Fixture) -> bool {
    let path = Path::new("fuzz");
    match target {
        Target::Msh => signorini::mesh::gmsh::parse_msh(input, path).is_ok(),
        Target::Stl => {
            let read = signorini::mesh::stl::parse_stl(input, path);
            if let Ok(m) = &read {
                let vertices = m
                    .vertices
                    .iter()
                    .map(|v| nalgebra::Vector3::new(v.0[0] as f64, v.0[1] as f64, v.0[2] as f64))
                    .collect();
                let triangles = m.faces.iter().map(|t| t.vertices).collect();
                if let Ok(s) = signorini::contact::TriangulatedSurface::new(vertices, triangles) {
                    let _ = s.closest_point(&nalgebra::Vector3::new(0.3, 0.2, 0.1));
                }
            }
            read.is_ok()
        }
        Target::CaseParse => std::str::from_utf8(input).is_ok_and(|text| parse(path, text).is_ok()),
        Target::Check => {
            let Ok(text) = std::str::from_utf8(input) else {
                return false;
            };
            let Ok(spec) = parse(&f.case_path, text) else {
                return false;
            };
            check(f, spec, f.mesh.clone())
        }
        Target::MeshCheck => {
            let Ok(mesh) = signorini::mesh::gmsh::parse_msh(input, path) else {
                return false;
            };
            let spec = parse(&f.case_path, CUBE_CASE).unwrap();
            check(f, spec, Arc::new(mesh))
        }
        Target::Inp => {
            let (main, included) = split_deck(input);
            let dir = f.case_path.parent().unwrap();
            std::fs::write(dir.join("main.inp"), main).unwrap();
            std::fs::write(dir.join("nodes.inp"), included).unwrap();
            let file = if main.starts_with(CASE_MESH.as_bytes()) {
                "inp_case.toml"
            } else {
                "main.inp"
            };
            check_file(&dir.join(file))
        }
    }
}

/// `signorini check FILE` in process: the case (or deck) read with its
/// mesh, the problem built as the run builds it, the output requests.
fn check_file(path: &Path) -> bool {
    let Ok(case) = signorini::case::load(path) else {
        return false;
    };
    signorini::run::problem_as_run(&case)
        .is_ok_and(|(problem, _)| case.output_requests(&problem).is_ok())
}

/// `check`: the case validated against `mesh`, its output requests too.
fn check(
    f: &Fixture,
    spec: signorini::case::schema::CaseFile,
    mesh: Arc<signorini::mesh::Mesh>,
) -> bool {
    if mesh.elements.is_empty() {
        return false; // `case::load` rejects it before
    }
    let case = Case {
        path: f.case_path.clone(),
        spec,
        mesh,
        notes: Vec::new(),
        text: String::new(),
    };
    case.build_problem()
        .is_ok_and(|problem| case.output_requests(&problem).is_ok())
}

/// Counts of one fuzzing run.
#[derive(Default)]
struct Counts {
    executions: [AtomicU64; TARGETS.len()],
    /// Executions whose mutated input was still accepted.
    accepted: [AtomicU64; TARGETS.len()],
    crashes: AtomicU64,
}

/// Fuzz on `threads` threads until `duration` or `max_executions` (per
/// thread) is reached; returns the counts and the crash files written.
fn fuzz(
    seed: u64,
    threads: usize,
    duration: Duration,
    max_executions: u64,
) -> (Counts, Vec<PathBuf>) {
    let corpus = corpus();
    let counts = Counts::default();
    let crashes = std::sync::Mutex::new(Vec::new());
    let stop = AtomicBool::new(false);
    let crash_dir = root().join("target/fuzz-crashes");
    // a panic is reported by the harness, not printed by the hook
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let start = Instant::now();
    std::thread::scope(|s| {
        for t in 0..threads {
            let (corpus, counts, crashes, stop, crash_dir) =
                (&corpus, &counts, &crashes, &stop, &crash_dir);
            s.spawn(move || {
                let f = fixture();
                let mut rng = StdRng::seed_from_u64(seed + t as u64);
                for n in 0..max_executions {
                    if n % 256 == 0 && (stop.load(Ordering::Relaxed) || start.elapsed() > duration)
                    {
                        break;
                    }
                    let k = rng.gen_range(0..TARGETS.len());
                    let target = TARGETS[k];
                    let seeds = match target {
                        Target::Msh | Target::MeshCheck => &corpus.msh[..],
                        Target::Stl => &corpus.stl[..],
                        Target::CaseParse => &corpus.cases[..],
                        // the cases that pass on the cube mesh
                        Target::Check => &corpus.cases[..2],
                        Target::Inp => &corpus.decks[..],
                    };
                    let mut input = seeds[rng.gen_range(0..seeds.len())].clone();
                    // 1 mutation half of the time, 2 a quarter, … at most 8:
                    // most inputs stay close to valid and reach deep code
                    let mutations = 1 + rng.gen::<u32>().trailing_zeros().min(7);
                    for _ in 0..mutations {
                        mutate(&mut input, &mut rng);
                    }
                    counts.executions[k].fetch_add(1, Ordering::Relaxed);
                    let outcome = catch_unwind(AssertUnwindSafe(|| execute(target, &input, &f)));
                    if matches!(outcome, Ok(true)) {
                        counts.accepted[k].fetch_add(1, Ordering::Relaxed);
                    }
                    if outcome.is_err() {
                        counts.crashes.fetch_add(1, Ordering::Relaxed);
                        std::fs::create_dir_all(crash_dir).unwrap();
                        let file = crash_dir.join(format!("{target:?}-{seed}-{t}-{n}.bin"));
                        std::fs::write(&file, &input).unwrap();
                        crashes.lock().unwrap().push(file);
                    }
                }
            });
        }
    });
    std::panic::set_hook(hook);
    (counts, crashes.into_inner().unwrap())
}

fn report(counts: &Counts, elapsed: Duration) -> u64 {
    let total: u64 = counts
        .executions
        .iter()
        .map(|c| c.load(Ordering::Relaxed))
        .sum();
    let secs = elapsed.as_secs_f64();
    println!(
        "fuzz: {total} executions in {secs:.0} s ({:.0}/s), {} crashes",
        total as f64 / secs,
        counts.crashes.load(Ordering::Relaxed)
    );
    for (k, t) in TARGETS.iter().enumerate() {
        println!(
            "  {t:?}: {} executions, {} accepted",
            counts.executions[k].load(Ordering::Relaxed),
            counts.accepted[k].load(Ordering::Relaxed)
        );
    }
    total
}

/// A short seeded run: the harness works and the first thousands of
/// mutations do not panic.
#[test]
fn fuzz_smoke() {
    // the seeds are valid inputs of their targets (else the fuzzing is shallow)
    let c = corpus();
    let f = fixture();
    for m in &c.msh {
        assert!(execute(Target::Msh, m, &f));
    }
    for m in &c.stl {
        assert!(execute(Target::Stl, m, &f));
    }
    for (i, m) in c.cases.iter().enumerate() {
        assert!(execute(Target::CaseParse, m, &f), "case {i}");
    }
    for m in &c.cases[..2] {
        assert!(execute(Target::Check, m, &f));
    }
    for m in &c.msh {
        assert!(execute(Target::MeshCheck, m, &f));
    }
    for (i, m) in c.decks.iter().enumerate() {
        let valid = i < c.valid_decks;
        assert_eq!(execute(Target::Inp, m, &f), valid, "deck {i}");
    }
    let start = Instant::now();
    let (counts, crashes) = fuzz(1, 1, Duration::from_secs(120), 3000);
    report(&counts, start.elapsed());
    assert!(crashes.is_empty(), "panics on: {crashes:?}");
}

/// The long run: `FUZZ_SECONDS` (default 60) on `FUZZ_THREADS` (default 2)
/// threads, seed `FUZZ_SEED` (default: the time).
#[test]
#[ignore]
fn fuzz_for_a_while() {
    let env = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<u64>().ok());
    let seconds = env("FUZZ_SECONDS").unwrap_or(60);
    let threads = env("FUZZ_THREADS").unwrap_or(2) as usize;
    let seed = env("FUZZ_SEED").unwrap_or_else(|| {
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs())
    });
    println!("fuzz: seed {seed}, {threads} threads, {seconds} s");
    let start = Instant::now();
    let (counts, crashes) = fuzz(seed, threads, Duration::from_secs(seconds), u64::MAX);
    report(&counts, start.elapsed());
    assert!(crashes.is_empty(), "panics on: {crashes:?}");
}
