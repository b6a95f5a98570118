//! Dual mortar contact between two deformable bodies (issue 28; Coulomb
//! friction in [`mortar_friction`](super::mortar_friction)), a gap producer of the node driver beside
//! [`surface_contact`](super::surface_contact): the kernels of
//! [`mortar`](super::mortar) give `D`, `M` and the averaged nodal normals;
//! [`MortarSurfaces`] pairs and integrates the faces, and [`MortarGap`]
//! (`mortar_contact/gap.rs`) turns one secondary node's row of them into
//! the [`GapKinematics`](super::kinematics::GapKinematics) the driver's
//! chain rule reads.
//!
//! ## The node's gap and lever (Popp, Gee & Wall 2009)
//! Secondary node `j` with dual multiplier `λ_j`, weighted gap
//! `g̃_j = n_jᵀ (Σ_l M_jl x_l − D_j x̃_j)` (`x̃_j = Σ_k R_jk x_k`, the
//! quadratic basis transformation; `R = I` on linear faces). The normal law
//! is evaluated per node on the area `A_j = D_j` and the normalised gap
//! `g_j = g̃_j / D_j`, so its automatic parameters `E/h` and the reported
//! `contact_pressure = λ_j` keep their node-to-surface meaning. The force
//! on the nodes is Popp's `−λ_j b_j`, with `b_j = −∂g̃_j/∂x` at fixed `D`,
//! `M`, `n` (`D_j R_jk n_j` on secondary node `k`, `−M_jl n_j` on primary
//! node `l`: [`MortarCoupling::contact_forces`](super::mortar::MortarCoupling::contact_forces)).
//! The driver's lever is `−b_j / D_j`, so that its force `A_j t_N lever`
//! is that force; the constraint row is the normalised gap's complete
//! linearisation, and the lever's derivative the one at constant area:
//! ```text
//! ∇g_j = (∇g̃_j − g_j ∇D_j) / D_j,      ∂lever/∂q = −(∂b_j/∂x) / D_j,
//! ```
//! with `∇g̃_j`, `∇D_j`, `∂b_j/∂x` from [`mortar_rows`] (every derivative of
//! `D`, `M`, `n` and the segmentation: Popp, Gitterle, Gee & Wall 2010).
//! The area's own change drops out of the residual's derivative exactly:
//! `∂(A t_N lever) = A (∂t_N/∂g) lever ∇gᵀ − t_N ∂b_j/∂x`, since
//! `A lever = −b_j`. The multiplier row `r_λ = A c(g, λ)` takes the
//! area's change too, `∂r_λ/∂q = (∂r_λ/∂g) ∇g + (r_λ/A) ∇D_j`
//! ([`GapKinematics::area_gradient`](super::kinematics::GapKinematics::area_gradient); active, `r_λ = −k g̃_j`), so
//! Newton's tangent is complete.

//! ## Search
//! Candidate face pairs from a bounding-box search (an R*-tree, the `rstar`
//! crate): each primary face's box grown by `2 h_f + 2 d` (`h_f` its size,
//! `d` the largest motion over the last increment, at the run's first
//! on Newton's path the largest prescribed motion, as
//! [`primary`](super::primary)'s rule), paired with every secondary face
//! whose box it meets; refreshed at the start of each increment, so the
//! sparsity pattern holds through it.
//!
//! A secondary node with `D_j ≤ 0` (no segment yet: beyond the primary
//! surface, or only partly over it with a negative dual integral) is open
//! at the search margin, and so is a node whose faces are less than half
//! covered, `D_j < ½ ∫ Ñ_j dA`: the dual basis is signed, so on a partly
//! covered support `M_jl / D_j` are not a partition's weights and
//! `g̃_j / D_j` extrapolates far beyond the node (an edge node of a
//! contact cap read −1e-2 for a true gap of +1e-3). The threshold is our
//! choice, not Popp et al.'s; a consistent dual basis on the covered part
//! (Cichosz & Bischoff 2011) is the published remedy, not done yet.
//! Either way the node has no row, and a node without support is inactive
//! whatever its multiplier (Hüeber & Wohlmuth 2005: the law's inactive
//! branch, [`Support::Unsupported`](super::laws::Support)), not active at
//! the margin with a zero multiplier row.
//!
//! After Newton converged, [`MortarSurfaces::pairs_hold`] searches again
//! at the converged state: where the pairs it adds change a node's gap
//! (bodies that started apart and closed within the increment), the
//! stepper searches again with the pairs a search at that answer finds
//! added ([`MortarSurfaces::refresh`]'s `reached`) and solves the
//! increment again, and cuts it only if that answer leaves them too.

