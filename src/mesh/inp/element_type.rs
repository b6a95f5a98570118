//! The Abaqus element types the reader knows, and the Abaqus face
//! numbering of the volume elements (`S1…` in `*SURFACE`).
//!
//! Node numbering inside C3D4, C3D8 and C3D6 is Gmsh's (and so this
//! crate's): C3D8 has the face `1-2-3-4` then `5-6-7-8` above it. The
//! mid-side nodes of C3D10, C3D20 and C3D15 are numbered as VTK numbers
//! them, and are put in this crate's order on reading
//! ([`from_abaqus_order`], [`ElementKind::vtk_order`]).

use super::super::{ElementKind, FacetKind};

/// What an element of a type becomes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Shape {
    /// A volume element.
    Volume(ElementKind),
    /// A surface element (shell, membrane, plane, rigid, surface): a facet
    /// of the surface sets of its element sets.
    Facet(FacetKind),
    /// A line element (truss, beam): its nodes join the node sets of its
    /// element sets.
    Line,
}

/// An element type: its shape and node count.
#[derive(Clone, Copy, Debug)]
pub(super) struct ElementType {
    pub(super) shape: Shape,
    pub(super) nodes: usize,
}

/// The type called `name` (upper case), or why it cannot be read.
pub(super) fn element_type(name: &str) -> Result<ElementType, String> {
    use ElementKind::{Hex20, Hex20R, Hex8, Tet10, Tet4, Wedge15, Wedge6};
    use FacetKind::{Quad4, Quad8, Tri3, Tri6};
    let (shape, nodes) = match name {
        "C3D4" | "C3D4H" => (Shape::Volume(Tet4), 4),
        "C3D8" | "C3D8R" | "C3D8I" | "C3D8H" | "C3D8RH" | "C3D8IH" => (Shape::Volume(Hex8), 8),
        "C3D10" | "C3D10M" | "C3D10H" | "C3D10MH" => (Shape::Volume(Tet10), 10),
        "C3D20" | "C3D20H" => (Shape::Volume(Hex20), 20),
        "C3D20R" | "C3D20RH" => (Shape::Volume(Hex20R), 20),
        "C3D6" | "C3D6H" => (Shape::Volume(Wedge6), 6),
        "C3D15" | "C3D15H" => (Shape::Volume(Wedge15), 15),
        "S6" | "STRI65" | "CPS6" | "CPE6" | "CAX6" | "M3D6" | "R3D6" => (Shape::Facet(Tri6), 6),
        "S8" | "S8R" | "CPS8" | "CPS8R" | "CPE8" | "CPE8R" | "CAX8" | "CAX8R" | "M3D8"
        | "M3D8R" => (Shape::Facet(Quad8), 8),
        "S3" | "S3R" | "STRI3" | "CPS3" | "CPE3" | "CAX3" | "M3D3" | "R3D3" | "SFM3D3" => {
            (Shape::Facet(Tri3), 3)
        }
        "S4" | "S4R" | "CPS4" | "CPS4R" | "CPS4I" | "CPE4" | "CPE4R" | "CPE4I" | "CPE4H"
        | "CAX4" | "CAX4R" | "M3D4" | "M3D4R" | "R3D4" | "SFM3D4" | "SFM3D4R" => {
            (Shape::Facet(Quad4), 4)
        }
        "T3D2" | "T2D2" | "B31" | "B21" | "B31H" | "B21H" => (Shape::Line, 2),
        "T3D3" | "T2D3" | "B32" | "B22" | "B32H" | "B22H" => (Shape::Line, 3),
        _ if name.starts_with("C3D") => {
            return Err(format!(
                "{name} is not supported yet: the volume elements read are C3D4, C3D10, C3D8, \
                 C3D20, C3D20R, C3D6 and C3D15 (and their H, M, R, I variants, with a note)"
            ))
        }
        _ => {
            return Err(format!(
                "element type {name} is not supported: the reader takes C3D4, C3D10, C3D8, \
                 C3D20(R), C3D6 and C3D15 volume elements, 3-, 4-, 6- and 8-node surface \
                 elements (S3, S4, S6, S8, CPS3, …, as facets of surface sets) and 2- and \
                 3-node line elements (T3D2, B31, …, as node sets)"
            ))
        }
    };
    Ok(ElementType { shape, nodes })
}

