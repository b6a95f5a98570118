//! Frictionless dual mortar contact of a body's surface against a rigid
//! obstacle (issue 28 item 3): plane, sphere, cylinder or triangulated
//! surface, translated by the interface's `c(t)`; linear and quadratic
//! faces (Tri3, Quad4, Tri6, Quad8).
//!
//! With a rigid primary the mortar integrals need only the secondary
//! surface: each secondary face is integrated by its own rule against the
//! obstacle's gap function ([`obstacle_rows`]: `D_j`, the weighted gap
//! `g̃_j = ∫ Φ_j g(x) dA`, the lever `L_jk = ∫ Φ_j N_k n dA` and their
//! complete derivatives). The rows have the form of the deformable mortar
//! rows with no primary nodes, so the gap producer is a
//! [`MortarGap`] holding them: the driver's node kinematics, Popp's form
//! (the law on `A_j = D_j` and `g_j = g̃_j/D_j`, the force `λ_j L_jk`),
//! the output (`contact_pressure = λ_j`) and the frictionless slip frame
//! are those of [`mortar_contact`](super::mortar_contact).
//!
//! ## Which nodes are integrated
//! A node whose own point is farther from the obstacle than twice the
//! largest of its faces (in the reference configuration) is open at that
//! margin, as node-to-surface's search margin, and its faces are
//! integrated only for the nodes that are near: a node's row is complete
//! because every face that holds a near node is integrated.

use super::mortar::obstacle_rows::{
    obstacle_rows, plane_rows, transformed_point, transforms_to_itself,
};
use super::mortar::Derivatives;
use super::mortar::FaceIntegrals;
use super::mortar_contact::{coordinates, face_size, node_faces, surface_faces};
use super::mortar_contact::{
    row_gaps, MortarGap, MortarRows, MortarSurfaces, RowCounts, RowSource,
};
use super::obstacle::RigidObstacle;
use super::projection::Projection;
use crate::mesh::Mesh;
use nalgebra::Vector3;
use std::collections::BTreeMap;
use std::sync::Arc;

/// A secondary surface against a rigid obstacle through dual mortar.
#[derive(Clone, Debug)]
pub struct MortarObstacle {
    /// The obstacle in its initial position.
    pub obstacle: RigidObstacle,
    /// The secondary surface as mortar surfaces without a primary side
    /// (its faces, the faces of each node; `margin` the smallest of
    /// `node_margins`).
    pub surfaces: MortarSurfaces,
    /// The secondary nodes (sorted mesh nodes, the interface's order).
    pub nodes: Vec<usize>,
    /// Per node, the gap beyond which it is open: twice the largest size
    /// of its faces in the reference configuration.
    pub node_margins: Vec<f64>,
}

impl MortarObstacle {
    /// Surface set `secondary` of `mesh` (its nodes `nodes`, sorted)
    /// against `obstacle`; `None` if the mesh has no such set.
    pub fn from_mesh(
        mesh: &Mesh,
        secondary: &str,
        nodes: &[usize],
        obstacle: RigidObstacle,
    ) -> Option<Self> {
        let faces = surface_faces(mesh, secondary)?;
        let node_faces = node_faces(&faces, nodes);
        let reference = coordinates(&mesh.nodes, &vec![0.0; 3 * mesh.num_nodes()]);
        let sizes: Vec<f64> = faces.iter().map(|f| face_size(f, &reference)).collect();
        let node_margins: Vec<f64> = node_faces
            .iter()
            .map(|fs| 2.0 * fs.iter().map(|&e| sizes[e]).fold(0.0, f64::max))
            .collect();
        let mean = (sizes.iter().map(|s| s * s).sum::<f64>() / sizes.len().max(1) as f64).sqrt();
        let margin = node_margins
            .iter()
            .copied()
            .filter(|m| *m > 0.0)
            .fold(f64::INFINITY, f64::min);
        let margin = if margin.is_finite() { margin } else { mean };
        let integrals = FaceIntegrals::of(&faces, &reference);
        let surfaces = MortarSurfaces::secondary_only(faces, node_faces, integrals, mean, margin);
        Some(Self {
            obstacle,
            surfaces,
            nodes: nodes.to_vec(),
            node_margins,
        })
    }

