//! The topology of the element kinds: their mid-side nodes (by edge),
//! their outward faces, and the node orders of VTK and Abaqus/CalculiX.
//!
//! This crate numbers the nodes of an element as Gmsh does. The quadratic
//! elements put a node on each edge, after the corners, in Gmsh's edge
//! order:
//!
//! ```text
//! Tet10    4:(0,1) 5:(1,2) 6:(2,0) 7:(3,0) 8:(3,2) 9:(3,1)
//! Hex20    8:(0,1) 9:(0,3) 10:(0,4) 11:(1,2) 12:(1,5) 13:(2,3)
//!          14:(2,6) 15:(3,7) 16:(4,5) 17:(4,7) 18:(5,6) 19:(6,7)
//! Wedge15  6:(0,1) 7:(0,2) 8:(0,3) 9:(1,2) 10:(1,4) 11:(2,5)
//!          12:(3,4) 13:(3,5) 14:(4,5)
//! ```
//!
//! VTK (and Abaqus, whose C3D10/C3D20/C3D15 numbering is VTK's, 1-based)
//! takes the edges of the bottom face in turn, then of the top face, then
//! the vertical ones: Tet10 `(0,1) (1,2) (2,0) (0,3) (1,3) (2,3)`, Hex20
//! `(0,1) (1,2) (2,3) (3,0) (4,5) (5,6) (6,7) (7,4) (0,4) (1,5) (2,6)
//! (3,7)`, Wedge15 `(0,1) (1,2) (2,0) (3,4) (4,5) (5,3) (0,3) (1,4)
//! (2,5)` ([`vtk_order`]).

use super::ElementKind;

/// The edges that carry the mid-side nodes, in node order: mid-side node
/// `corners + m` is the midpoint of `edges(kind)[m]`. Empty for a linear
/// element.
pub fn edges(kind: ElementKind) -> &'static [[usize; 2]] {
    match kind {
        ElementKind::Tet4 | ElementKind::Hex8 | ElementKind::Wedge6 => &[],
        ElementKind::Tet10 => &[[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]],
        ElementKind::Hex20 | ElementKind::Hex20R => &[
            [0, 1],
            [0, 3],
            [0, 4],
            [1, 2],
            [1, 5],
            [2, 3],
            [2, 6],
            [3, 7],
            [4, 5],
            [4, 7],
            [5, 6],
            [6, 7],
        ],
        ElementKind::Wedge15 => &[
            [0, 1],
            [0, 2],
            [0, 3],
            [1, 2],
            [1, 4],
            [2, 5],
            [3, 4],
            [3, 5],
            [4, 5],
        ],
    }
}

/// Number of corner nodes.
pub fn num_corners(kind: ElementKind) -> usize {
    kind.num_nodes() - edges(kind).len()
}

/// The linear element on the same corners.
pub fn linear(kind: ElementKind) -> ElementKind {
    match kind {
        ElementKind::Tet4 | ElementKind::Tet10 => ElementKind::Tet4,
        ElementKind::Hex8 | ElementKind::Hex20 | ElementKind::Hex20R => ElementKind::Hex8,
        ElementKind::Wedge6 | ElementKind::Wedge15 => ElementKind::Wedge6,
    }
}

/// See [`ElementKind::vtk_order`].
pub fn vtk_order(kind: ElementKind) -> &'static [usize] {
    match kind {
        ElementKind::Tet4 => &[0, 1, 2, 3],
        ElementKind::Hex8 => &[0, 1, 2, 3, 4, 5, 6, 7],
        ElementKind::Wedge6 => &[0, 1, 2, 3, 4, 5],
        ElementKind::Tet10 => &[0, 1, 2, 3, 4, 5, 6, 7, 9, 8],
        ElementKind::Hex20 | ElementKind::Hex20R => &[
            0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15,
        ],
        ElementKind::Wedge15 => &[0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11],
    }
}

/// An element's nodes in this crate's order from VTK's order (meshio's,
/// and Abaqus's): node `vtk_order[i]` is the given node `i`.
pub fn from_vtk_order(kind: ElementKind, vtk: &[usize]) -> Vec<usize> {
    let mut nodes = vtk.to_vec();
    for (i, &internal) in vtk_order(kind).iter().enumerate() {
        if let (Some(slot), Some(&node)) = (nodes.get_mut(internal), vtk.get(i)) {
            *slot = node;
        }
    }
    nodes
}

