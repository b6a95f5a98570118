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
    corner_key(nodes.len(), nodes.iter().copied())
}

/// [`face_key`] of the face of `len` nodes that `nodes` yields (corners
/// first), without collecting them.
fn corner_key(len: usize, nodes: impl Iterator<Item = usize>) -> [usize; 4] {
    let mut k = [usize::MAX; 4];
    let corners = facet_kind(len).num_corners().min(len);
    for (slot, n) in k.iter_mut().zip(nodes.take(corners)) {
        *slot = n;
    }
    k.sort_unstable();
    k
}

/// [`face_key`] of local face `local` of element `el`.
fn element_face_key(el: &super::Element, local: &[usize]) -> [usize; 4] {
    corner_key(local.len(), local.iter().map(|&a| el.nodes[a]))
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
            (el.kind.faces().iter().enumerate())
                .map(move |(f, local)| (element_face_key(el, local), e as u32, f as u8))
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

/// How many element faces have a key, and the last of them (element,
/// local face).
#[derive(Clone, Copy, Default)]
struct FaceCount {
    count: usize,
    element: usize,
    face: usize,
}

/// For each of `keys`, the element faces with that key
/// ([`face_key`]): one on the boundary, two or more inside the mesh
/// (an interface between two regions), none for a facet that is no
/// element's face. Only the faces whose corners all lie on a key are
/// looked up, so the cost is a pass over the elements and not a sort of
/// all their faces ([`boundary_faces`]).
fn faces_with_keys(
    mesh: &Mesh,
    keys: impl Iterator<Item = [usize; 4]>,
) -> HashMap<[usize; 4], FaceCount> {
    use rayon::prelude::*;
    let mut found: HashMap<[usize; 4], FaceCount> =
        keys.map(|k| (k, FaceCount::default())).collect();
    let mut on_key = vec![false; mesh.nodes.len()];
    for &n in found.keys().flatten() {
        // (usize::MAX pads a triangle's key)
        if let Some(on) = on_key.get_mut(n) {
            *on = true;
        }
    }
    let hits: Vec<([usize; 4], usize, usize)> = (mesh.elements.par_iter().enumerate())
        .flat_map_iter(|(e, el)| {
            let (found, on_key) = (&found, &on_key);
            (el.kind.faces().iter().enumerate()).filter_map(move |(f, local)| {
                let corners = facet_kind(local.len()).num_corners().min(local.len());
                if !local[..corners].iter().all(|&a| on_key[el.nodes[a]]) {
                    return None;
                }
                let key = element_face_key(el, local);
                found.contains_key(&key).then_some((key, e, f))
            })
        })
        .collect();
    for (key, element, face) in hits {
        if let Some(c) = found.get_mut(&key) {
            *c = FaceCount {
                count: c.count + 1,
                element,
                face,
            };
        }
    }
    found
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
        let keys = (self.surfaces.iter()).flat_map(|s| s.facets.iter().map(|f| face_key(&f.nodes)));
        let faces = faces_with_keys(self, keys);
        let mut orphans = Vec::new();
        for surface in &mut self.surfaces {
            for facet in &mut surface.facets {
                let found = faces
                    .get(&face_key(&facet.nodes))
                    .copied()
                    .unwrap_or_default();
                match found.count {
                    1 => {
                        let el = &self.elements[found.element];
                        let face: Vec<usize> = (el.kind.faces()[found.face].iter())
                            .map(|&a| el.nodes[a])
                            .collect();
                        // keep the facet's first node, follow the face's cycle
                        let start = face.iter().position(|&n| n == facet.nodes[0]);
                        if let Some(s) = start {
                            // a facet given by its corners takes the face's
                            // mid-side nodes too
                            facet.nodes = rotated(&face, s);
                            facet.kind = facet_kind(facet.nodes.len());
                        }
                    }
                    // no element's face
                    0 => orphans.push(OrphanFacet {
                        surface: surface.name.clone(),
                        facet_id: facet.id,
                    }),
                    // an interface between two regions keeps its orientation
                    _ => {}
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
