//! The node driver's linearisation as constraint rows: per secondary node
//! its gap at the unknowns, the unit normal `n`, its area `A` and the gap's
//! gradient per coupled node, `∇g = Σ_k e_k ⊗ ∂g/∂x_k`, so that
//!
//! ```text
//! g(u + δ) ≈ g(u) + ∇g · δ,
//! ```
//!
//! and a normal force `A t_N` of the node acts on the unknowns as
//! `A t_N ∇g` where the gap is affine (the condensed path's columns).
//! Node-to-surface, `∂g/∂x_k` is `n` on the secondary node and `−w_i n` on
//! the primary nodes of its reaction (`∇g = Bᵀ n` with the lever
//! `B = ∂(x_s − x̄)/∂u` at fixed projection: `+I` on the secondary node,
//! `−w_i I` on the primary nodes, none against a rigid obstacle), and a
//! nodal traction `t` acts as `A_s Bᵀ t`. Dual mortar (Popp, Gee & Wall
//! 2009) gives the general form, `∂g_j/∂x_k` the normalised gap's complete
//! gradient over every node its row couples; against a rigid plane it is
//! `R_jk n` (Popp's `L_jk / D_j` at fixed `D`: biorthogonality,
//! `∫ Φ_j Ñ_k dA = δ_jk D_j`), so that on linear faces the rows are
//! node-to-surface's, and `A = D_j` is integrated over the current surface.
//! What a solve that meets the contact conditions directly reads (the
//! condensed path, the Josephy–Newton step), whatever the primary kind: the
//! rows come from the same [`GapProducer`] as the assembly.

use super::{ContactContext, ContactInterface, MortarGap, Primary, RigidGap, SurfaceGap};
use crate::contact::friction::TangentialResponse;
use crate::contact::kinematics::{GapKinematics, GapProducer, PrimaryWeights, QAllocator};
use crate::contact::laws::NodeContactState;
use crate::contact::mortar::Derivatives;
use crate::contact::obstacle::RigidObstacle;
use nalgebra::{DefaultAllocator, Dim, Vector3};

/// One secondary node's gap linearised at the unknowns (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct ConstraintRow {
    /// Signed gap `g` (`g ≥ 0` open).
    pub gap: f64,
    /// Unit normal `n` toward the secondary body.
    pub normal: Vector3<f64>,
    /// The node's area: the tributary reference area `A_s`, or dual
    /// mortar's `D_j` at the unknowns.
    pub area: f64,
    /// The secondary mesh node `s`.
    pub node: usize,
    /// The primary nodes of the reaction and their weights `w_i`.
    pub primary: PrimaryWeights,
    /// `(k, ∂g/∂x_k)` per coupled mesh node `k`, the secondary node first
    /// (module docs): `n` on it and `−w_i n` on the primary nodes
    /// node-to-surface, `R_jk n` of dual mortar on a rigid plane; entries
    /// below 1e-13 of the largest (the integrals' round-off where
    /// biorthogonality makes them zero) left out; empty in dual mortar's
    /// rows without derivatives
    /// ([`ContactInterface::constraint_rows_with`]).
    pub node_gradients: Vec<(usize, Vector3<f64>)>,
    /// The node's position in the frame its friction anchor is kept in
    /// ([`GapProducer::relative_position`]).
    pub relative_position: Vector3<f64>,
    /// The primary triangle the node projects on, to be kept in its state
    /// (node-to-surface only: [`GapKinematics::facet`](crate::contact::kinematics::GapKinematics)).
    pub facet: Option<usize>,
    /// `(k, b_k)` per coupled mesh node: the direction a normal force `A t_N`
    /// of the node acts along on the unknowns (`A t_N b`), where it differs
    /// from `∇g` (dual mortar: Popp's lever at fixed `D`, `M`, `n`,
    /// `R_jk n` on the secondary nodes and `−(M_jl/D_j) n` on the primary
    /// ones; components below 1e-13 of the largest, the integrals'
    /// round-off where a flat face or biorthogonality makes them zero, left
    /// out); `None`: `b = ∇g` (node-to-surface, rigid obstacles).
    pub force: Option<Vec<(usize, Vector3<f64>)>>,
    /// `(k, w_k)` per coupled mesh node: the lever `B = Σ_k w_k e_k ⊗ I`
    /// a traction of the node acts through (`A Bᵀ t`), where it is not
    /// `e_s − Σ_i w_i e_{p_i}` of [`primary`](Self::primary)
    /// ([`GapProducer::lever_weights`]: dual mortar's `R_jk` on the
    /// secondary nodes, `−M_jl/D_j` on the primary ones); `None` otherwise.
    pub lever: Option<Vec<(usize, f64)>>,
}