/// See [`ElementKind::faces`]. A Wedge6's bottom triangle `0, 1, 2` is
/// counter-clockwise seen from above (Gmsh), so its outward face is
/// `0, 2, 1`.
pub fn faces(kind: ElementKind) -> &'static [&'static [usize]] {
    match kind {
        ElementKind::Tet4 => &[&[0, 2, 1], &[0, 1, 3], &[0, 3, 2], &[1, 2, 3]],
        ElementKind::Hex8 => &[
            &[0, 3, 2, 1],
            &[4, 5, 6, 7],
            &[0, 1, 5, 4],
            &[1, 2, 6, 5],
            &[2, 3, 7, 6],
            &[3, 0, 4, 7],
        ],
        ElementKind::Wedge6 => &[
            &[0, 2, 1],
            &[3, 4, 5],
            &[0, 1, 4, 3],
            &[1, 2, 5, 4],
            &[2, 0, 3, 5],
        ],
        ElementKind::Tet10 => &[
            &[0, 2, 1, 6, 5, 4],
            &[0, 1, 3, 4, 9, 7],
            &[0, 3, 2, 7, 8, 6],
            &[1, 2, 3, 5, 8, 9],
        ],
        ElementKind::Hex20 | ElementKind::Hex20R => &[
            &[0, 3, 2, 1, 9, 13, 11, 8],
            &[4, 5, 6, 7, 16, 18, 19, 17],
            &[0, 1, 5, 4, 8, 12, 16, 10],
            &[1, 2, 6, 5, 11, 14, 18, 12],
            &[2, 3, 7, 6, 13, 15, 19, 14],
            &[3, 0, 4, 7, 9, 10, 17, 15],
        ],
        ElementKind::Wedge15 => &[
            &[0, 2, 1, 7, 9, 6],
            &[3, 4, 5, 12, 14, 13],
            &[0, 1, 4, 3, 6, 10, 12, 8],
            &[1, 2, 5, 4, 9, 11, 14, 10],
            &[2, 0, 3, 5, 7, 8, 13, 11],
        ],
    }
}

/// The node of `kind` on the edge between corners `a` and `b`, if any.
pub fn mid_side_node(kind: ElementKind, a: usize, b: usize) -> Option<usize> {
    let m = edges(kind)
        .iter()
        .position(|e| *e == [a, b] || *e == [b, a])?;
    Some(num_corners(kind) + m)
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [ElementKind; 7] = [
        ElementKind::Tet4,
        ElementKind::Hex8,
        ElementKind::Tet10,
        ElementKind::Hex20,
        ElementKind::Hex20R,
        ElementKind::Wedge6,
        ElementKind::Wedge15,
    ];

    /// A quadratic face's corners are those of the linear element's face in
    /// the same place, and its mid-side node `k` sits on the edge between
    /// its corners `k` and `k + 1` (the Tri6/Quad8 order).
    #[test]
    fn quadratic_faces_follow_their_corners() {
        for kind in ALL {
            let lin = linear(kind).faces();
            assert_eq!(kind.faces().len(), lin.len(), "{kind:?}");
            for (face, corners) in kind.faces().iter().zip(lin) {
                let c = corners.len();
                assert_eq!(&face[..c], *corners, "{kind:?}");
                if !kind.is_quadratic() {
                    assert_eq!(face.len(), c);
                    continue;
                }
                assert_eq!(face.len(), 2 * c, "{kind:?}");
                for k in 0..c {
                    let m = mid_side_node(kind, face[k], face[(k + 1) % c]);
                    assert_eq!(m, Some(face[c + k]), "{kind:?} face {face:?} edge {k}");
                }
            }
        }
    }

    /// VTK's (and Abaqus's) node `i` of a quadratic element is on the edge
    /// VTK's documentation lists for it (vtkQuadraticTetra, -Hexahedron,
    /// -Wedge), and `vtk_order` is a permutation.
    #[test]
    fn vtk_order_puts_each_mid_side_node_on_vtks_edge() {
        let vtk_edges: [(ElementKind, &[[usize; 2]]); 3] = [
            (
                ElementKind::Tet10,
                &[[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]],
            ),
            (
                ElementKind::Hex20,
                &[
                    [0, 1],
                    [1, 2],
                    [2, 3],
                    [3, 0],
                    [4, 5],
                    [5, 6],
                    [6, 7],
                    [7, 4],
                    [0, 4],
                    [1, 5],
                    [2, 6],
                    [3, 7],
                ],
            ),
            (
                ElementKind::Wedge15,
                &[
                    [0, 1],
                    [1, 2],
                    [2, 0],
                    [3, 4],
                    [4, 5],
                    [5, 3],
                    [0, 3],
                    [1, 4],
                    [2, 5],
                ],
            ),
        ];
        for (kind, edges) in vtk_edges {
            let order = vtk_order(kind);
            let c = num_corners(kind);
            assert_eq!(&order[..c], &(0..c).collect::<Vec<_>>()[..]);
            for (m, [a, b]) in edges.iter().enumerate() {
                assert_eq!(Some(order[c + m]), mid_side_node(kind, *a, *b), "{kind:?}");
            }
        }
        for kind in ALL {
            let mut sorted = vtk_order(kind).to_vec();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..kind.num_nodes()).collect::<Vec<_>>());
        }
    }
}