use super::kinematics::current_position;
use super::mortar::{
    mortar_row_values, mortar_rows, Derivatives, FaceIntegrals, FaceShape, MortarCoupling,
    MortarRow, RowValues, SurfaceFace,
};
use crate::mesh::{FacetKind, Mesh};
use nalgebra::Vector3;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{RTree, AABB};
use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

mod gap;
mod row_cache;
pub use gap::MortarGap;
pub(crate) use gap::{row_gaps, RowSource};
use row_cache::RowCache;
pub use row_cache::RowCounts;

/// The two surfaces of a mortar interface and their candidate face pairs.
#[derive(Clone, Debug)]
pub struct MortarSurfaces {
    /// The primary surface set's name.
    pub primary_surface: String,
    /// The secondary surface's faces (global node numbers).
    pub secondary_faces: Vec<SurfaceFace>,
    /// The primary surface's faces.
    pub primary_faces: Vec<SurfaceFace>,
    /// The primary surface's nodes (sorted).
    pub primary_nodes: Vec<usize>,
    /// Per secondary node (the interface's order), the secondary faces
    /// that hold it.
    pub node_faces: Vec<Vec<usize>>,
    /// Per secondary face, the candidate primary faces (refreshed by
    /// [`refresh`](Self::refresh)).
    pub candidates: Vec<Vec<usize>>,
    /// The primary surface's element size (square root of its mean face
    /// area in the reference configuration).
    pub element_size: f64,
    /// The search margin of the last refresh: the gap reported for a node
    /// without a segment.
    pub margin: f64,
    /// Every node of either surface's faces (sorted): the coordinates the
    /// rows depend on.
    surface_nodes: Vec<usize>,
    /// The rows of the last configurations ([`RowCache`]).
    cache: RowCache,
    /// The secondary faces' `∫ Ñ_j dA` in the reference configuration
    /// ([`FaceIntegrals`]: the nodes' areas at set-up, read again where a
    /// face has not moved).
    pub(crate) face_integrals: FaceIntegrals,
    /// With friction, `D` and `M` at the last converged configuration
    /// (the covered rows there, taken at each [`refresh`](Self::refresh)),
    /// which the weighted slip is measured against
    /// ([`mortar_friction`](super::mortar_friction)); `None` without
    /// friction.
    pub committed: Option<MortarCoupling>,
}

/// The producer's rows per secondary node (those covered, see "Search").
pub type MortarRows = BTreeMap<usize, MortarRow>;

/// The face shape of a mesh facet (same node order).
fn face_shape(kind: FacetKind) -> FaceShape {
    match kind {
        FacetKind::Tri3 => FaceShape::Tri3,
        FacetKind::Quad4 => FaceShape::Quad4,
        FacetKind::Tri6 => FaceShape::Tri6,
        FacetKind::Quad8 => FaceShape::Quad8,
    }
}

/// The faces of surface set `name` of `mesh`; `None` without that set.
pub(crate) fn surface_faces(mesh: &Mesh, name: &str) -> Option<Vec<SurfaceFace>> {
    let set = mesh.surface(name)?;
    Some(
        set.facets
            .iter()
            .map(|f| SurfaceFace {
                shape: face_shape(f.kind),
                nodes: f.nodes.clone(),
            })
            .collect(),
    )
}

/// Per node of `nodes` (sorted), the indices of the `faces` that hold it.
pub(crate) fn node_faces(faces: &[SurfaceFace], nodes: &[usize]) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new(); nodes.len()];
    for (e, face) in faces.iter().enumerate() {
        for n in &face.nodes {
            if let Ok(i) = nodes.binary_search(n) {
                out[i].push(e);
            }
        }
    }
    out
}

impl MortarSurfaces {
    /// Surface set `secondary` of `mesh` (its nodes `nodes`, sorted)
    /// against surface set `primary`, paired in the reference
    /// configuration; `None` if the mesh lacks either set.
    pub fn from_mesh(mesh: &Mesh, secondary: &str, primary: &str, nodes: &[usize]) -> Option<Self> {
        let secondary_faces = surface_faces(mesh, secondary)?;
        let primary_faces = surface_faces(mesh, primary)?;
        let node_faces = node_faces(&secondary_faces, nodes);
        let primary_nodes = mesh.surface_nodes(mesh.surface(primary)?);
        let reference = coordinates(&mesh.nodes, &vec![0.0; 3 * mesh.num_nodes()]);
        let area: f64 = primary_faces
            .iter()
            .map(|f| face_size(f, &reference).powi(2))
            .sum();
        let element_size = (area / primary_faces.len().max(1) as f64).sqrt();
        let mut surface_nodes: Vec<usize> = (secondary_faces.iter().chain(&primary_faces))
            .flat_map(|f| f.nodes.iter().copied())
            .collect();
        surface_nodes.sort_unstable();
        surface_nodes.dedup();
        let face_integrals = FaceIntegrals::of(&secondary_faces, &reference);
        let mut out = Self {
            primary_surface: primary.to_string(),
            secondary_faces,
            primary_faces,
            primary_nodes,
            node_faces,
            candidates: Vec::new(),
            element_size,
            margin: 2.0 * element_size,
            surface_nodes,
            cache: RowCache::default(),
            face_integrals,
            committed: None,
        };
        out.refresh(&mesh.nodes, &vec![0.0; 3 * mesh.num_nodes()], 0.0, None);
        Some(out)
    }