    /// `D_j = ∫ Ñ_j dA` of every secondary node in the reference
    /// configuration of `mesh` (the nodes' areas `A_j`; the faces'
    /// integrals taken when the surfaces were made).
    pub fn reference_areas(&self, mesh: &Mesh) -> Vec<f64> {
        let xs = coordinates(&mesh.nodes, &vec![0.0; 3 * mesh.num_nodes()]);
        let d = self.surfaces.full_integrals(&xs);
        self.nodes
            .iter()
            .map(|n| d.get(n).copied().unwrap_or(0.0))
            .collect()
    }

    /// The mesh nodes secondary node `i`'s row couples: itself first, then
    /// the nodes of its faces.
    pub fn coupled_nodes(&self, i: usize) -> Vec<usize> {
        self.surfaces.coupled_nodes(i, self.nodes[i])
    }

    /// The groups of mesh nodes whose displacements secondary node `i`'s
    /// tangent couples with each other (each group one clique of the
    /// sparsity pattern). Against a plane at a node with `x̃_j = x_j`
    /// ([`transforms_to_itself`]) the lever is `L_jk = D_j δ_jk n` in
    /// every configuration (biorthogonality), so the tangent couples the
    /// node with each node of its faces and no two others: one pair each
    /// (the elements' couplings already, where the elements are all
    /// assembled here). Otherwise `∂L_jk/∂x_m` couples every two nodes of
    /// its faces: [`coupled_nodes`](Self::coupled_nodes), one group.
    pub fn coupled_groups(&self, i: usize) -> Vec<Vec<usize>> {
        let nodes = self.coupled_nodes(i);
        let faces = &self.surfaces.secondary_faces;
        let on_itself = (self.surfaces.node_faces[i].first())
            .is_some_and(|&e| transforms_to_itself(&faces[e], self.nodes[i]));
        match (&self.obstacle, on_itself) {
            (RigidObstacle::Plane { .. }, true) => {
                nodes[1..].iter().map(|&m| vec![nodes[0], m]).collect()
            }
            _ => vec![nodes],
        }
    }

    /// The rows of the near nodes (module docs) at the nodes' current
    /// coordinates `xs` with the obstacle translated by `translation`:
    /// every node's `D_j`, `g̃_j`, lever and normal, with their derivatives
    /// or without ([`Derivatives`]; without, against a plane, in closed
    /// form, [`plane_rows`]), keyed by mesh node. A face the kernels
    /// cannot integrate (degenerate) leaves every node open in this
    /// evaluation; the element assembly reports such a face's element.
    pub fn rows(
        &self,
        translation: &Vector3<f64>,
        xs: &[Vector3<f64>],
        derivatives: Derivatives,
    ) -> MortarRows {
        let project = |p: &Vector3<f64>| self.obstacle.project(&(p - translation));
        let near = self.near(xs, &project);
        let selected = self.faces_of(&near);
        let faces = &self.surfaces.secondary_faces;
        let plane = matches!(self.obstacle, RigidObstacle::Plane { .. });
        let mut rows = match (plane, derivatives) {
            (true, Derivatives::Without) => {
                let integrals = &self.surfaces.face_integrals;
                plane_rows(faces, integrals, &selected, xs, &project)
            }
            _ => obstacle_rows(faces, &selected, xs, &project, derivatives),
        }
        .unwrap_or_default();
        let near_nodes: std::collections::BTreeSet<usize> =
            near.iter().map(|&i| self.nodes[i]).collect();
        rows.retain(|n, _| near_nodes.contains(n));
        rows
    }

    /// The near nodes (indices into [`nodes`](Self::nodes), module docs)
    /// at coordinates `xs`, `project` the translated obstacle's projection.
    fn near(
        &self,
        xs: &[Vector3<f64>],
        project: &impl Fn(&Vector3<f64>) -> Projection,
    ) -> Vec<usize> {
        (0..self.nodes.len())
            .filter(|&i| project(&xs[self.nodes[i]]).gap < self.node_margins[i])
            .collect()
    }