impl ConstraintRow {
    /// Row `d` of the lever `B` as `(dof, value)`: `+1` on `3s + d`, `−w_i`
    /// on `3p_i + d`; `w_k` on `3k + d` where the producer gives the
    /// weights ([`lever`](Self::lever)).
    pub fn lever_row(&self, d: usize) -> Vec<(usize, f64)> {
        if let Some(weights) = &self.lever {
            return weights.iter().map(|&(k, w)| (3 * k + d, w)).collect();
        }
        std::iter::once((3 * self.node + d, 1.0))
            .chain(self.primary.iter().map(|&(p, w)| (3 * p + d, -w)))
            .collect()
    }

    /// The force direction `b` as `(dof, value)`, zero components left out
    /// ([`force`](Self::force), else [`gradient`](Self::gradient)): the
    /// condensed path's column of `E`.
    pub fn force_direction(&self) -> Vec<(usize, f64)> {
        match &self.force {
            Some(force) => dof_entries(force),
            None => self.gradient(),
        }
    }

    /// `∇g` as `(dof, value)` from [`node_gradients`](Self::node_gradients),
    /// zero components left out: the secondary node's three first
    /// (`d = 0, 1, 2`), then each other coupled node's (node-to-surface:
    /// `Bᵀ n`).
    pub fn gradient(&self) -> Vec<(usize, f64)> {
        dof_entries(&self.node_gradients)
    }
}

/// Per-node vectors `(a, v)` as `(dof, value)`, zero components left out.
fn dof_entries(vectors: &[(usize, Vector3<f64>)]) -> Vec<(usize, f64)> {
    (vectors.iter())
        .flat_map(|(a, v)| {
            (0..3)
                .filter(|&d| v[d] != 0.0)
                .map(move |d| (3 * a + d, v[d]))
        })
        .collect()
}

/// `(k, b_k)` per node `k` of `nodes` from the lever `b` (node-major),
/// components below 1e-13 of the largest set to zero and nodes left with
/// none left out (see [`ConstraintRow::force`]).
fn force_vectors(nodes: &[usize], lever: &[f64]) -> Vec<(usize, Vector3<f64>)> {
    let largest = lever.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let clean = |v: f64| if v.abs() < 1e-13 * largest { 0.0 } else { v };
    (nodes.iter().enumerate())
        .map(|(a, &k)| (k, Vector3::from_fn(|d, _| clean(lever[3 * a + d]))))
        .filter(|(_, v)| *v != Vector3::zeros())
        .collect()
}

/// `(k, ∂g/∂x_k)` per node `k` of `nodes` from `gradient` (node-major),
/// nodes whose largest entry is below 1e-13 of the largest left out (see
/// [`ConstraintRow::node_gradients`]).
fn node_gradients(nodes: &[usize], gradient: &[f64]) -> Vec<(usize, Vector3<f64>)> {
    let at = |a: usize| Vector3::new(gradient[3 * a], gradient[3 * a + 1], gradient[3 * a + 2]);
    let largest = (0..nodes.len()).map(|a| at(a).amax()).fold(0.0, f64::max);
    (nodes.iter().enumerate())
        .map(|(a, &k)| (k, at(a)))
        .filter(|(_, v)| v.amax() >= 1e-13 * largest)
        .collect()
}

