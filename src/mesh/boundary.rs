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

/// Sorted corner list of a face, padded with `usize::MAX` (faces have 3
/// or 4 corners; a quadratic face's mid-side nodes follow them and are
/// not part of the key): a key that identifies a face whatever its
/// orientation.
fn face_key(nodes: &[usize]) -> [usize; 4] {
    let mut k = [usize::MAX; 4];
    let corners = facet_kind(nodes.len()).num_corners();
    for (slot, &n) in k.iter_mut().zip(&nodes[..corners.min(nodes.len())]) {
        *slot = n;
    }
    k.sort_unstable();
    k
}

fn facet_kind(n: usize) -> FacetKind {
    FacetKind::of_node_count(n).unwrap_or(FacetKind::Quad4)
}

/// The face `nodes` (corners, then mid-side nodes) started at its corner
/// `start`: corners and mid-side nodes each rotated by `start`, so the
/// mid-side node `k` stays between the corners `k` and `k + 1`.
fn rotated(nodes: &[usize], start: usize) -> Vec<usize> {
    let c = facet_kind(nodes.len()).num_corners().min(nodes.len());
    let (corners, mids) = nodes.split_at(c);
    let mut out: Vec<usize> = (0..c).map(|i| corners[(start + i) % c]).collect();
    out.extend((0..mids.len()).map(|i| mids[(start + i) % mids.len()]));
    out
}

/// The faces of the mesh that belong to exactly one element, outward
/// oriented, keyed by their sorted node list.
///
/// Every element face is listed with its key and the list is sorted
/// (in parallel): a face shared by two elements appears twice in a row.
/// Sorting fixed-size keys is several times faster than hashing node
/// vectors on meshes with millions of faces.
pub fn boundary_faces(mesh: &Mesh) -> HashMap<[usize; 4], BoundaryFace> {
    use rayon::prelude::*;
    let mut faces: Vec<([usize; 4], u32, u8)> = mesh
        .elements
        .par_iter()
        .enumerate()
        .flat_map_iter(|(e, el)| {
            el.kind.faces().iter().enumerate().map(move |(f, local)| {
                let nodes: Vec<usize> = local.iter().map(|&a| el.nodes[a]).collect();
                (face_key(&nodes), e as u32, f as u8)
            })
        })
        .collect();
    faces.par_sort_unstable();
    let mut out = HashMap::new();
    let mut i = 0;
    while i < faces.len() {
        let mut j = i + 1;
        while j < faces.len() && faces[j].0 == faces[i].0 {
            j += 1;
        }
        if j == i + 1 {
            let (key, e, f) = faces[i];
            let el = &mesh.elements[e as usize];
            let nodes = el.kind.faces()[f as usize]
                .iter()
                .map(|&a| el.nodes[a])
                .collect();
            out.insert(
                key,
                BoundaryFace {
                    element: e as usize,
                    nodes,
                },
            );
        }
        i = j;
    }
    out
}

/// Keys of all faces shared by two or more elements.
fn interior_face_keys_of(elements: &[super::Element]) -> std::collections::HashSet<[usize; 4]> {
    let mut count: HashMap<[usize; 4], usize> = HashMap::new();
    for el in elements {
        for local in el.kind.faces() {
            let nodes: Vec<usize> = local.iter().map(|&a| el.nodes[a]).collect();
            *count.entry(face_key(&nodes)).or_insert(0) += 1;
        }
    }
    count
        .into_iter()
        .filter(|(_, c)| *c > 1)
        .map(|(k, _)| k)
        .collect()
}

/// Boundary faces as facets, outward-oriented.
pub fn boundary_facets(mesh: &Mesh) -> Vec<Facet> {
    let mut out: Vec<(usize, Facet)> = boundary_faces(mesh)
        .into_values()
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
        let mut interior = None;
        let mut orphans = Vec::new();
        for surface in &mut self.surfaces {
            for facet in &mut surface.facets {
                let key = face_key(&facet.nodes);
                match faces.get(&key) {
                    Some(face) => {
                        // keep the facet's first node, follow the face's cycle
                        let start = face.nodes.iter().position(|&n| n == facet.nodes[0]);
                        if let Some(s) = start {
                            // a facet given by its corners takes the face's
                            // mid-side nodes too
                            facet.nodes = rotated(&face.nodes, s);
                            facet.kind = facet_kind(facet.nodes.len());
                        }
                    }
                    None => {
                        // an interface between two regions keeps its orientation
                        let interior =
                            interior.get_or_insert_with(|| interior_face_keys_of(&self.elements));
                        if !interior.contains(&key) {
                            orphans.push(OrphanFacet {
                                surface: surface.name.clone(),
                                facet_id: facet.id,
                            });
                        }
                    }
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
