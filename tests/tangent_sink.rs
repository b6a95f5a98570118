//! The tangent written into a sink (`signorini::assembly::sink`, what a
//! distributed run on PETSc assembles into PETSc's matrix) equals the
//! tangent written as values on the pattern: two processes' shares of the
//! elements (even and odd) and of the nodes, each writing its element
//! blocks and, through the side pattern, its own rows of contact and
//! loads, add up to the serial tangent to 1e-12 of its largest entry, on
//! every entry of the serial pattern and nowhere else. Checked for a
//! finite-strain material (the element loop) with a follower pressure and
//! penalty contact against a rigid plane, for Hooke's material (the cached
//! constant `K`, written as its mirrored lower triangle) with mortar
//! contact and its multipliers (the last process's rows), and for two
//! bodies in node-to-surface contact.

mod common;

use common::{fix, perturbed_state, press, problem, surface_interface};
use nalgebra::Vector3;
use signorini::assembly::share::{Communicator, Share};
use signorini::assembly::sink::{Entries, Tangent, TangentSink};
use signorini::contact::interface::ContactInterface;
use signorini::contact::laws::NormalLaw;
use signorini::contact::obstacle::RigidObstacle;
use signorini::material::{LinearElastic, Material, NeoHookean};
use signorini::mesh::{structured::box_mesh, ElementKind};
use signorini::problem::Problem;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// Process `rank` of two whose sums add nothing: only the tangent, each
/// process's part, is compared.
struct Alone {
    rank: usize,
}

impl Communicator for Alone {
    fn rank(&self) -> usize {
        self.rank
    }
    fn size(&self) -> usize {
        2
    }
    fn sum(&self, _: &mut [f64]) {}
}

/// A sink that adds every entry into a map `(row, column) → value`, the
/// rows `own` admits for [`Entries::OwnRows`].
struct Triplets {
    own: Vec<bool>,
    entries: Arc<Mutex<HashMap<(usize, usize), f64>>>,
}

impl Triplets {
    fn add(&self, i: usize, j: usize, v: f64) {
        *self.entries.lock().unwrap().entry((i, j)).or_insert(0.0) += v;
    }
}

impl TangentSink for Triplets {
    fn begin(&self) {}
    fn add_element(&self, dofs: &[usize], values: &[f64]) {
        let n = dofs.len();
        for (r, &i) in dofs.iter().enumerate() {
            for (c, &j) in dofs.iter().enumerate() {
                self.add(i, j, values[r * n + c]);
            }
        }
    }
    fn add_columns(
        &self,
        pattern: &faer::sparse::SymbolicSparseColMat<usize>,
        values: &[f64],
        which: Entries,
    ) {
        let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
        for j in 0..pattern.ncols() {
            for k in cp[j]..cp[j + 1] {
                let i = ri[k];
                match which {
                    Entries::LowerMirrored => {
                        self.add(i, j, values[k]);
                        if i != j {
                            self.add(j, i, values[k]);
                        }
                    }
                    Entries::OwnRows if self.own[i] => self.add(i, j, values[k]),
                    Entries::OwnRows => {}
                }
            }
        }
    }
    fn finish(&self) -> Result<(), String> {
        Ok(())
    }
    fn multiply(&self, _: &[f64], _: &mut [f64]) -> Result<(), String> {
        Err("not read here".into())
    }
    fn identity_rows(&self, _: &[bool], _: usize) -> Result<f64, String> {
        Err("not read here".into())
    }
}