/// [`ConstraintRow::node_gradients`] from a node's kinematics `k`: empty
/// where its force is apart from `∇g` (dual mortar's lever) and the rows
/// were taken without derivatives.
fn row_gradients<Q: Dim, P>(
    k: &GapKinematics<Q, P>,
    derivatives: Derivatives,
) -> Vec<(usize, Vector3<f64>)>
where
    DefaultAllocator: QAllocator<Q>,
{
    match (&k.lever, derivatives) {
        (Some(_), Derivatives::Without) => Vec::new(),
        _ => node_gradients(&k.nodes, k.gradient.as_slice()),
    }
}

/// One secondary node's slip from its committed friction history at the
/// unknowns ([`GapProducer::slip`]): what Coulomb's law of the node reads
/// besides its [`ConstraintRow`].
#[derive(Clone, Debug, PartialEq)]
pub struct SlipRow {
    /// `d`, the node's motion from its anchor: `(x_s − c(t)) − (x_s − c)ₙ`
    /// against a rigid obstacle, `x_s − Σ N̄_j y_j` from its primary
    /// material point between bodies.
    pub offset: Vector3<f64>,
    /// The committed traction `t_T,n` as the producer rebuilds it at the
    /// unknowns (carried by the primary surface between bodies).
    pub committed_traction: Vector3<f64>,
}

impl ContactInterface {
    /// Every secondary node's [`SlipRow`] at time `t` and unknowns `x`
    /// from the node `states` (their committed friction history, and the
    /// kept triangle between bodies); `None` where the node has no primary
    /// within the search margin. A dual mortar producer reads its rows
    /// with `derivatives` or without (the weighted slip's value is the
    /// same; only its gradient, which a row does not hold, needs them).
    pub fn slip_rows(
        &self,
        reference: &[[f64; 3]],
        t: f64,
        x: &[f64],
        states: &[NodeContactState],
        derivatives: Derivatives,
    ) -> Vec<Option<SlipRow>> {
        let ctx = ContactContext {
            reference,
            t,
            x,
            first_multiplier: 0,
        };
        let mut rows = Vec::with_capacity(self.nodes.len());
        with_producer!(self, &ctx, derivatives, p => {
            self.for_each_node(p, &ctx, |i| states[i], |node, state, k| {
                rows.push(k.map(|mut k| {
                    let frame = p.slip(node, &mut k, &state.friction);
                    SlipRow {
                        offset: frame.kinematics.offset,
                        committed_traction: frame.kinematics.traction,
                    }
                }));
            });
        });
        rows
    }

    /// Exact stick's tangential multiplier of every node set to a solved
    /// traction: `λ_T ← t_T` (`tractions[i] = (t_T, n)`, the unit normal
    /// it lies normal to) in the form the producer's slip reads back
    /// ([`GapProducer::augment`]: the global vector against a rigid
    /// obstacle, its components on the anchor triangle's edges between
    /// bodies), at unknowns `x`, time `t`. What a solve that meets
    /// Coulomb's law directly (the condensed path) hands to the history.
    pub fn set_friction_multipliers(
        &self,
        reference: &[[f64; 3]],
        t: f64,
        x: &[f64],
        states: &mut [NodeContactState],
        tractions: &[(Vector3<f64>, Vector3<f64>)],
    ) {
        let ctx = ContactContext {
            reference,
            t,
            x,
            first_multiplier: 0,
        };
        let mut histories = Vec::with_capacity(self.nodes.len());
        with_producer!(self, &ctx, self.reads_derivatives(false), p => {
            self.for_each_node(p, &ctx, |i| states[i], |node, state, _| {
                let (traction, normal) = &tractions[node.index];
                let response = TangentialResponse {
                    traction: *traction,
                    ..TangentialResponse::none()
                };
                histories.push(p.augment(node, &state.friction, Some((&response, normal))));
            });
        });
        for (state, history) in states.iter_mut().zip(histories) {
            state.friction = history;
        }
    }

