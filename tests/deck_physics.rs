//! The deck's physics against closed forms (issue 33), each deck run as
//! it is (`signorini::run` on the `.inp`):
//! - `*HYPERELASTIC, OGDEN, N=2` and `N=3`: a cube stretched uniaxially
//!   (λ = 1.5, the lateral faces free) gives the reaction of Ogden's
//!   nominal stress in Abaqus's convention, to 1e-8;
//! - `*TIME POINTS` and `*AMPLITUDE`: a bar under an amplitude-shaped
//!   `*CLOAD` writes its VTU files at the deck's time points exactly, and
//!   its tip displacement follows the amplitude, to 1e-10;
//! - `*DLOAD … GRAV`: a bar of C3D20 hanging under its weight has the
//!   quadratic displacement `u_z(z) = −ρg(L² − z²)/(2E)`, to 1e-10, and
//!   CalculiX's `ccx` on the same deck agrees (skipped without `ccx`).

mod ccx;

use signorini::run::{run, RunOptions, RunOutcome};
use std::fmt::Write;
use std::path::Path;

fn run_deck(dir: &Path, name: &str, text: &str) -> RunOutcome {
    let deck = dir.join(name);
    std::fs::write(&deck, text).unwrap();
    run(
        &deck,
        &RunOptions {
            output: Some(dir.join("out")),
            threads: None,
            cancel: None,
            restart: None,
        },
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The rows of a history's CSV (the header skipped).
fn rows(csv: &Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(csv).unwrap();
    text.lines()
        .filter_map(|l| l.split(',').map(|f| f.trim().parse().ok()).collect())
        .collect()
}

/// The unit cube of one C3D8, symmetry planes x = y = z = 0, the face
/// x = 1 moved by 0.5 (λ = 1.5), with `material`'s lines.
fn stretched_cube(material: &str) -> String {
    format!(
        "*HEADING
uniaxial stretch of an Ogden cube
*NODE
1, 0., 0., 0.
2, 1., 0., 0.
3, 1., 1., 0.
4, 0., 1., 0.
5, 0., 0., 1.
6, 1., 0., 1.
7, 1., 1., 1.
8, 0., 1., 1.
*ELEMENT, TYPE=C3D8, ELSET=Cube
1, 1, 2, 3, 4, 5, 6, 7, 8
*NSET, NSET=X0
1, 4, 5, 8
*NSET, NSET=X1
2, 3, 6, 7
*NSET, NSET=Y0
1, 2, 5, 6
*NSET, NSET=Z0
1, 2, 3, 4
*MATERIAL, NAME=Rubber
{material}
*SOLID SECTION, ELSET=Cube, MATERIAL=Rubber
*BOUNDARY
X0, 1, 1
Y0, 2, 2
Z0, 3, 3
*STEP, NLGEOM
*STATIC
0.1, 1.
*BOUNDARY
X1, 1, 1, 0.5
*NODE PRINT, NSET=X1
RF
*END STEP
"
    )
}

/// Abaqus's Ogden (`W = Σ 2μ_i/α_i² (Σ_a λ̄_a^α_i − 3) + (J − 1)²/D1`)
/// in uniaxial stress: the principal Kirchhoff stresses are
/// `τ_a = Σ_i (2μ_i/α_i)(λ̄_a^α_i − ⅓ Σ_b λ̄_b^α_i) + 2J(J − 1)/D1`; the
/// lateral stretch `t` solves `τ₂(λ, t, t) = 0` (bisection, to
/// rounding), and the nominal stress is `P = τ₁/λ`.
fn ogden_nominal_stress(mu: &[f64], alpha: &[f64], d1: f64, lambda: f64) -> f64 {
    let tau = |stretches: [f64; 3], a: usize| {
        let j: f64 = stretches.iter().product();
        let bar = stretches.map(|l| l * j.powf(-1.0 / 3.0));
        let deviatoric: f64 = mu
            .iter()
            .zip(alpha)
            .map(|(&m, &al)| {
                let sum: f64 = bar.iter().map(|b| b.powf(al)).sum();
                2.0 * m / al * (bar[a].powf(al) - sum / 3.0)
            })
            .sum();
        deviatoric + 2.0 * j * (j - 1.0) / d1
    };
    let lateral = |t: f64| tau([lambda, t, t], 1);
    let (mut lo, mut hi) = (0.3, 1.0);
    assert!(lateral(lo) < 0.0 && lateral(hi) > 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if lateral(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let t = 0.5 * (lo + hi);
    tau([lambda, t, t], 0) / lambda
}

/// Treloar's rubber as Ogden fitted it (μ'_i = 0.63, 0.0012, −0.01 MPa
/// of the form `μ'_i/α_i`, here in Abaqus's `μ_i = μ'_i α_i/2`), slightly
/// compressible (D1 = 0.01/MPa, κ = 200 MPa): N = 2 and N = 3.
/// The cube's stretch is homogeneous, which the trilinear element holds
/// exactly, so the reaction on the face x = 1 (area 1) is the nominal
/// stress at every increment, to Newton's tolerance (1e-8 relative).
#[test]
fn ogden_decks_stretch_as_abaqus_ogden() {
    let terms: [(&[f64], &[f64]); 2] = [
        (&[0.4095, 0.003], &[1.3, 5.0]),
        (&[0.4095, 0.003, 0.01], &[1.3, 5.0, -2.0]),
    ];
    for (mu, alpha) in terms {
        let n = mu.len();
        let mut data: Vec<f64> = mu.iter().zip(alpha).flat_map(|(&m, &a)| [m, a]).collect();
        data.push(0.01);
        data.extend(std::iter::repeat_n(0.0, n - 1));
        let mut lines = String::new();
        for chunk in data.chunks(8) {
            let fields: Vec<String> = chunk.iter().map(|x| format!("{x:?}")).collect();
            let _ = writeln!(lines, "{}", fields.join(", "));
        }
        let material = format!("*HYPERELASTIC, OGDEN, N={n}\n{}", lines.trim_end());
        let dir = tempfile::tempdir().unwrap();
        run_deck(dir.path(), "cube.inp", &stretched_cube(&material));
        let history = rows(&dir.path().join("out/X1_RF.csv"));
        assert_eq!(history.last().unwrap()[0], 1.0);
        for row in &history[1..] {
            let lambda = 1.0 + 0.5 * row[0];
            let expected = ogden_nominal_stress(mu, alpha, 0.01, lambda);
            let error = (row[1].abs() - expected).abs();
            println!(
                "N={n} λ={lambda}: RF {:.12e}, Ogden {expected:.12e}",
                row[1]
            );
            assert!(
                error <= 1e-8 * expected.abs(),
                "N={n} λ={lambda}: {row:?} vs {expected}"
            );
            assert!(
                row[2].abs() + row[3].abs() <= 1e-8 * expected.abs(),
                "{row:?}"
            );
        }
    }
}

/// A column of C3D8 (1 × 1 × 2, E = 100, ν = 0) fixed at z = 0 and pulled
/// at z = 2 by `*CLOAD` 2.5 per node (total 10) shaped by `*AMPLITUDE`
/// `(0, 0), (0.5, 1), (1, 0.25)`, with `*TIME POINTS` 0.2, 0.5, 0.8 on
/// its step of period 1.
fn pulled_column() -> String {
    let mut nodes = String::new();
    for k in 0..3 {
        for (j, (x, y)) in [(0., 0.), (1., 0.), (1., 1.), (0., 1.)].iter().enumerate() {
            let _ = writeln!(nodes, "{}, {x:?}, {y:?}, {:?}", 1 + j + 4 * k, k as f64);
        }
    }
    format!(
        "*NODE
{nodes}*ELEMENT, TYPE=C3D8, ELSET=Column
1, 1, 2, 3, 4, 5, 6, 7, 8
2, 5, 6, 7, 8, 9, 10, 11, 12
*NSET, NSET=Bottom
1, 2, 3, 4
*NSET, NSET=Top
9, 10, 11, 12
*MATERIAL, NAME=Soft
*ELASTIC
100., 0.
*SOLID SECTION, ELSET=Column, MATERIAL=Soft
*AMPLITUDE, NAME=Bump
0., 0., 0.5, 1., 1., 0.25
*TIME POINTS, NAME=Frames
0.2, 0.5, 0.8
*BOUNDARY
Bottom, 1, 3
*STEP
*STATIC, TIME POINTS=Frames
0.1, 1.
*CLOAD, AMPLITUDE=Bump
Top, 3, 2.5
*NODE PRINT, NSET=Top
U
*NODE FILE
U
*END STEP
"
    )
}

/// The times of the datasets of a `.pvd`.
fn pvd_times(pvd: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(pvd).unwrap();
    text.split("timestep=\"")
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].parse().unwrap())
        .collect()
}

/// The VTU files are at the deck's time points and the step's end (and
/// the reference state at 0), as CalculiX writes them; at every increment
/// (the histories' rows) the tip displacement is the amplitude's share of
/// `F L/(E A) = 10 × 2/100 = 0.2` (ν = 0: a uniform uniaxial stress,
/// exact in the trilinear element), to 1e-10.
#[test]
fn time_points_and_amplitude_land_at_the_decks_times() {
    let dir = tempfile::tempdir().unwrap();
    run_deck(dir.path(), "column.inp", &pulled_column());
    let times = pvd_times(&dir.path().join("out/column.pvd"));
    let expected = [0.0, 0.2, 0.5, 0.8, 1.0];
    assert_eq!(times.len(), expected.len(), "{times:?}");
    for (t, e) in times.iter().zip(expected) {
        assert!((t - e).abs() <= 1e-12, "{times:?}");
    }
    let bump = |t: f64| {
        if t <= 0.5 {
            2.0 * t
        } else {
            1.0 - 1.5 * (t - 0.5)
        }
    };
    let history = rows(&dir.path().join("out/Top_U3.csv"));
    for e in &expected[1..] {
        assert!(
            history.iter().any(|r| (r[0] - e).abs() <= 1e-12),
            "no row at {e}: {history:?}"
        );
    }
    for row in &history {
        let u = 0.2 * bump(row[0]);
        assert!(
            (row[1] - u).abs() <= 1e-10 * 0.2,
            "t = {}: {} vs {u}",
            row[0],
            row[1]
        );
    }
}

/// A 1 × 1 × 4 column of four C3D20 (E = 1000, ν = 0, `*DENSITY` 2)
/// fixed at its top z = 4 and hanging under `*DLOAD` `GRAV` 10 in −z.
fn hanging_column() -> String {
    let id = |i: usize, j: usize, k: usize| 1 + i + 3 * j + 9 * k;
    let mut nodes = String::new();
    let mut top = Vec::new();
    for k in 0..=8 {
        for j in 0..3 {
            for i in 0..3 {
                let corner = i != 1 && j != 1;
                let used = if k % 2 == 0 {
                    !(i == 1 && j == 1)
                } else {
                    corner
                };
                if used {
                    let (x, y, z) = (0.5 * i as f64, 0.5 * j as f64, 0.5 * k as f64);
                    let _ = writeln!(nodes, "{}, {x:?}, {y:?}, {z:?}", id(i, j, k));
                    if k == 8 {
                        top.push(id(i, j, k).to_string());
                    }
                }
            }
        }
    }
    let mut elements = String::new();
    let ring = [(0, 0), (2, 0), (2, 2), (0, 2)];
    let mids = [(1, 0), (2, 1), (1, 2), (0, 1)];
    for e in 0..4 {
        let k = 2 * e;
        let mut n: Vec<usize> = Vec::new();
        n.extend(ring.iter().map(|&(i, j)| id(i, j, k)));
        n.extend(ring.iter().map(|&(i, j)| id(i, j, k + 2)));
        n.extend(mids.iter().map(|&(i, j)| id(i, j, k)));
        n.extend(mids.iter().map(|&(i, j)| id(i, j, k + 2)));
        n.extend(ring.iter().map(|&(i, j)| id(i, j, k + 1)));
        let text: Vec<String> = n.iter().map(|x| x.to_string()).collect();
        let _ = writeln!(
            elements,
            "{}, {},\n{}",
            e + 1,
            text[..15].join(", "),
            text[15..].join(", ")
        );
    }
    format!(
        "*NODE
{nodes}*ELEMENT, TYPE=C3D20, ELSET=Column
{elements}*NSET, NSET=Top
{}
*MATERIAL, NAME=Heavy
*ELASTIC
1000., 0.
*DENSITY
2.
*SOLID SECTION, ELSET=Column, MATERIAL=Heavy
*BOUNDARY
Top, 1, 3
*STEP
*STATIC
1., 1.
*DLOAD
Column, GRAV, 10., 0., 0., -1.
*END STEP
",
        top.join(", ")
    )
}

/// The hanging bar: `σ_zz(z) = ρ g z`, `u_z(z) = −ρg(L² − z²)/(2E)` (ν = 0,
/// so the one-dimensional solution is the three-dimensional one), which
/// the quadratic C3D20 holds exactly: every node to 1e-10 of the tip's
/// `ρgL²/(2E) = 0.16`, and no lateral motion.
#[test]
fn gravity_hangs_a_bar_as_the_closed_form() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("column.inp");
    let outcome = run_deck(dir.path(), "column.inp", &hanging_column());
    let mesh = signorini::mesh::inp::read_inp(&deck).unwrap().mesh;
    let (rho_g, e, l) = (20.0, 1000.0, 4.0);
    let tip = rho_g * l * l / (2.0 * e);
    for (n, x) in mesh.nodes.iter().enumerate() {
        let u = &outcome.displacement[3 * n..3 * n + 3];
        let expected = -rho_g * (l * l - x[2] * x[2]) / (2.0 * e);
        assert!(
            (u[2] - expected).abs() <= 1e-10 * tip,
            "node at {x:?}: {u:?} vs {expected}"
        );
        assert!(
            u[0].abs() + u[1].abs() <= 1e-10 * tip,
            "node at {x:?}: {u:?}"
        );
    }
}

/// Gravity that cannot be applied is refused at its `*DLOAD` line: a
/// material without `*DENSITY`, a direction of zero length, an element
/// number for the set.
#[test]
fn bad_gravity_is_refused_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "*DENSITY\n2.\n",
            "",
            "*MATERIAL 'Heavy' (of *SOLID SECTION, ELSET=Column) has no *DENSITY",
        ),
        (
            "GRAV, 10., 0., 0., -1.",
            "GRAV, 10., 0., 0., 0.",
            "the direction (n1, n2, n3) has zero length",
        ),
        (
            "Column, GRAV",
            "1, GRAV",
            "give an element set (*ELSET) instead of an element number",
        ),
        ("Column, GRAV", "Colum, GRAV", "Colum"),
    ];
    for (k, (from, to, message)) in cases.into_iter().enumerate() {
        let text = hanging_column().replace(from, to);
        let line = text.lines().position(|l| l.contains("GRAV")).unwrap() + 1;
        let deck = dir.path().join(format!("bad{k}.inp"));
        std::fs::write(&deck, &text).unwrap();
        let err = match signorini::case::load(&deck).and_then(|c| c.build_problem().map(|_| ())) {
            Err(e) => e.to_string(),
            Ok(()) => panic!("{message}: accepted"),
        };
        assert!(err.contains(&format!("at line {line}:")), "{err}");
        assert!(err.contains(message), "{message}? {err}");
    }
}