/// The serial tangent of `make()` at the perturbed state of amplitude
/// `a`, against the sum of two processes' sinks; and how many contact
/// nodes are active there.
fn assert_sinks_add_up(make: impl Fn() -> Problem, a: f64, what: &str) {
    let serial = make();
    let x = perturbed_state(&serial, a, false);
    let state = serial.initial_contact_state(&x);
    let mut k = vec![0.0; serial.model.pattern.nnz()];
    let (_, reports) = serial.residual_in(1.0, &x, &state, Some(&mut k)).unwrap();
    let active = reports.iter().flatten().filter(|r| r.active).count();
    assert!(active > 0, "{what}: no contact node active");
    let entries = Arc::new(Mutex::new(HashMap::new()));
    let (elements, nodes) = (
        serial.model.mesh.elements.len(),
        serial.model.mesh.num_nodes(),
    );
    let dofs = serial.model.num_dofs();
    for rank in 0..2 {
        let mut part = make();
        let share = Share {
            owned: (0..elements).map(|e| e % 2 == rank).collect(),
            own_nodes: (0..nodes).map(|n| n % 2 == rank).collect(),
            communicator: Arc::new(Alone { rank }),
        };
        let own = (0..serial.num_unknowns())
            .map(|i| share.owns_row(i, dofs))
            .collect();
        part.set_share(share);
        let sink = Triplets {
            own,
            entries: Arc::clone(&entries),
        };
        part.residual_into(1.0, &x, &state, Some(Tangent::Sink(&sink)))
            .unwrap();
    }
    let mut entries = entries.lock().unwrap().clone();
    let scale = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let pattern = serial.model.pattern.symbolic();
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    for j in 0..pattern.ncols() {
        for p in cp[j]..cp[j + 1] {
            let sunk = entries.remove(&(ri[p], j)).unwrap_or(0.0);
            assert!(
                (sunk - k[p]).abs() <= 1e-12 * scale,
                "{what}: entry ({}, {j}) {sunk:e} against {:e}",
                ri[p],
                k[p]
            );
        }
    }
    let outside = entries.values().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(
        outside <= 1e-12 * scale,
        "{what}: {outside:e} outside the pattern"
    );
}

/// A 4 × 3 × 2 Hex8 block of `material` on the plane z = 0, x and y held
/// on its symmetry planes, a pressure on its top (`follower` or dead).
fn block(material: Arc<dyn Material>, follower: bool) -> Problem {
    let mesh = box_mesh(ElementKind::Hex8, [4, 3, 2], [1.0, 0.8, 0.5]);
    let mut pr = problem(mesh, material);
    fix(&mut pr, "xmin", &[(0, 0.0)]);
    fix(&mut pr, "ymin", &[(1, 0.0)]);
    press(&mut pr, "zmax", 5.0, follower);
    pr
}

fn floor() -> RigidObstacle {
    RigidObstacle::plane(Vector3::zeros(), Vector3::z()).unwrap()
}

#[test]
fn finite_strain_with_a_follower_pressure_and_penalty_contact() {
    let make = || {
        let material = Arc::new(NeoHookean::new(100.0, 0.3, "m").unwrap());
        let mut pr = block(material, true);
        let law = NormalLaw::Penalty { epsilon: 1e4 };
        let c = ContactInterface::rigid(&pr.model.mesh, "zmin", floor(), &law.into()).unwrap();
        pr.set_contacts(vec![c]);
        pr
    };
    assert_sinks_add_up(make, 0.01, "neo-Hookean, follower, penalty");
}

#[test]
fn hooke_with_mortar_contact_and_its_multipliers() {
    let make = || {
        let material = Arc::new(LinearElastic::new(100.0, 0.3, "m").unwrap());
        let mut pr = block(material, false);
        let law = NormalLaw::Rockafellar { p: 100.0, k: 1.0 };
        let c =
            ContactInterface::mortar_rigid(&pr.model.mesh, "zmin", floor(), &law.into()).unwrap();
        pr.set_contacts(vec![c]);
        pr
    };
    assert_sinks_add_up(make, 0.01, "Hooke, mortar");
}

#[test]
fn two_bodies_in_node_to_surface_contact() {
    let make = || {
        let mesh = common::stacked_blocks_mesh();
        let material = Arc::new(LinearElastic::new(100.0, 0.3, "m").unwrap());
        let mut pr = problem(mesh, material);
        common::support_stacked_blocks(&mut pr, 1.0);
        let law = NormalLaw::Penalty { epsilon: 1e4 };
        let c = surface_interface(&pr, "upper.zmin", "lower.zmax", law);
        pr.set_contacts(vec![c]);
        pr
    };
    assert_sinks_add_up(make, 0.01, "two bodies");
}