    /// The secondary side alone (a rigid obstacle's primary side has no
    /// faces, [`MortarObstacle`](super::mortar_rigid::MortarObstacle)): no
    /// candidates; the row cache keyed by the secondary faces' nodes.
    pub(crate) fn secondary_only(
        secondary_faces: Vec<SurfaceFace>,
        node_faces: Vec<Vec<usize>>,
        face_integrals: FaceIntegrals,
        element_size: f64,
        margin: f64,
    ) -> Self {
        let mut surface_nodes: Vec<usize> = (secondary_faces.iter())
            .flat_map(|f| f.nodes.iter().copied())
            .collect();
        surface_nodes.sort_unstable();
        surface_nodes.dedup();
        Self {
            primary_surface: String::new(),
            candidates: vec![Vec::new(); secondary_faces.len()],
            secondary_faces,
            primary_faces: Vec::new(),
            primary_nodes: Vec::new(),
            node_faces,
            element_size,
            margin,
            surface_nodes,
            cache: RowCache::default(),
            face_integrals,
            committed: None,
        }
    }

    /// Recompute the candidate face pairs at configuration `x`: each
    /// primary face's box grown by `2 h_f + 2 motion` against the
    /// secondary faces' boxes; with `reached` (the unknowns of an answer
    /// that left the last pairs) also the pairs a search there with no
    /// motion finds. Returns whether a pair changed.
    pub fn refresh(
        &mut self,
        reference: &[[f64; 3]],
        x: &[f64],
        motion: f64,
        reached: Option<&[f64]>,
    ) -> bool {
        let xs = coordinates(reference, x);
        let (mut candidates, smallest) = self.search(&xs, motion);
        if let Some(reached) = reached {
            let there = self.search(&coordinates(reference, reached), 0.0).0;
            super::primary::merge_candidates(&mut candidates, there);
        }
        let changed = candidates != self.candidates;
        if changed {
            self.cache.clear();
        }
        self.candidates = candidates;
        if smallest.is_finite() {
            self.margin = smallest.max(1e-3 * self.element_size);
        }
        self.commit_coupling(&xs);
        changed
    }

    /// Per secondary face, the primary faces whose box grown by
    /// `2 h_f + 2 motion` meets its box at coordinates `xs`; and the
    /// smallest positive growth.
    fn search(&self, xs: &[Vector3<f64>], motion: f64) -> (Vec<Vec<usize>>, f64) {
        let mut smallest = f64::INFINITY;
        let tree = RTree::bulk_load(
            self.primary_faces
                .iter()
                .enumerate()
                .map(|(p, face)| {
                    let margin = 2.0 * face_size(face, xs) + 2.0 * motion;
                    if margin > 0.0 {
                        smallest = smallest.min(margin);
                    }
                    let (lo, hi) = face_box(face, xs, margin);
                    GeomWithData::new(Rectangle::from_corners(lo, hi), p)
                })
                .collect(),
        );
        let candidates = self
            .secondary_faces
            .iter()
            .map(|face| {
                let (lo, hi) = face_box(face, xs, 0.0);
                let mut found: Vec<usize> = tree
                    .locate_in_envelope_intersecting(AABB::from_corners(lo, hi))
                    .map(|p| p.data)
                    .collect();
                found.sort_unstable();
                found
            })
            .collect();
        (candidates, smallest)
    }