/// The Abaqus faces of a volume element, 1-based node numbers in the
/// element, as the Abaqus manual lists them: C3D4 `S1 = 1-2-3`,
/// `S2 = 1-4-2`, `S3 = 2-4-3`, `S4 = 3-4-1`; C3D8 `S1 = 1-2-3-4`,
/// `S2 = 5-8-7-6`, `S3 = 1-5-6-2`, `S4 = 2-6-7-3`, `S5 = 3-7-8-4`,
/// `S6 = 4-8-5-1`.
fn abaqus_faces(kind: ElementKind) -> &'static [&'static [usize]] {
    match crate::mesh::topology::linear(kind) {
        // C3D6 and C3D15: S1 = 1-2-3, S2 = 4-6-5, S3 = 1-4-5-2,
        // S4 = 2-5-6-3, S5 = 3-6-4-1 (the quadratic kinds by their corners)
        ElementKind::Wedge6 => &[
            &[1, 2, 3],
            &[4, 6, 5],
            &[1, 4, 5, 2],
            &[2, 5, 6, 3],
            &[3, 6, 4, 1],
        ],
        ElementKind::Tet4 => &[&[1, 2, 3], &[1, 4, 2], &[2, 4, 3], &[3, 4, 1]],
        ElementKind::Hex8 => &[
            &[1, 2, 3, 4],
            &[5, 8, 7, 6],
            &[1, 5, 6, 2],
            &[2, 6, 7, 3],
            &[3, 7, 8, 4],
            &[4, 8, 5, 1],
        ],
        _ => &[],
    }
}

/// An element's nodes in this crate's order, from the order of the deck
/// (Abaqus numbers the mid-side nodes of C3D10, C3D20 and C3D15 as VTK
/// does): node `vtk_order[i]` is the deck's node `i`.
pub(super) fn from_abaqus_order(kind: ElementKind, deck: Vec<usize>) -> Vec<usize> {
    if kind.vtk_order().len() != deck.len() || !kind.is_quadratic() {
        return deck;
    }
    crate::mesh::topology::from_vtk_order(kind, &deck)
}

/// The note for a deck's element type that is read as a kind that is not
/// exactly it (`None` where it is): what differs. `base` is the kind's
/// plain Abaqus name.
pub(super) fn variant_note(type_name: &str, base: &str) -> Option<String> {
    match type_name {
        _ if type_name == base => None,
        "C3D20R" => Some(
            "C3D20R elements are read as 20-node hexahedra with 2×2×2 reduced Gauss \
             integration, as Abaqus integrates them (CalculiX adds no hourglass control to them \
             either)"
                .to_string(),
        ),
        _ if type_name.starts_with("C3D10M") => Some(format!(
            "{type_name} elements are read as C3D10 (the standard 10-node tetrahedron with 4 \
             Gauss points; the modified formulation's lumped contact and hourglass terms are not \
             reproduced)"
        )),
        _ => Some(format!(
            "{type_name} elements are read as {base} (full integration: no reduced integration, \
             hybrid pressure or incompatible modes)"
        )),
    }
}

/// Face `S<number>` of an element of kind `kind` as local node indices in
/// the outward order of [`ElementKind::faces`] (the face with the same
/// nodes); `None` if the element has no such face.
pub(super) fn outward_face(kind: ElementKind, number: usize) -> Option<&'static [usize]> {
    let abaqus = abaqus_faces(kind).get(number.checked_sub(1)?)?;
    kind.faces().iter().copied().find(|face| {
        let corners = FacetKind::of_node_count(face.len()).map_or(0, FacetKind::num_corners);
        corners == abaqus.len() && abaqus.iter().all(|&a| face[..corners].contains(&(a - 1)))
    })
}

