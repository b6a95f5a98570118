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

use super::mortar::obstacle_rows::{obstacle_row_values, obstacle_rows, transformed_point};
use super::mortar::MortarRow;
use super::mortar_contact::{coordinates, face_size, full_integrals, node_faces, surface_faces};
use super::mortar_contact::{MortarGap, MortarSurfaces, RowCounts};
use super::obstacle::RigidObstacle;
use super::projection::Projection;
use crate::mesh::Mesh;
use nalgebra::Vector3;
use std::collections::BTreeMap;

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
        let surfaces = MortarSurfaces::secondary_only(faces, node_faces, mean, margin);
        Some(Self {
            obstacle,
            surfaces,
            nodes: nodes.to_vec(),
            node_margins,
        })
    }

    /// `D_j = ∫ Ñ_j dA` of every secondary node in the reference
    /// configuration of `mesh` (the nodes' areas `A_j`).
    pub fn reference_areas(&self, mesh: &Mesh) -> Vec<f64> {
        let xs = coordinates(&mesh.nodes, &vec![0.0; 3 * mesh.num_nodes()]);
        let d = full_integrals(&self.surfaces.secondary_faces, &xs);
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

    /// The rows of the near nodes (module docs) at unknowns `x` with the
    /// obstacle translated by `translation`: every node's `D_j`, `g̃_j`,
    /// lever and normal with their derivatives, keyed by mesh node. A face
    /// the kernels cannot integrate (degenerate) leaves every node open in
    /// this evaluation; the element assembly reports such a face's element.
    pub fn rows(
        &self,
        translation: &Vector3<f64>,
        reference: &[[f64; 3]],
        x: &[f64],
    ) -> BTreeMap<usize, MortarRow> {
        let xs = coordinates(reference, x);
        let project = |p: &Vector3<f64>| self.obstacle.project(&(p - translation));
        let near = self.near(&xs, &project);
        let selected = self.faces_of(&near);
        let mut rows = obstacle_rows(&self.surfaces.secondary_faces, &selected, &xs, &project)
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

    /// Every secondary node's normalised gap `g_j = g̃_j / D_j` at unknowns
    /// `x`, the obstacle translated by `translation` (the interface's node
    /// order; the open gap `margin` of the surfaces beyond a node's own
    /// margin): the gaps of [`producer`](Self::producer)'s rows without
    /// their derivatives, for a solve that reads only gaps. From the row
    /// cache where this configuration's rows are there; otherwise on a
    /// plane in closed form, `g_j = g(x̃_j)`
    /// ([`transformed_point`]: biorthogonality, exact to round-off), on a
    /// curved obstacle by the rows' own sums ([`obstacle_row_values`], to
    /// the bit). A face the kernels cannot integrate leaves every node
    /// open, as the rows do.
    pub fn gaps(&self, translation: &Vector3<f64>, reference: &[[f64; 3]], x: &[f64]) -> Vec<f64> {
        let xs = coordinates(reference, x);
        let open = self.surfaces.margin;
        let extra = [translation.x, translation.y, translation.z];
        if let Some(rows) = self.surfaces.cached(&xs, &extra) {
            let gap = |node: &usize| rows.get(node).filter(|r| r.d > 0.0);
            let gap = |node| gap(node).map_or(open, |r| r.weighted_gap / r.d);
            return self.nodes.iter().map(gap).collect();
        }
        self.surfaces.count_values();
        let project = |p: &Vector3<f64>| self.obstacle.project(&(p - translation));
        let near = self.near(&xs, &project);
        let mut gaps = vec![open; self.nodes.len()];
        if let RigidObstacle::Plane { .. } = self.obstacle {
            let faces = &self.surfaces.secondary_faces;
            for i in near {
                if let Some(&e) = self.surfaces.node_faces[i].first() {
                    let point = transformed_point(&faces[e], self.nodes[i], &xs);
                    gaps[i] = project(&point).gap;
                }
            }
            return gaps;
        }
        let selected = self.faces_of(&near);
        let faces = &self.surfaces.secondary_faces;
        let Ok(values) = obstacle_row_values(faces, &selected, &xs, &project) else {
            return gaps;
        };
        for i in near {
            if let Some(v) = values.get(&self.nodes[i]).filter(|v| v.d > 0.0) {
                gaps[i] = v.weighted_gap / v.d;
            }
        }
        gaps
    }

    /// The gap producer at unknowns `x`, the obstacle translated by
    /// `translation`: a [`MortarGap`] over [`rows`](Self::rows), from the
    /// surfaces' row cache (keyed by the secondary nodes' coordinates and
    /// the translation) where this configuration was integrated last or
    /// the one before.
    pub fn producer(
        &self,
        translation: &Vector3<f64>,
        reference: &[[f64; 3]],
        x: &[f64],
    ) -> MortarGap<'_> {
        let xs = coordinates(reference, x);
        let extra = [translation.x, translation.y, translation.z];
        let rows =
            (self.surfaces).cached_rows(&xs, &extra, || self.rows(translation, reference, x));
        MortarGap {
            surfaces: &self.surfaces,
            rows,
        }
    }

    /// How often the producer asked for rows and how often it integrated
    /// them, since this interface was built (or cloned).
    pub fn row_counts(&self) -> RowCounts {
        self.surfaces.row_counts()
    }
}