/// The hanging bar's deck run by CalculiX (`ccx`, its C3D20 fully
/// integrated as ours): the same displacement at every node, to 1e-6 of
/// the tip's (ccx prints 7 significant digits), so `GRAV`'s magnitude,
/// direction and `*DENSITY` are read as CalculiX reads them (measured:
/// 2.3e-14). Skipped with a message when `ccx` is not installed.
#[test]
fn gravity_agrees_with_calculix() {
    if !ccx::installed() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let text = hanging_column();
    let ids: Vec<&str> = text
        .lines()
        .skip(1)
        .take_while(|l| !l.starts_with('*'))
        .map(|l| l.split(',').next().unwrap())
        .collect();
    let with_print = text.replace("*END STEP", "*NODE PRINT, NSET=Nall\nU\n*END STEP");
    let with_print = with_print.replace(
        "*MATERIAL",
        &format!("*NSET, NSET=Nall\n{}\n*MATERIAL", ids.join(",\n")),
    );
    std::fs::write(dir.path().join("column.inp"), &with_print).unwrap();
    let reference = ccx::run(dir.path(), "column");
    assert_eq!(reference.len(), ids.len());
    let outcome = run_deck(dir.path(), "ours.inp", &with_print);
    let mesh = signorini::mesh::inp::read_inp(&dir.path().join("ours.inp"))
        .unwrap()
        .mesh;
    let tip = 0.16;
    let mut worst = 0.0f64;
    for (id, u) in &reference {
        let n = mesh.node_ids.iter().position(|i| i == id).unwrap();
        for (c, &theirs) in u.iter().enumerate() {
            let ours = outcome.displacement[3 * n + c];
            worst = worst.max((ours - theirs).abs());
            assert!(
                (ours - theirs).abs() <= 1e-6 * tip,
                "node {id}: {ours} vs ccx {theirs}"
            );
        }
    }
    println!("largest difference from ccx {worst:.3e} (tip {tip})");
}