    /// Whether the candidate pairs of the increment's start still give
    /// every secondary node the gap a fresh search at unknowns `x` would
    /// (the same normalised gap `g̃_j/D_j` to 1e-9 of the element size, or
    /// open either way), as [`PrimarySurface`](super::primary)'s pairs
    /// must hold: otherwise the stepper cuts the increment, and the next
    /// search grows with the motion. The gaps are the rows' values
    /// ([`mortar_row_values`]) with the pairs used and with those and the
    /// fresh ones, read only for the nodes of the secondary faces that have
    /// a fresh pair (every other node's row has the same pairs either way)
    /// and from the pairs of the faces that hold those nodes.
    pub fn pairs_hold(&self, reference: &[[f64; 3]], x: &[f64]) -> bool {
        let xs = coordinates(reference, x);
        let (fresh, _) = self.search(&xs, 0.0);
        let used = self.pairs();
        let mut all = used.clone();
        for (s, (now, before)) in fresh.iter().zip(&self.candidates).enumerate() {
            all.extend(now.iter().filter(|p| !before.contains(p)).map(|&p| (s, p)));
        }
        if all.len() == used.len() {
            return true;
        }
        // only the nodes of the faces with a new pair can see another gap:
        // their rows whole, from every pair of the faces that hold them
        let affected: BTreeSet<usize> = (all[used.len()..].iter())
            .flat_map(|&(s, _)| self.secondary_faces[s].nodes.iter().copied())
            .collect();
        let gaps = |pairs: &[(usize, usize)]| {
            self.covered_gaps(&self.pairs_holding(pairs, &affected), &xs)
        };
        let (Some(before), Some(now)) = (gaps(&used), gaps(&all)) else {
            return false;
        };
        let tolerance = 1e-9 * self.element_size;
        let open = self.margin;
        let holds = affected.iter().all(|n| {
            let a = before.get(n).copied().unwrap_or(open);
            let b = now.get(n).copied().unwrap_or(open);
            (a - b).abs() <= tolerance || (a > 0.0 && b > 0.0)
        });
        holds
    }

    /// The face `pairs` whose secondary face holds one of the mesh nodes
    /// `nodes`, in their order: every pair of those nodes' rows, so that
    /// each of those rows is the one all the pairs give, to the bit.
    fn pairs_holding(
        &self,
        pairs: &[(usize, usize)],
        nodes: &BTreeSet<usize>,
    ) -> Vec<(usize, usize)> {
        (pairs.iter().copied())
            .filter(|&(s, _)| (self.secondary_faces[s].nodes.iter()).any(|n| nodes.contains(n)))
            .collect()
    }

    /// The normalised gap `g̃_j/D_j` of every covered secondary node
    /// (see "Search") from the face `pairs` at coordinates `xs`; `None`
    /// where a face cannot be integrated.
    fn covered_gaps(
        &self,
        pairs: &[(usize, usize)],
        xs: &[Vector3<f64>],
    ) -> Option<BTreeMap<usize, f64>> {
        let values =
            mortar_row_values(&self.secondary_faces, &self.primary_faces, pairs, xs).ok()?;
        let full = self.full_integrals(xs);
        Some(
            values
                .into_iter()
                .filter(|r| r.d > 0.0 && covered(r.d, full.get(&r.node)))
                .map(|r| (r.node, r.weighted_gap / r.d))
                .collect(),
        )
    }

    /// What leaves secondary nodes open at unknowns `x` because their
    /// face pairs cannot be integrated ([`covered_rows`](Self::covered_rows)
    /// filters them out without a word), for the report's warning: a face
    /// the kernels refuse ([`mortar_row_values`]' error: a degenerate face,
    /// a projection that fails) leaves every node of the interface open; a
    /// face whose integrals are not finite (one folded onto a line has no
    /// normal: NaN, not an error) leaves its nodes open. `None` where every
    /// row is finite.
    pub fn integration_failure(&self, reference: &[[f64; 3]], x: &[f64]) -> Option<String> {
        let rows = match self.row_values(reference, x) {
            Err(e) => {
                let n = self.node_faces.len();
                return Some(format!(
                    "a mortar face pair cannot be integrated ({e}); all {n} secondary \
                     nodes of the interface are left open, with no contact force"
                ));
            }
            Ok(rows) => rows,
        };
        let finite = |r: &RowValues| {
            r.d.is_finite() && r.weighted_gap.is_finite() && r.m.iter().all(|m| m.1.is_finite())
        };
        let bad = rows.iter().filter(|r| !finite(r)).count();
        (bad > 0).then(|| {
            format!(
                "the mortar integrals of {bad} secondary nodes are not finite (a degenerate \
                 face, e.g. one folded onto a line); those nodes are left open, with no \
                 contact force"
            )
        })
    }