    /// Every secondary node's [`ConstraintRow`] at time `t` and unknowns
    /// `x` (`None` for a node with no primary within the search margin),
    /// with the nodes' states where given (a deformable interface then uses
    /// each node's kept triangle, as the assembly does).
    pub fn constraint_rows(
        &self,
        reference: &[[f64; 3]],
        t: f64,
        x: &[f64],
        states: Option<&[NodeContactState]>,
    ) -> Vec<Option<ConstraintRow>> {
        self.constraint_rows_with(reference, t, x, states, Derivatives::With)
    }

    /// [`constraint_rows`](Self::constraint_rows), a dual mortar
    /// producer's rows with `derivatives` or without
    /// ([`Derivatives::Without`]: each row's gap, normal, area `D_j`,
    /// primary weights and force direction, [`ConstraintRow::force`], its
    /// `node_gradients` empty). Without is what the frictionless condensed
    /// path reads; the other producers' rows are complete either way
    /// (their `∇g` is their force direction).
    pub fn constraint_rows_with(
        &self,
        reference: &[[f64; 3]],
        t: f64,
        x: &[f64],
        states: Option<&[NodeContactState]>,
        derivatives: Derivatives,
    ) -> Vec<Option<ConstraintRow>> {
        let ctx = ContactContext {
            reference,
            t,
            x,
            first_multiplier: 0,
        };
        let mut rows = Vec::with_capacity(self.nodes.len());
        with_producer!(self, &ctx, derivatives, p => {
            let state_of = |i| {
                states.map_or_else(|| NodeContactState::initial(&self.law_at(i), p.open_gap()), |s| s[i])
            };
            self.for_each_node(p, &ctx, state_of, |node, _, k| {
                rows.push(k.map(|k| ConstraintRow {
                    gap: k.gap,
                    normal: k.normal,
                    area: k.area.unwrap_or(self.areas[node.index]),
                    node: node.mesh_node,
                    primary: k.primary.clone(),
                    node_gradients: row_gradients(&k, derivatives),
                    relative_position: p.relative_position(node),
                    facet: k.facet,
                    force: k.lever.as_ref().map(|b| force_vectors(&k.nodes, b.as_slice())),
                    lever: p.lever_weights(&k),
                }));
            });
        });
        rows
    }

    /// Whether the rows follow projections on a primary surface of
    /// another body (node-to-surface between bodies: each row exact at
    /// fixed projection, [`ConstraintRow`]; dual mortar between bodies:
    /// at fixed segmentation, `D`, `M` and normals).
    pub fn projected_gap(&self) -> bool {
        matches!(self.primary, Primary::Surface(_) | Primary::Mortar(_))
    }

    /// Whether the rows move with the unknowns and are each exact only at
    /// the point they were taken (a solve on them repeats at its answer
    /// until they settle): between bodies ([`Self::projected_gap`]), and
    /// against a rigid sphere or cylinder, whose normal `n(x_s)` turns
    /// with the node's position (`∇g = n` on the secondary node alone, the
    /// lever `B = I`), and against a triangulated surface, flat or curved,
    /// whose normal turns from facet to facet: each node on the triangle
    /// the facet choice keeps
    /// ([`TriangulatedSurface::project_keeping`](crate::contact::triangulated::TriangulatedSurface::project_keeping):
    /// the last converged increment's while the node is over it within the
    /// sticky band, as on a deformable primary surface), so that Newton's
    /// iterates and the rounds read the same face at the answer.
    pub fn rows_move(&self) -> bool {
        self.projected_gap()
            || matches!(
                &self.primary,
                Primary::Rigid(
                    RigidObstacle::Sphere { .. }
                        | RigidObstacle::Cylinder { .. }
                        | RigidObstacle::Triangulated(_)
                )
            )
    }

    /// Whether every node's area is the fixed tributary `A_s` (`false`:
    /// dual mortar's `D_j`, integrated over the current surface, so that
    /// a penalty's force `D_j ε ⟨−g⟩` is not affine in the unknowns).
    pub fn fixed_area(&self) -> bool {
        !matches!(self.primary, Primary::Mortar(_) | Primary::MortarRigid(_))
    }