    /// The faces that hold the nodes `near` (sorted, once each).
    fn faces_of(&self, near: &[usize]) -> Vec<usize> {
        let mut selected: Vec<usize> = near
            .iter()
            .flat_map(|&i| self.surfaces.node_faces[i].iter().copied())
            .collect();
        selected.sort_unstable();
        selected.dedup();
        selected
    }

    /// The normalised gap `g_j = g̃_j / D_j` of every near node with
    /// `D_j > 0` (mesh node to gap) at the nodes' current coordinates
    /// `xs`, the obstacle translated by `translation`: the gaps of
    /// [`rows`](Self::rows) without their derivatives, for a solve that
    /// reads only gaps. On a plane in closed form, `g_j = g(x̃_j)`
    /// ([`transformed_point`]: biorthogonality, exact to round-off), on a
    /// curved obstacle from the rows without derivatives (to the bit). A
    /// face the kernels cannot integrate leaves every node open, as the
    /// rows do.
    pub fn gap_values(
        &self,
        translation: &Vector3<f64>,
        xs: &[Vector3<f64>],
    ) -> BTreeMap<usize, f64> {
        if let RigidObstacle::Plane { .. } = self.obstacle {
            let project = |p: &Vector3<f64>| self.obstacle.project(&(p - translation));
            let near = self.near(xs, &project);
            let faces = &self.surfaces.secondary_faces;
            let gap = |i: usize| {
                let &e = self.surfaces.node_faces[i].first()?;
                let point = transformed_point(&faces[e], self.nodes[i], xs);
                Some((self.nodes[i], project(&point).gap))
            };
            return near.into_iter().filter_map(gap).collect();
        }
        row_gaps(&self.rows(translation, xs, Derivatives::Without))
    }

    /// The gap producer at unknowns `x`, the obstacle translated by
    /// `translation`: a [`MortarGap`] over [`rows`](Self::rows) with their
    /// derivatives or without (what the operation reads, [`Derivatives`];
    /// from the surfaces' row cache, keyed by the secondary nodes'
    /// coordinates and the translation, where this configuration was
    /// integrated last or the one before), its gaps alone over
    /// [`gap_values`](Self::gap_values).
    pub fn producer(
        &self,
        translation: &Vector3<f64>,
        reference: &[[f64; 3]],
        x: &[f64],
        derivatives: Derivatives,
    ) -> MortarGap<'_> {
        let source = ObstacleRows {
            obstacle: self,
            translation: *translation,
            xs: coordinates(reference, x),
        };
        MortarGap::from_source(&self.surfaces, Box::new(source), derivatives)
    }

    /// How often the producer asked for rows and how often it integrated
    /// them, since this interface was built (or cloned).
    pub fn row_counts(&self) -> RowCounts {
        self.surfaces.row_counts()
    }
}

/// A rigid obstacle's rows in one configuration: the secondary nodes'
/// current coordinates and the obstacle's translation.
struct ObstacleRows<'a> {
    obstacle: &'a MortarObstacle,
    translation: Vector3<f64>,
    xs: Vec<Vector3<f64>>,
}

impl ObstacleRows<'_> {
    /// The row cache's further key: the translation.
    fn extra(&self) -> [f64; 3] {
        let t = &self.translation;
        [t.x, t.y, t.z]
    }
}

impl RowSource for ObstacleRows<'_> {
    fn rows(&self, derivatives: Derivatives) -> Arc<MortarRows> {
        let surfaces = &self.obstacle.surfaces;
        let integrate = || self.obstacle.rows(&self.translation, &self.xs, derivatives);
        surfaces.cached_rows(&self.xs, &self.extra(), derivatives, integrate)
    }

    fn gaps(&self) -> BTreeMap<usize, f64> {
        let surfaces = &self.obstacle.surfaces;
        if let Some(rows) = surfaces.cached(&self.xs, &self.extra()) {
            return row_gaps(&rows);
        }
        surfaces.count_values();
        self.obstacle.gap_values(&self.translation, &self.xs)
    }

    fn obstacle_translation(&self) -> Option<Vector3<f64>> {
        Some(self.translation)
    }
}