    /// The candidate (secondary face, primary face) pairs.
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        self.candidates
            .iter()
            .enumerate()
            .flat_map(|(s, ps)| ps.iter().map(move |&p| (s, p)))
            .collect()
    }

    /// The mesh nodes secondary node `i`'s weighted gap may couple in this
    /// increment: the nodes of its faces (the normal, the transformation)
    /// and of their candidate primary faces (`M`); the node itself first.
    pub fn coupled_nodes(&self, i: usize, node: usize) -> Vec<usize> {
        let mut nodes = vec![node];
        for &e in &self.node_faces[i] {
            nodes.extend(&self.secondary_faces[e].nodes);
            for &p in &self.candidates[e] {
                nodes.extend(&self.primary_faces[p].nodes);
            }
        }
        nodes[1..].sort_unstable();
        let mut seen = std::collections::HashSet::new();
        nodes.retain(|n| seen.insert(*n));
        nodes
    }

    /// The areas `A_j` of the secondary `nodes` in the reference
    /// configuration of `mesh`: `∫ Ñ_j dA` over each node's faces, the
    /// `D_j` of a fully covered node ([`node_integrals`](super::mortar::node_integrals), as the coverage
    /// test reads it; 0 at a node on no face). Not the reference `D_j`
    /// itself: where the bodies start apart, the first search pairs only
    /// the faces within its margin, and the two spheres' contact edge read
    /// 6 % too little area that way.
    pub fn reference_areas(&self, mesh: &Mesh, nodes: &[usize]) -> Option<Vec<f64>> {
        let xs = coordinates(&mesh.nodes, &vec![0.0; 3 * mesh.num_nodes()]);
        let full = self.full_integrals(&xs);
        Some(
            nodes
                .iter()
                .map(|n| full.get(n).copied().unwrap_or(0.0))
                .collect(),
        )
    }

    /// The rows' values at unknowns `x` (`g̃_j`, `D_j`, `M_jl`, `n_j` of
    /// every node a segment reaches, [`mortar_row_values`]: no
    /// derivatives, not filtered by coverage).
    pub fn row_values(
        &self,
        reference: &[[f64; 3]],
        x: &[f64],
    ) -> Result<Vec<RowValues>, super::mortar::MortarError> {
        let xs = coordinates(reference, x);
        mortar_row_values(
            &self.secondary_faces,
            &self.primary_faces,
            &self.pairs(),
            &xs,
        )
    }

    /// The producer's rows at unknowns `x`: every covered secondary node's
    /// [`MortarRow`] with its derivatives (see [`MortarGap::at`]), from the
    /// cache where this configuration was integrated last or the one
    /// before.
    pub fn rows_at(&self, reference: &[[f64; 3]], x: &[f64]) -> Arc<MortarRows> {
        self.rows_at_coordinates(&coordinates(reference, x), Derivatives::With)
    }

    /// The covered rows at the nodes' current coordinates `xs`, with their
    /// derivatives or without (`derivatives`), through the row cache.
    pub fn rows_at_coordinates(
        &self,
        xs: &[Vector3<f64>],
        derivatives: Derivatives,
    ) -> Arc<MortarRows> {
        self.cached_rows(xs, &[], derivatives, || self.covered_rows(xs, derivatives))
    }

    /// The rows at coordinates `xs` and the further parameters `extra`
    /// (a rigid obstacle's translation) with at least `derivatives`, from
    /// the row cache keyed by the surfaces' nodes' coordinates and `extra`,
    /// or from `integrate`: the one cache of the deformable and the rigid
    /// producers.
    pub(crate) fn cached_rows(
        &self,
        xs: &[Vector3<f64>],
        extra: &[f64],
        derivatives: Derivatives,
        integrate: impl FnOnce() -> MortarRows,
    ) -> Arc<MortarRows> {
        self.cache
            .rows(self.cache_key(xs, extra), derivatives, integrate)
    }

    /// The rows at coordinates `xs` and `extra` where the row cache holds
    /// them (not counted as asked for), else `None`.
    pub(crate) fn cached(&self, xs: &[Vector3<f64>], extra: &[f64]) -> Option<Arc<MortarRows>> {
        self.cache.peek(&self.cache_key(xs, extra))
    }

    /// The row cache's key: the surfaces' nodes' coordinates, then `extra`.
    fn cache_key(&self, xs: &[Vector3<f64>], extra: &[f64]) -> Vec<f64> {
        (self.surface_nodes.iter())
            .flat_map(|&n| [xs[n].x, xs[n].y, xs[n].z])
            .chain(extra.iter().copied())
            .collect()
    }

    /// How often the producer asked for rows and how often it integrated
    /// them, since this interface was built (or cloned).
    pub fn row_counts(&self) -> RowCounts {
        self.cache.counts()
    }

    /// Count one evaluation of the gaps without derivatives.
    pub(crate) fn count_values(&self) {
        self.cache.count_values();
    }

    /// Every covered node's row at `coordinates`: `D_j ≥ ½ ∫ Ñ_j dA` over
    /// its faces (see the module docs, "Search"). A face the kernels cannot
    /// integrate leaves every node open (the report warns:
    /// [`integration_failure`](Self::integration_failure)).
    fn covered_rows(&self, coordinates: &[Vector3<f64>], derivatives: Derivatives) -> MortarRows {
        self.covered_rows_of(&self.pairs(), coordinates, derivatives)
    }

    /// The covered rows of the secondary mesh nodes `near` alone at
    /// coordinates `xs`, from the pairs of the faces that hold them
    /// ([`pairs_holding`](Self::pairs_holding)): each the row of
    /// [`rows_at_coordinates`](Self::rows_at_coordinates) to the bit, at
    /// the cost of those faces' segments; not cached (a reading of the
    /// nodes near contact, [`MortarGap::near`]).
    pub(crate) fn rows_near(
        &self,
        xs: &[Vector3<f64>],
        near: &BTreeSet<usize>,
        derivatives: Derivatives,
    ) -> MortarRows {
        let pairs = self.pairs_holding(&self.pairs(), near);
        let mut rows = self.covered_rows_of(&pairs, xs, derivatives);
        rows.retain(|n, _| near.contains(n));
        rows
    }

    /// [`covered_rows`](Self::covered_rows) from the face `pairs`.
    fn covered_rows_of(
        &self,
        pairs: &[(usize, usize)],
        coordinates: &[Vector3<f64>],
        derivatives: Derivatives,
    ) -> MortarRows {
        let rows = mortar_rows(
            &self.secondary_faces,
            &self.primary_faces,
            pairs,
            coordinates,
            derivatives,
        )
        .unwrap_or_default();
        let full = self.full_integrals(coordinates);
        rows.into_iter()
            .filter(|r| covered(r.d, full.get(&r.node)))
            .map(|r| (r.node, r))
            .collect()
    }

    /// `∫ Ñ_j dA` over all secondary faces of every node `j` (a fully
    /// covered node's `D_j`, [`node_integrals`](super::mortar::node_integrals)) at the current
    /// `coordinates` (a face where the reference integrals were taken read
    /// from them, [`FaceIntegrals`]); a face that cannot be formed adds
    /// nothing.
    pub(crate) fn full_integrals(&self, coordinates: &[Vector3<f64>]) -> BTreeMap<usize, f64> {
        let faces = &self.secondary_faces;
        let mut out = BTreeMap::new();
        for (e, face) in faces.iter().enumerate() {
            let Ok(integrals) = self.face_integrals.at(faces, e, coordinates) else {
                continue;
            };
            for (&n, v) in face.nodes.iter().zip(integrals) {
                *out.entry(n).or_insert(0.0) += v;
            }
        }
        out
    }
}