/// Number of faces (`S1…S4` or `S1…S6`).
pub(super) fn face_count(kind: ElementKind) -> usize {
    abaqus_faces(kind).len()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every Abaqus face matches exactly one face of the element, and the
    /// faces of an element are all different: the numbering is a bijection.
    #[test]
    fn abaqus_faces_are_the_element_faces() {
        let kinds = [
            ElementKind::Tet4,
            ElementKind::Hex8,
            ElementKind::Tet10,
            ElementKind::Hex20,
            ElementKind::Hex20R,
            ElementKind::Wedge6,
            ElementKind::Wedge15,
        ];
        for kind in kinds {
            let mut seen = Vec::new();
            for s in 1..=face_count(kind) {
                let face = outward_face(kind, s).expect("a face");
                assert!(!seen.contains(&face), "{kind:?} S{s}");
                seen.push(face);
            }
            assert_eq!(seen.len(), kind.faces().len());
            assert!(outward_face(kind, 0).is_none());
            assert!(outward_face(kind, face_count(kind) + 1).is_none());
        }
        // C3D4 S3 is the face opposite node 1; C3D8 S2 the face 5-6-7-8
        assert_eq!(outward_face(ElementKind::Tet4, 3), Some(&[1, 2, 3][..]));
        assert_eq!(outward_face(ElementKind::Hex8, 2), Some(&[4, 5, 6, 7][..]));
        // C3D6/C3D15 S1 the bottom triangle, S3 the side 1-4-5-2
        assert_eq!(outward_face(ElementKind::Wedge6, 1), Some(&[0, 2, 1][..]));
        assert_eq!(
            outward_face(ElementKind::Wedge6, 3),
            Some(&[0, 1, 4, 3][..])
        );
        assert_eq!(
            outward_face(ElementKind::Tet10, 3),
            Some(&[1, 2, 3, 5, 8, 9][..])
        );
        assert_eq!(
            outward_face(ElementKind::Wedge15, 4),
            Some(&[1, 2, 5, 4, 9, 11, 14, 10][..])
        );
    }

    /// A C3D10, C3D20 and C3D15 written with Abaqus's node numbers: each
    /// mid-side node the deck lists (manual, "Three-dimensional solid
    /// element library": C3D10 node 5 on 1-2, 7 on 3-1, 8 on 1-4, 10 on
    /// 3-4; C3D20 node 12 on 4-1, 17 on 1-5; C3D15 node 9 on 3-1, 13 on
    /// 1-4) lands on the same edge in this crate's order.
    #[test]
    fn abaqus_mid_side_nodes_land_on_their_edges() {
        use crate::mesh::topology::mid_side_node;
        type AbaqusEdges = &'static [(usize, [usize; 2])];
        let cases: [(ElementKind, AbaqusEdges); 3] = [
            (
                ElementKind::Tet10,
                &[
                    (5, [1, 2]),
                    (7, [3, 1]),
                    (8, [1, 4]),
                    (9, [2, 4]),
                    (10, [3, 4]),
                ],
            ),
            (
                ElementKind::Hex20,
                &[
                    (9, [1, 2]),
                    (12, [4, 1]),
                    (16, [8, 5]),
                    (17, [1, 5]),
                    (20, [4, 8]),
                ],
            ),
            (
                ElementKind::Wedge15,
                &[(9, [3, 1]), (12, [6, 4]), (13, [1, 4]), (15, [3, 6])],
            ),
        ];
        for (kind, edges) in cases {
            // the deck's node i is the mesh node 100 + i
            let deck: Vec<usize> = (1..=kind.num_nodes()).map(|i| 100 + i).collect();
            let nodes = from_abaqus_order(kind, deck);
            for (abaqus, [a, b]) in edges {
                let local = mid_side_node(kind, a - 1, b - 1).expect("an edge");
                assert_eq!(nodes[local], 100 + abaqus, "{kind:?} node {abaqus}");
            }
        }
    }
}