    /// `Ok` where every node's gap is affine in the unknowns everywhere
    /// (`g = g(0) + ∇g · u` with one `∇g`: a rigid plane, node-to-surface
    /// or dual mortar, whose `g_j = Σ_k R_jk g(x_k)` there), else what the
    /// primary is, in words ("is against a sphere, …").
    pub fn affine_gap(&self) -> Result<(), String> {
        let obstacle = match &self.primary {
            Primary::Rigid(obstacle) => obstacle,
            Primary::MortarRigid(m) => &m.obstacle,
            Primary::Mortar(_) => {
                return Err(
                    "uses discretisation = \"mortar\" between two bodies (its gap \
                            follows the segmentation on the primary surface)"
                        .into(),
                )
            }
            // a primary surface (and any primary kind added later)
            _ => {
                return Err(
                    "is between two bodies (its gap follows the projection on the \
                            primary surface)"
                        .into(),
                )
            }
        };
        let curved = match obstacle {
            RigidObstacle::Plane { .. } => return Ok(()),
            RigidObstacle::Sphere { .. } => "sphere",
            RigidObstacle::Cylinder { .. } => "cylinder",
            _ => "triangulated surface",
        };
        Err(format!(
            "is against a {curved}, whose gap is not linear in the displacement"
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::laws::NormalLaw;
    use crate::contact::setup::Enforcement;
    use crate::mesh::structured::box_mesh;
    use crate::mesh::ElementKind;

    /// The row's `∇g = Bᵀn` is the driver's gap derivative: a central
    /// difference (`h = 1e-6`) of [`ContactInterface::gaps`] along each of
    /// the node's unknowns equals it to 1e-8, on an oblique rigid plane
    /// (affine) and on a sphere (curved), at a displaced state; the row's
    /// gap is the driver's.
    #[test]
    fn row_gradient_is_the_gap_derivative() {
        let mesh = box_mesh(ElementKind::Hex8, [2, 2, 1], [1.0, 1.0, 0.5]);
        let enforcement = Enforcement::from(NormalLaw::Penalty { epsilon: 1.0 });
        let normal = Vector3::new(0.3, -0.2, 1.0).normalize();
        let obstacles = [
            RigidObstacle::plane(Vector3::new(0.0, 0.0, -0.1), normal).unwrap(),
            RigidObstacle::sphere(Vector3::new(0.5, 0.5, -2.0), 1.9).unwrap(),
        ];
        let n = 3 * mesh.num_nodes();
        let x: Vec<f64> = (0..n).map(|i| 0.01 * ((7 * i % 5) as f64 - 2.0)).collect();
        for (o, obstacle) in obstacles.into_iter().enumerate() {
            let c = ContactInterface::rigid(&mesh, "zmin", obstacle, &enforcement).unwrap();
            assert_eq!(c.affine_gap().is_ok(), o == 0);
            assert_eq!(c.rows_move(), o == 1);
            let rows = c.constraint_rows(&mesh.nodes, 0.0, &x, None);
            let gaps = c.gaps(&mesh.nodes, 0.0, &x, None);
            for (i, row) in rows.iter().enumerate() {
                let row = row.as_ref().expect("a rigid obstacle always projects");
                assert_eq!(row.gap, gaps[i]);
                assert_eq!(row.area, c.areas[i]);
                let gradient = row.gradient();
                for d in 0..3 {
                    let dof = 3 * row.node + d;
                    let h = 1e-6;
                    let (mut plus, mut minus) = (x.clone(), x.clone());
                    plus[dof] += h;
                    minus[dof] -= h;
                    let g = |x: &[f64]| c.gaps(&mesh.nodes, 0.0, x, None)[i];
                    let fd = (g(&plus) - g(&minus)) / (2.0 * h);
                    let exact = gradient.iter().find(|e| e.0 == dof).map_or(0.0, |e| e.1);
                    assert!(
                        (fd - exact).abs() < 1e-8,
                        "node {i} dof {d}: {fd} vs {exact}"
                    );
                }
                assert_eq!(row.lever_row(1), vec![(3 * row.node + 1, 1.0)]);
            }
        }
    }
}
