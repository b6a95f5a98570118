//! `[[output.history]] quantity = "reaction_moment"`: the reaction moment
//! `Σ (x_a − c) × r_a` of a set, checked against Saint-Venant torsion of a
//! circular shaft, against equilibrium of the two ends, and against the
//! same sum taken from the run's residual by hand.

use signorini::output::{ConvergedIncrement, StepObserver, Summary};
use signorini::run::{RunOptions, Simulation};
use std::path::Path;

const E: f64 = 1000.0;
const NU: f64 = 0.25;
const LENGTH: f64 = 2.0;
const DEGREES: f64 = 0.5;

/// `Σ (x_a − c) × r_a` over the top face, about its current centroid,
/// from the converged increment's displacement and residual.
#[derive(Default)]
struct ByHand {
    moment_z: f64,
}

impl StepObserver for ByHand {
    fn on_increment(&mut self, inc: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        let mesh = &inc.problem.model.mesh;
        let nodes = mesh.surface_nodes(mesh.surface("top").unwrap());
        let u = inc.displacement();
        let x: Vec<[f64; 3]> = nodes
            .iter()
            .map(|&n| std::array::from_fn(|i| mesh.nodes[n][i] + u[3 * n + i]))
            .collect();
        let c: Vec<f64> = (0..2)
            .map(|i| x.iter().map(|p| p[i]).sum::<f64>() / x.len() as f64)
            .collect();
        self.moment_z = nodes
            .iter()
            .zip(&x)
            .map(|(&n, p)| {
                (p[0] - c[0]) * inc.residual[3 * n + 1] - (p[1] - c[1]) * inc.residual[3 * n]
            })
            .sum();
        Ok(())
    }
}

/// `J_h = ∫ r² dA` over the mesh's cross-section (its `bottom` facets, flat
/// quadrilaterals at z = 0, each split into two triangles; over a
/// triangle `∫ r² dA = A/6 (a·a + b·b + c·c + a·b + b·c + c·a)`).
fn polar_moment(simulation: &Simulation) -> f64 {
    let mesh = &simulation.problem().model.mesh;
    let bottom = mesh.surface("bottom").unwrap();
    let mut j = 0.0;
    for facet in &bottom.facets {
        let p: Vec<[f64; 2]> = facet.nodes[..4]
            .iter()
            .map(|&n| [mesh.nodes[n][0], mesh.nodes[n][1]])
            .collect();
        for [a, b, c] in [[p[0], p[1], p[2]], [p[0], p[2], p[3]]] {
            let area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs();
            let dot = |u: [f64; 2], v: [f64; 2]| u[0] * v[0] + u[1] * v[1];
            j += area / 6.0
                * (dot(a, a) + dot(b, b) + dot(c, c) + dot(a, b) + dot(b, c) + dot(c, a));
        }
    }
    j
}

/// The last row of a history's CSV, after its time.
fn last_row(dir: &Path, name: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(dir.join(format!("{name}.csv"))).unwrap();
    let line = text.lines().last().unwrap();
    line.split(',')
        .skip(1)
        .map(|v| v.parse().unwrap())
        .collect()
}

/// A Saint Venant–Kirchhoff circular shaft (R = 1, L = 2, Hex8) fixed at
/// its base and its top face turned by θ = 0.5° (`rotation`): the torque
/// is Saint-Venant's `T = G J θ / L` (a circular section does not warp, so
/// the ends' restraint changes nothing; the finite-strain terms are
/// O(θ²R²/L²) ~ 1e-5), with `J_h = ∫ r² dA` of the mesh's 32-sided
/// section (1.3 % below π R⁴ / 2): within 1e-4 (2.1e-6 measured; Hex8
/// represent the field `u = θ z (−y, x) / L` exactly, what remains is the
/// straight sides' small warping; linear elasticity measures 2.1e-4, its
/// strain of the finite rotation's radial contraction). Moment
/// balance in the current configuration (a frame-indifferent material):
/// the base's moment about the origin balances the top's to 1e-8 (in
/// linear elasticity only the reference configuration's balances), and
/// the history equals `Σ (x − c) × r` taken from the residual by hand to
/// 1e-12.
#[test]
fn torque_of_a_twisted_shaft() {
    let text = format!(
        "[mesh]\nfile = \"torsion_cylinder.msh\"\n\n\
         [[material]]\nregion = \"body\"\nmodel = \"saint_venant_kirchhoff\"\n\
         youngs_modulus = {E}\npoisson_ratio = {NU}\n\n\
         [[displacement]]\nsurface = \"bottom\"\nx = 0.0\ny = 0.0\nz = 0.0\n\n\
         [[displacement]]\nsurface = \"top\"\n\
         rotation = {{ axis = [0, 0, 1], centre = [0, 0, {LENGTH}], angle = {DEGREES} }}\n\n\
         [[step]]\nname = \"twist\"\nend_time = 1.0\ninitial_increment = 1.0\n\n\
         [solver]\nresidual_tolerance = 1e-12\n\n\
         [output]\nname = \"shaft\"\nfields = [\"displacement\"]\n\n\
         [[output.history]]\nname = \"torque\"\nquantity = \"reaction_moment_z\"\nsurface = \"top\"\n\n\
         [[output.history]]\nname = \"base\"\nquantity = \"reaction_moment\"\nsurface = \"bottom\"\npoint = [0, 0, 0]\n"
    );
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let mut simulation = Simulation::from_toml(&text, &data).unwrap();
    let out = tempfile::tempdir().unwrap();
    let options = RunOptions {
        output: Some(out.path().to_path_buf()),
        threads: Some(1),
        cancel: None,
        restart: None,
    };
    let mut by_hand = ByHand::default();
    simulation.run(&options, &mut by_hand).unwrap();
    let j = polar_moment(&simulation);
    let g = E / (2.0 * (1.0 + NU));
    let saint_venant = g * j * DEGREES.to_radians() / LENGTH;
    let torque = last_row(out.path(), "torque")[0];
    let base = last_row(out.path(), "base");
    eprintln!(
        "J_h = {j:.6} (π/2 = {:.6}), T = {torque:.6e}, G J_h θ / L = {saint_venant:.6e}, \
         relative {:.3e}; base {base:?}",
        std::f64::consts::FRAC_PI_2,
        torque / saint_venant - 1.0
    );
    assert!(
        (torque / saint_venant - 1.0).abs() < 1e-4,
        "T = {torque:.6e} against G J_h θ / L = {saint_venant:.6e}"
    );
    assert!(
        (base[2] + torque).abs() < 1e-8 * torque,
        "base {base:?}, top {torque}"
    );
    assert!(
        (by_hand.moment_z - torque).abs() < 1e-12 * torque,
        "history {torque:.15e}, by hand {:.15e}",
        by_hand.moment_z
    );
    let svg = std::fs::read_to_string(out.path().join("torque.svg")).unwrap();
    assert!(
        svg.contains("Reaction moment M_z on set &apos;top&apos;"),
        "{svg}"
    );
}
