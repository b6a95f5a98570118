//! The table of Gmsh element types: dimension, node count and shape.

use super::cursor::Cursor;
use crate::Result;

/// Dimension, node count and shape of a Gmsh element type.
#[derive(Clone, Copy, Debug)]
pub(super) struct ElementInfo {
    pub(super) dim: u8,
    pub(super) nodes: usize,
    pub(super) shape: &'static str,
}

/// The Gmsh element types with a fixed number of nodes (`GmshDefines.h`).
/// The reader must know the node count of every type it may have to skip.
pub(super) fn element_info(element_type: i64) -> Option<ElementInfo> {
    const PNT: &str = "point";
    const LIN: &str = "line";
    const TRI: &str = "triangle";
    const QUA: &str = "quadrangle";
    const TET: &str = "tetrahedron";
    const HEX: &str = "hexahedron";
    const PRI: &str = "prism";
    const PYR: &str = "pyramid";
    let (dim, nodes, shape) = match element_type {
        15 => (0, 1, PNT),
        1 => (1, 2, LIN),
        8 => (1, 3, LIN),
        26 => (1, 4, LIN),
        27 => (1, 5, LIN),
        28 => (1, 6, LIN),
        62..=66 => (1, element_type as usize - 55, LIN),
        2 => (2, 3, TRI),
        9 => (2, 6, TRI),
        20 => (2, 9, TRI),
        21 => (2, 10, TRI),
        22 => (2, 12, TRI),
        23 | 24 => (2, 15, TRI),
        25 | 53 => (2, 21, TRI),
        42 => (2, 28, TRI),
        43 => (2, 36, TRI),
        44 => (2, 45, TRI),
        45 => (2, 55, TRI),
        46 => (2, 66, TRI),
        52 => (2, 18, TRI),
        54 => (2, 24, TRI),
        55 => (2, 27, TRI),
        56 => (2, 30, TRI),
        3 => (2, 4, QUA),
        10 => (2, 9, QUA),
        16 => (2, 8, QUA),
        36 | 40 => (2, 16, QUA),
        37 => (2, 25, QUA),
        38 | 60 => (2, 36, QUA),
        39 => (2, 12, QUA),
        41 => (2, 20, QUA),
        47 => (2, 49, QUA),
        48 => (2, 64, QUA),
        49 => (2, 81, QUA),
        50 => (2, 100, QUA),
        51 => (2, 121, QUA),
        57 => (2, 24, QUA),
        58 => (2, 28, QUA),
        59 => (2, 32, QUA),
        61 => (2, 40, QUA),
        4 => (3, 4, TET),
        11 => (3, 10, TET),
        29 => (3, 20, TET),
        30 => (3, 35, TET),
        31 => (3, 56, TET),
        32 => (3, 22, TET),
        33 => (3, 28, TET),
        71 => (3, 84, TET),
        72 => (3, 120, TET),
        73 => (3, 165, TET),
        74 => (3, 220, TET),
        75 => (3, 286, TET),
        79..=83 => (3, 34 + 6 * (element_type as usize - 79), TET),
        137 => (3, 16, TET),
        5 => (3, 8, HEX),
        12 => (3, 27, HEX),
        17 => (3, 20, HEX),
        92 => (3, 64, HEX),
        93 => (3, 125, HEX),
        94 => (3, 216, HEX),
        95 => (3, 343, HEX),
        96 => (3, 512, HEX),
        97 => (3, 729, HEX),
        98 => (3, 1000, HEX),
        99..=105 => (3, 32 + 12 * (element_type as usize - 99), HEX),
        6 => (3, 6, PRI),
        13 => (3, 18, PRI),
        18 => (3, 15, PRI),
        90 => (3, 40, PRI),
        91 => (3, 75, PRI),
        106 => (3, 126, PRI),
        107 => (3, 196, PRI),
        108 => (3, 288, PRI),
        109 => (3, 405, PRI),
        110 => (3, 550, PRI),
        111..=117 => (3, 24 + 9 * (element_type as usize - 111), PRI),
        7 => (3, 5, PYR),
        14 => (3, 14, PYR),
        19 => (3, 13, PYR),
        118 => (3, 30, PYR),
        119 => (3, 55, PYR),
        120 => (3, 91, PYR),
        121 => (3, 140, PYR),
        122 => (3, 204, PYR),
        123 => (3, 285, PYR),
        124 => (3, 385, PYR),
        125..=131 => (3, 21 + 8 * (element_type as usize - 125), PYR),
        _ => return None,
    };
    Some(ElementInfo { dim, nodes, shape })
}

impl ElementInfo {
    /// Checks that an ASCII element line gave this type's number of node tags
    /// and copies them into `out`.
    pub(super) fn node_tags(
        &self,
        cur: &Cursor,
        at: usize,
        tag: i64,
        element_type: i64,
        nodes: &[i64],
        out: &mut Vec<u64>,
    ) -> Result<()> {
        if nodes.len() != self.nodes {
            return Err(cur.syntax(
                at,
                format!(
                    "expected {} node tags for element {tag} of type {element_type}, found {}",
                    self.nodes,
                    nodes.len()
                ),
            ));
        }
        out.clear();
        out.extend(nodes.iter().map(|&t| u64::try_from(t).unwrap_or(0)));
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn element_table_knows_the_linear_types() {
        let nodes = |t| element_info(t).map(|i| (i.dim, i.nodes));
        assert_eq!(nodes(4), Some((3, 4)));
        assert_eq!(nodes(5), Some((3, 8)));
        assert_eq!(nodes(2), Some((2, 3)));
        assert_eq!(nodes(3), Some((2, 4)));
        assert_eq!(nodes(15), Some((0, 1)));
        assert_eq!(nodes(11), Some((3, 10)));
        assert_eq!(nodes(17), Some((3, 20)));
        assert_eq!(nodes(66), Some((1, 11)));
        assert_eq!(nodes(83), Some((3, 58)));
        assert_eq!(nodes(105), Some((3, 104)));
        assert_eq!(nodes(117), Some((3, 78)));
        assert_eq!(nodes(131), Some((3, 69)));
        assert_eq!(nodes(0), None);
        assert_eq!(nodes(34), None); // polygons have no fixed node count
    }
}