/// Whether a node with `D_j = d` takes part: `D_j ≥ ½ ∫ Ñ_j dA` over its
/// faces (`full`; see the module docs, "Search").
fn covered(d: f64, full: Option<&f64>) -> bool {
    d >= 0.5 * full.copied().unwrap_or(0.0)
}

/// Current positions `X + u` of every mesh node.
pub(crate) fn coordinates(reference: &[[f64; 3]], x: &[f64]) -> Vec<Vector3<f64>> {
    (0..reference.len())
        .map(|n| current_position(reference, x, n))
        .collect()
}

/// A face's size: the square root of its corners' polygon area (the
/// diagonals' cross product).
pub(crate) fn face_size(face: &SurfaceFace, xs: &[Vector3<f64>]) -> f64 {
    let c = |k: usize| xs[face.nodes[k]];
    let area = if face.shape.is_triangle() {
        0.5 * (c(1) - c(0)).cross(&(c(2) - c(0))).norm()
    } else {
        0.5 * (c(2) - c(0)).cross(&(c(3) - c(1))).norm()
    };
    area.sqrt()
}

/// A face's bounding box grown by `margin`.
fn face_box(face: &SurfaceFace, xs: &[Vector3<f64>], margin: f64) -> ([f64; 3], [f64; 3]) {
    let first = xs[face.nodes[0]];
    let (lo, hi) = face.nodes.iter().fold((first, first), |(lo, hi), &n| {
        (lo.inf(&xs[n]), hi.sup(&xs[n]))
    });
    let (lo, hi) = (lo.add_scalar(-margin), hi.add_scalar(margin));
    ([lo.x, lo.y, lo.z], [hi.x, hi.y, hi.z])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::kinematics::GapKinematics;
    use crate::contact::laws::{NodeContactState, NormalLaw};
    use crate::mesh::structured::box_mesh;
    use crate::mesh::{ElementKind, Mesh, Region, SurfaceSet};
    use nalgebra::Dyn;

    /// A 2 × 2 Quad4 (or Quad8) secondary patch (an upper block's bottom)
    /// over a 3 × 3 primary one (a lower block's top), the upper block
    /// warped and pressed in by `depth`: the mesh and the two surfaces.
    fn pair(kind: ElementKind) -> (Mesh, MortarSurfaces, Vec<usize>) {
        let lower = box_mesh(kind, [3, 3, 1], [1.0, 1.0, 0.5]);
        let upper = box_mesh(kind, [2, 2, 1], [1.0, 1.0, 0.5]);
        let n = lower.nodes.len();
        let mut mesh = lower.clone();
        mesh.nodes
            .extend(upper.nodes.iter().map(|x| [x[0], x[1], x[2] + 0.5]));
        mesh.node_ids = (1..=mesh.nodes.len() as u64).collect();
        mesh.regions = vec![Region {
            name: "body".into(),
            elements: vec![],
        }];
        let shifted = |s: &SurfaceSet, name: &str, by: usize| {
            let mut s = s.clone();
            s.name = name.into();
            s.facets
                .iter_mut()
                .for_each(|f| f.nodes.iter_mut().for_each(|k| *k += by));
            s
        };
        mesh.elements.clear();
        mesh.surfaces = vec![
            shifted(lower.surface("zmax").unwrap(), "primary", 0),
            shifted(upper.surface("zmin").unwrap(), "secondary", n),
        ];
        let nodes = mesh.surface_nodes(mesh.surface("secondary").unwrap());
        let surfaces = MortarSurfaces::from_mesh(&mesh, "secondary", "primary", &nodes).unwrap();
        (mesh, surfaces, nodes)
    }

    /// A configuration that warps both surfaces and presses the secondary
    /// `nodes` in by 0.03.
    fn state(mesh: &Mesh, nodes: &[usize]) -> Vec<f64> {
        let mut x: Vec<f64> = (0..3 * mesh.nodes.len())
            .map(|i| 0.005 * ((i as f64) * 0.77).sin())
            .collect();
        nodes.iter().for_each(|&n| x[3 * n + 2] -= 0.03);
        x
    }

    /// The driver's terms of a mortar node against central differences
    /// (step 1e-6) of the producer itself, whose `D`, `M`, `n` and
    /// segmentation follow the nodes: `∇g` of the normalised gap,
    /// `∂(A b)/∂q = A ∂b/∂q` of the lever at the area `A = D_j`, `∂n/∂q`,
    /// and the normal law's `r_q = f b` with its
    /// `K_qq = (∂f/∂g) b ∇gᵀ + f ∂b/∂q`, to 1e-6 of their size; on
    /// linear and quadratic faces. The differences' error is `O(h²)` with a
    /// large constant where the clip polygon has slivers (the blocks'
    /// outer edges nearly coincide): about 1e-7 at `h = 1e-6`, falling 100×
    /// per 10× smaller step; a missing term would be off by its own size.
    /// With a multiplier (Rockafellar's and the slack law, at `λ ≠ 0` off
    /// the solution, so `r_λ ≠ 0`), the multiplier row `∂r_λ/∂q`, whose
    /// `(r_λ/A) ∇D_j` the rows took in late (it vanishes with `r_λ`).
    #[test]
    fn driver_terms_match_finite_differences() {
        for kind in [ElementKind::Hex8, ElementKind::Hex20] {
            let (mesh, surfaces, nodes) = pair(kind);
            let x = state(&mesh, &nodes);
            let law = NormalLaw::Penalty { epsilon: 300.0 };
            let st = NodeContactState::initial(&law, -1.0);
            let mut checked = 0;
            for &j in nodes.iter().skip(nodes.len() / 2).take(3) {
                let p0 = MortarGap::at(&surfaces, &mesh.nodes, &x, Derivatives::With);
                let Some(row) = p0.node_row(j) else {
                    continue;
                };
                let k0 = p0.row_kinematics(j, row);
                let r0 = k0.normal_response(&law, k0.area.unwrap(), &st);
                assert!(r0.active, "{kind:?} node {j} closed");
                let lever = k0.lever.clone().unwrap();
                let h = 1e-6;
                for (a, &node) in k0.nodes.iter().enumerate() {
                    for d in 0..3 {
                        let at = |s: f64| {
                            let mut y = x.clone();
                            y[3 * node + d] += s * h;
                            let p = MortarGap::at(&surfaces, &mesh.nodes, &y, Derivatives::With);
                            let k = p.row_kinematics(j, p.node_row(j).unwrap());
                            assert_eq!(k.nodes, k0.nodes);
                            let r = k.normal_response(&law, k.area.unwrap(), &st);
                            (k, r)
                        };
                        let ((kp, rp), (km, rm)) = (at(1.0), at(-1.0));
                        let c = 3 * a + d;
                        let close = |fd: f64, exact: f64, scale: f64, what: &str| {
                            assert!(
                                (fd - exact).abs() <= 1e-6 * scale,
                                "{kind:?} node {j}, q{c} {what}: fd {fd:e} exact {exact:e}"
                            );
                        };
                        let scale = k0.gradient.amax().max(1.0);
                        close((kp.gap - km.gap) / (2.0 * h), k0.gradient[c], scale, "∇g");
                        for r in 0..k0.gradient.len() {
                            let area_lever = |k: &GapKinematics<Dyn>| {
                                k.area.unwrap() * k.lever.as_ref().unwrap()[r]
                            };
                            let fd = (area_lever(&kp) - area_lever(&km)) / (2.0 * h);
                            let (a0, scale) = (k0.area.unwrap(), lever.amax().max(1.0));
                            close(fd / a0, k0.hessian[(r, c)], scale, "∂b/∂q");
                            let fd = (rp.residual[r] - rm.residual[r]) / (2.0 * h);
                            close(fd, r0.stiffness[(r, c)], r0.stiffness.amax(), "K_qq");
                        }
                        for r in 0..3 {
                            let fd = (kp.normal[r] - km.normal[r]) / (2.0 * h);
                            close(fd, k0.normal_gradient[(r, c)], 1.0, "∂n/∂q");
                        }
                    }
                }
                checked += 1;
            }
            assert!(checked >= 2, "{kind:?}: {checked} nodes checked");
        }
    }

    /// `∂r_λ/∂q` of a mortar node (see
    /// [`driver_terms_match_finite_differences`]) against central
    /// differences of `r_λ`, for the laws with a multiplier, active and
    /// inactive; to 1e-6 of the row's size.
    #[test]
    fn multiplier_row_matches_finite_differences() {
        let (mesh, surfaces, nodes) = pair(ElementKind::Hex8);
        let x = state(&mesh, &nodes);
        let laws = [
            NormalLaw::Rockafellar { p: 300.0, k: 200.0 },
            NormalLaw::Slack { p: 300.0, k: 200.0 },
        ];
        let p0 = MortarGap::at(&surfaces, &mesh.nodes, &x, Derivatives::With);
        let mut checked = 0;
        for &j in nodes.iter().skip(nodes.len() / 2).take(3) {
            let Some(row) = p0.node_row(j) else {
                continue;
            };
            let k0 = p0.row_kinematics(j, row);
            // λ above and far below the law's switch at this gap
            for (law, lambda) in laws.iter().flat_map(|l| [(l, 0.7), (l, -5.0)]) {
                let mut st = NodeContactState::initial(law, k0.gap);
                st.lambda = lambda;
                let r0 = k0.normal_response(law, k0.area.unwrap(), &st);
                assert!(r0.r_lambda.abs() > 1e-6, "{law:?}: r_λ {}", r0.r_lambda);
                let scale = r0.multiplier_row.amax();
                for (a, &node) in k0.nodes.iter().enumerate() {
                    for d in 0..3 {
                        let h = 1e-6;
                        let r_lambda = |s: f64| {
                            let mut y = x.clone();
                            y[3 * node + d] += s * h;
                            let p = MortarGap::at(&surfaces, &mesh.nodes, &y, Derivatives::With);
                            let k = p.row_kinematics(j, p.node_row(j).unwrap());
                            k.normal_response(law, k.area.unwrap(), &st).r_lambda
                        };
                        let fd = (r_lambda(1.0) - r_lambda(-1.0)) / (2.0 * h);
                        let exact = r0.multiplier_row[3 * a + d];
                        assert!(
                            (fd - exact).abs() <= 1e-6 * scale,
                            "{law:?} λ {lambda} node {j} q{}: fd {fd:e} exact {exact:e}",
                            3 * a + d
                        );
                    }
                }
            }
            checked += 1;
        }
        assert!(checked >= 2, "{checked} nodes checked");
    }

    /// The rows of some secondary nodes alone ([`MortarSurfaces::rows_near`])
    /// are the full reading's rows of those nodes to the bit, with and
    /// without derivatives, on linear and quadratic faces: each near node's
    /// every face pair is read, in the same order.
    #[test]
    fn rows_near_are_the_full_rows_to_the_bit() {
        for kind in [ElementKind::Hex8, ElementKind::Hex20] {
            let (mesh, surfaces, nodes) = pair(kind);
            let x = state(&mesh, &nodes);
            let xs = coordinates(&mesh.nodes, &x);
            // two secondary nodes: some faces hold neither
            let near: BTreeSet<usize> = nodes.iter().take(2).copied().collect();
            for derivatives in [Derivatives::Without, Derivatives::With] {
                let all = surfaces.rows_at_coordinates(&xs, derivatives);
                let some = surfaces.rows_near(&xs, &near, derivatives);
                let expected: Vec<_> = all.iter().filter(|(n, _)| near.contains(n)).collect();
                assert_eq!(expected.len(), 2, "{kind:?}");
                assert_eq!(some.iter().collect::<Vec<_>>(), expected, "{kind:?}");
            }
            let fewer = surfaces.pairs_holding(&surfaces.pairs(), &near).len();
            assert!(fewer < surfaces.pairs().len(), "{kind:?}: every pair read");
        }
    }
}
