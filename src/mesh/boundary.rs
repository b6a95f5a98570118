//! The boundary of a volume mesh: element faces that belong to exactly one
//! element, with their outward orientation, and the orientation of the
//! surface sets read from a mesh file.

use super::{ElementKind, Facet, FacetKind, Mesh};
use std::collections::HashMap;

/// An element face, outward-oriented, with the element it bounds.
#[derive(Clone, Debug)]
pub struct BoundaryFace {
    pub element: usize,
    pub nodes: Vec<usize>,
}

fn face_key(nodes: &[usize]) -> Vec<usize> {
    let mut k = nodes.to_vec();
    k.sort_unstable();
    k
}

fn facet_kind(n: usize) -> FacetKind {
    if n == 3 {
        FacetKind::Tri3
    } else {
        FacetKind::Quad4
    }
}

/// All element faces keyed by their sorted node list; faces shared by two
/// elements map to `None`, faces on the boundary to their outward-oriented
/// node list.
pub fn boundary_faces(mesh: &Mesh) -> HashMap<Vec<usize>, Option<BoundaryFace>> {
    let mut faces: HashMap<Vec<usize>, Option<BoundaryFace>> = HashMap::new();
    for (e, el) in mesh.elements.iter().enumerate() {
        for local in el.kind.faces() {
            let nodes: Vec<usize> = local.iter().map(|&a| el.nodes[a]).collect();
            faces
                .entry(face_key(&nodes))
                .and_modify(|f| *f = None)
                .or_insert(Some(BoundaryFace { element: e, nodes }));
        }
    }
    faces
}

/// Boundary faces as facets, outward-oriented.
pub fn boundary_facets(mesh: &Mesh) -> Vec<Facet> {
    let mut out: Vec<(usize, Facet)> = boundary_faces(mesh)
        .into_values()
        .flatten()
        .map(|f| {
            (
                f.element,
                Facet {
                    kind: facet_kind(f.nodes.len()),
                    nodes: f.nodes,
                    id: 0,
                },
            )
        })
        .collect();
    // deterministic order: by element, then by node list
    out.sort_by(|a, b| (a.0, &a.1.nodes).cmp(&(b.0, &b.1.nodes)));
    out.into_iter().map(|(_, f)| f).collect()
}

/// A facet of a surface set that lies on no volume element's boundary face.
#[derive(Debug, Clone)]
pub struct OrphanFacet {
    pub surface: String,
    pub facet_id: u64,
}

impl Mesh {
    /// Re-order the nodes of every surface-set facet so that its right-hand
    /// normal points out of the body, by matching it to the boundary face of
    /// the volume element it bounds. Facets that match an interior face keep
    /// their orientation (an interface between two regions); facets that
    /// match no element face are returned.
    pub fn orient_surfaces(&mut self) -> Vec<OrphanFacet> {
        let faces = boundary_faces(self);
        let mut orphans = Vec::new();
        for surface in &mut self.surfaces {
            for facet in &mut surface.facets {
                match faces.get(&face_key(&facet.nodes)) {
                    Some(Some(face)) => {
                        // keep the facet's first node, follow the face's cycle
                        let start = face.nodes.iter().position(|&n| n == facet.nodes[0]);
                        if let Some(s) = start {
                            let k = face.nodes.len();
                            facet.nodes = (0..k).map(|i| face.nodes[(s + i) % k]).collect();
                        }
                    }
                    Some(None) => {}
                    None => orphans.push(OrphanFacet {
                        surface: surface.name.clone(),
                        facet_id: facet.id,
                    }),
                }
            }
        }
        orphans
    }
}

/// The volume element kinds present in a mesh.
pub fn element_kinds(mesh: &Mesh) -> Vec<ElementKind> {
    let mut kinds: Vec<ElementKind> = Vec::new();
    for e in &mesh.elements {
        if !kinds.contains(&e.kind) {
            kinds.push(e.kind);
        }
    }
    kinds
}
