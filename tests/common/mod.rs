//! Shared helpers of the integration tests: problems on structured meshes
//! built directly through the library API.
#![allow(dead_code)]

use signorini::assembly::Model;
use signorini::material::Material;
use signorini::mesh::Mesh;
use signorini::problem::{Amplitude, PrescribedDisplacement, Problem, SolverSettings, Step};
use signorini::solve::linear::{Ordering, SparseLdlt};
use signorini::solve::stepping::{run_steps, IncrementRecord, StepObserver};
use std::sync::Arc;

/// A problem with one material everywhere and no loads yet.
pub fn problem(mesh: Mesh, material: Arc<dyn Material>) -> Problem {
    let n = mesh.elements.len();
    let model = Model::new(Arc::new(mesh), vec![material], vec![0; n]).expect("valid mesh");
    Problem {
        model,
        prescribed: Vec::new(),
        pressures: Vec::new(),
        body_forces: Vec::new(),
        steps: vec![Step {
            name: "load".into(),
            end_time: 1.0,
            initial_increment: 1.0,
            min_increment: 1e-4,
            max_increment: 1.0,
        }],
        settings: SolverSettings {
            residual_tolerance: 1e-10,
            ..SolverSettings::default()
        },
    }
}

/// Prescribe components `(component, value)` on every node of a surface.
pub fn fix(problem: &mut Problem, surface: &str, components: &[(usize, f64)]) {
    let mesh = &problem.model.mesh;
    let s = mesh.surface(surface).expect("surface exists");
    problem.prescribed.push(PrescribedDisplacement {
        surface: surface.into(),
        nodes: mesh.surface_nodes(s),
        components: components.to_vec(),
        amplitude: Amplitude::ramp(),
    });
}

/// Records every converged increment.
#[derive(Default)]
pub struct Recorder {
    pub increments: Vec<IncrementRecord>,
}

impl StepObserver for Recorder {
    fn on_converged(&mut self, _p: &Problem, record: &IncrementRecord, _u: &[f64]) -> signorini::Result<()> {
        self.increments.push(record.clone());
        Ok(())
    }
}

/// Solve all steps; return the displacement and the increments.
pub fn solve(problem: &Problem) -> (Vec<f64>, Vec<IncrementRecord>) {
    let mut solver = SparseLdlt::new(Ordering::Amd, 1);
    let mut rec = Recorder::default();
    let u = run_steps(problem, &mut solver, &mut rec, "unused".into()).expect("converges");
    (u, rec.increments)
}
