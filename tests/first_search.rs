//! The first increment's contact search covers the increment's prescribed
//! motion (`src/contact/primary.rs`, search rule): bodies that start apart
//! and close within that increment are paired at its start, so that the
//! stepper's pairs check keeps Newton's first solve instead of searching
//! the pairs again where its answer reached and solving the increment a
//! second time (examples/two-spheres with mortar on Newton's path:
//! 17 iterations thrown away before, BENCHMARKS.md "Session 26: mortar
//! Newton, the first search").

mod common;

use common::{mortar_blocks, two_bodies};
use signorini::contact::interface::NodeReport;
use signorini::contact::laws::NormalLaw;
use signorini::mesh::{structured::box_mesh, ElementKind};
use signorini::problem::{ContactState, Problem};
use signorini::solve::backend::linear_solver;
use signorini::solve::linear::Ordering;
use signorini::solve::nonlinear::Evaluation;
use signorini::solve::record::IterationRecord;
use signorini::solve::stepping::{run_steps, IncrementRecord, StepObserver};

const E: f64 = 100.0;
/// The open gap between the blocks at the start: more than the margin
/// `2 h` of a search without motion (h = 1/3 on the upper block's faces).
const GAP: f64 = 1.0;
/// How far the upper top is pushed past closing the gap.
const SQUEEZE: f64 = 0.01;

/// What the run did: searches again, Newton records told (every
/// attempt), the converged increments, and the force on the lower bottom.
#[derive(Default)]
struct Count {
    searched_again: usize,
    iterations: usize,
    increments: Vec<IncrementRecord>,
    bottom_force: f64,
    bottom: Vec<usize>,
}

impl StepObserver<Problem> for Count {
    fn on_converged(
        &mut self,
        _p: &Problem,
        record: &IncrementRecord,
        _u: &[f64],
        evaluation: &Evaluation<Vec<Vec<NodeReport>>>,
        _c: &ContactState,
    ) -> signorini::Result<()> {
        self.increments.push(record.clone());
        // Σ (f_int − f_ext) over the held nodes: the reaction
        self.bottom_force = self
            .bottom
            .iter()
            .map(|&n| evaluation.residual[3 * n + 2])
            .sum();
        Ok(())
    }
    fn on_search_again(&mut self, _step: &str, _time: f64) {
        self.searched_again += 1;
    }
    fn on_iteration(&mut self, _step: &str, _time: f64, _record: &IterationRecord) {
        self.iterations += 1;
    }
}

/// Two linear elastic blocks 1 × 1 × 0.5 (lower 4 × 4 × 2 Hex8, upper
/// 3 × 3 × 2, non-matching), `GAP` apart, symmetry planes x = 0 and
/// y = 0, the lower bottom held in z and the upper top moved down by
/// `GAP + SQUEEZE` in one increment; dual mortar, upper bottom secondary.
/// Both blocks in uniaxial stress: the force is `E · SQUEEZE / 1.0` on
/// the unit area, exactly (a patch test of the mortar interface).
#[test]
fn blocks_that_close_in_the_first_increment_are_solved_once() {
    let lower = box_mesh(ElementKind::Hex8, [4, 4, 2], [1.0, 1.0, 0.5]);
    let upper = box_mesh(ElementKind::Hex8, [3, 3, 2], [1.0, 1.0, 0.5]);
    let mesh = two_bodies(lower, "lower", upper, "upper", [0.0, 0.0, 0.5 + GAP]);
    let law = NormalLaw::Rockafellar { p: E, k: E };
    let mut pr = mortar_blocks(mesh, E, -(GAP + SQUEEZE), law);
    let mesh = &pr.model.mesh;
    let bottom = mesh.surface_nodes(mesh.surface("lower.zmin").unwrap());
    let mut count = Count {
        bottom,
        ..Count::default()
    };
    let mut solver = linear_solver(&pr.settings, Ordering::Amd, 1);
    run_steps(&mut pr, &mut *solver, &mut count, "unused".into()).expect("converges");
    let [only] = &count.increments[..] else {
        panic!("one increment, no cut: {:?}", count.increments);
    };
    assert_eq!(
        count.searched_again, 0,
        "the first search paired the blocks"
    );
    // every Newton correction told belongs to the increment's one solve
    assert_eq!(count.iterations, only.iterations, "{:?}", only.newton);
    let expected = E * SQUEEZE / 1.0;
    let error = (count.bottom_force.abs() - expected).abs() / expected;
    assert!(
        error < 1e-8,
        "force {} against {expected}",
        count.bottom_force
    );
}
