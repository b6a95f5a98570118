//! The Abaqus element types the reader knows, and the Abaqus face
//! numbering of the volume elements (`S1…` in `*SURFACE`).
//!
//! Node numbering inside C3D4 and C3D8 is Gmsh's (and so this crate's):
//! C3D8 has the face `1-2-3-4` then `5-6-7-8` above it.

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
    use ElementKind::{Hex8, Tet4};
    use FacetKind::{Quad4, Tri3};
    let (shape, nodes) = match name {
        "C3D4" | "C3D4H" => (Shape::Volume(Tet4), 4),
        "C3D8" | "C3D8R" | "C3D8I" | "C3D8H" | "C3D8RH" | "C3D8IH" => (Shape::Volume(Hex8), 8),
        "S3" | "S3R" | "STRI3" | "CPS3" | "CPE3" | "CAX3" | "M3D3" | "R3D3" | "SFM3D3" => {
            (Shape::Facet(Tri3), 3)
        }
        "S4" | "S4R" | "CPS4" | "CPS4R" | "CPS4I" | "CPE4" | "CPE4R" | "CPE4I" | "CPE4H"
        | "CAX4" | "CAX4R" | "M3D4" | "M3D4R" | "R3D4" | "SFM3D4" | "SFM3D4R" => {
            (Shape::Facet(Quad4), 4)
        }
        "T3D2" | "T2D2" | "B31" | "B21" | "B31H" | "B21H" => (Shape::Line, 2),
        "T3D3" | "T2D3" | "B32" | "B22" | "B32H" | "B22H" => (Shape::Line, 3),
        _ if name.starts_with("C3D10")
            || name.starts_with("C3D20")
            || name.starts_with("C3D15") =>
        {
            return Err(format!(
                "{name} is a quadratic element, not supported yet: only linear C3D4 and C3D8 \
                 volume elements are; mesh with first-order elements (Gmsh: -order 1)"
            ))
        }
        _ if name.starts_with("C3D") => {
            return Err(format!(
                "{name} is not supported yet: only C3D4 (4-node tetrahedra) and C3D8 \
                 (8-node hexahedra) volume elements are"
            ))
        }
        _ => {
            return Err(format!(
                "element type {name} is not supported: the reader takes C3D4 and C3D8 volume \
                 elements, 3- and 4-node surface elements (S3, S4, CPS3, CPS4, …, as facets of \
                 surface sets) and 2- and 3-node line elements (T3D2, B31, …, as node sets)"
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
    match kind {
        ElementKind::Tet4 => &[&[1, 2, 3], &[1, 4, 2], &[2, 4, 3], &[3, 4, 1]],
        ElementKind::Hex8 => &[
            &[1, 2, 3, 4],
            &[5, 8, 7, 6],
            &[1, 5, 6, 2],
            &[2, 6, 7, 3],
            &[3, 7, 8, 4],
            &[4, 8, 5, 1],
        ],
    }
}

/// Face `S<number>` of an element of kind `kind` as local node indices in
/// the outward order of [`ElementKind::faces`] (the face with the same
/// nodes); `None` if the element has no such face.
pub(super) fn outward_face(kind: ElementKind, number: usize) -> Option<&'static [usize]> {
    let abaqus = abaqus_faces(kind).get(number.checked_sub(1)?)?;
    kind.faces()
        .iter()
        .copied()
        .find(|face| face.len() == abaqus.len() && abaqus.iter().all(|&a| face.contains(&(a - 1))))
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
        for kind in [ElementKind::Tet4, ElementKind::Hex8] {
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
    }
}
