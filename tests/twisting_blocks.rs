//! `examples/twisting-blocks` on its coarse mesh (`coarse.msh`, 4 × 4 and
//! 3 × 3 cells on the contact faces): a block pressed onto another, then
//! its top face turned by 90° in 20 increments, dual mortar contact with
//! Coulomb friction (μ = 0.3, exact stick). The run takes no cut, every
//! closed node slips at the end, and the saturated reaction moment is the
//! full-slip moment `M = μ ∫ p |r| dA` of the transmitted mean pressure.

use signorini::output::observer::Silent;
use signorini::run::{RunOptions, Simulation};
use std::path::Path;

const MU: f64 = 0.3;
/// The side of the upper block's square contact face.
const SIDE: f64 = 1.0;

/// The rows of a history's CSV: time, then its values.
fn rows(dir: &Path, name: &str) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(dir.join(format!("{name}.csv"))).unwrap();
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// `Σ_j A_j |r_j|` over the nodes of the face `surface` (its Hex8 faces
/// are squares: `A_j` a quarter of each adjacent facet's area, the dual
/// mortar's `D_jj`), `r_j` the node's distance from the vertical axis:
/// `∫ |r| dA` by the nodal rule the interface transmits tractions with.
fn nodal_radius_integral(simulation: &Simulation, surface: &str) -> f64 {
    let mesh = &simulation.problem().model.mesh;
    let face = mesh.surface(surface).unwrap();
    let mut sum = 0.0;
    for facet in &face.facets {
        let p: Vec<[f64; 3]> = facet.nodes.iter().map(|&n| mesh.nodes[n]).collect();
        let side = |a: usize, b: usize| (0..3).map(|i| (p[b][i] - p[a][i]).powi(2)).sum::<f64>();
        let area = (side(0, 1) * side(1, 2)).sqrt();
        sum += p
            .iter()
            .map(|x| 0.25 * area * x[0].hypot(x[1]))
            .sum::<f64>();
    }
    sum
}

/// The coarse twisting blocks: no cut in the press nor in the twist, at
/// most 6 Newton iterations per twist increment, every closed node
/// slipping at 90°, and the saturated moment (the mean over the last 15
/// increments, which vary by less than 1 % of it: no chattering)
/// - against `μ p Σ_j A_j |r_j|` (uniform pressure `p = F_z / a²` on the
///   nodal rule): within 1 % (0.2 % measured; the pressure is not exactly
///   uniform);
/// - against the continuum's `μ p a³ (√2 + ln(1 + √2)) / 6`: within 12 %
///   (+9.4 % measured on 3 × 3 cells: the nodal rule's `Σ A_j |r_j|` is
///   9.1 % above `∫ |r| dA`, an O(h²) error; 3.2 % on the example's 5 × 5).
#[test]
fn twisting_blocks_saturate_at_the_full_slip_moment() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/twisting-blocks");
    let text = std::fs::read_to_string(dir.join("case.toml"))
        .unwrap()
        .replace("file = \"blocks.msh\"", "file = \"coarse.msh\"");
    assert!(text.contains("coarse.msh"));
    let mut simulation = Simulation::from_toml(&text, &dir).unwrap();
    let out = tempfile::tempdir().unwrap();
    let options = RunOptions {
        output: Some(out.path().to_path_buf()),
        threads: None,
        cancel: None,
        restart: None,
    };
    let summary = simulation.run(&options, &mut Silent).unwrap().summary;
    assert_eq!(
        summary.increments.len(),
        21,
        "one press, twenty twist increments"
    );
    for inc in &summary.increments {
        assert_eq!(inc.cuts, 0, "a cut at t = {}", inc.time);
        if inc.step_name == "twist" {
            assert!(
                inc.iterations <= 6,
                "{} iterations at t = {}",
                inc.iterations,
                inc.time
            );
        }
    }
    let interface = &summary.increments.last().unwrap().contact["interface"];
    assert!(interface.closed_nodes > 0);
    assert_eq!(interface.stick_nodes, 0, "full slip at 90°");
    assert_eq!(interface.slip_nodes, interface.closed_nodes);

    let moment = rows(out.path(), "moment");
    let press = rows(out.path(), "press");
    let last: Vec<f64> = moment[moment.len() - 15..].iter().map(|r| r[1]).collect();
    let saturated = last.iter().sum::<f64>() / last.len() as f64;
    let spread = last
        .iter()
        .fold(0.0f64, |m, v| m.max((v - saturated).abs()));
    assert!(spread < 1e-2 * saturated, "moment {last:?}");
    let pressure = -press.last().unwrap()[1] / (SIDE * SIDE);
    let nodal = MU * pressure * nodal_radius_integral(&simulation, "upper_bottom");
    let sqrt2 = std::f64::consts::SQRT_2;
    let continuum = MU * pressure * SIDE.powi(3) * (sqrt2 + (1.0 + sqrt2).ln()) / 6.0;
    eprintln!(
        "p = {pressure:.5}, M = {saturated:.5}, nodal rule {nodal:.5} ({:+.2} %), \
         continuum {continuum:.5} ({:+.2} %)",
        100.0 * (saturated / nodal - 1.0),
        100.0 * (saturated / continuum - 1.0)
    );
    assert!((saturated / nodal - 1.0).abs() < 1e-2);
    assert!((saturated / continuum - 1.0).abs() < 0.12);
    let svg = std::fs::read_to_string(out.path().join("moment.svg")).unwrap();
    assert!(svg.contains("reaction moment M_z (N·mm)"), "{svg}");
}
