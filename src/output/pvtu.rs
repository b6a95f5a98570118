//! The result files of a distributed run (`mpirun -np N`): each process
//! writes the `.vtu` piece of the elements it owns (`NAME_0001_p3.vtu`:
//! those elements, the nodes they use, the fields restricted to them and a
//! point array `global_node`, the node's index in the whole mesh), and
//! rank 0 writes the `.pvtu` file that ParaView opens as one data set
//! (`NAME_0001.pvtu`, listing the pieces and their arrays), which the
//! `.pvd` lists.

use std::borrow::Cow;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::fields::{CellField, ConvergedIncrement, NodalField};
use super::observer::StepObserver;
use super::recovery::PatchRecovery;
use super::summary::Summary;
use super::{vtu, write_atomically, xml_escape};
use crate::mesh::{Element, Mesh};
use crate::Result;

/// This process's piece of every `.pvtu`.
#[derive(Clone, Debug)]
pub struct Pieces {
    pub rank: usize,
    /// The number of processes (and of pieces).
    pub parts: usize,
    /// The elements this process owns (indices into the mesh).
    pub elements: Vec<usize>,
    /// The patch recovery of the piece's nodes, made on the whole mesh
    /// ([`PatchRecovery::of_nodes`]: the process may hold only the
    /// elements it reads); `None` when no recovered field is written.
    pub recovery: Option<Arc<PatchRecovery>>,
}

impl Pieces {
    /// The piece of process `rank` of the data set `file` (`NAME_0001.pvtu`
    /// → `NAME_0001_p{rank}.vtu`).
    pub fn piece_file(file: &str, rank: usize) -> String {
        format!("{}_p{rank}.vtu", file.trim_end_matches(".pvtu"))
    }

    /// Write this process's piece of `file` into `dir`: its elements, the
    /// nodes they use and those entries of `point_data` and `cell_data`
    /// (given over the whole mesh), and `global_node`.
    pub fn write_piece(
        &self,
        dir: &Path,
        file: &str,
        mesh: &Mesh,
        point_data: &[vtu::Field],
        cell_data: &[vtu::Field],
        options: vtu::VtuOptions,
    ) -> Result<()> {
        let mut local = vec![usize::MAX; mesh.num_nodes()];
        let mut nodes = Vec::new();
        for &e in &self.elements {
            for &n in &mesh.elements[e].nodes {
                if local[n] == usize::MAX {
                    local[n] = nodes.len();
                    nodes.push(n);
                }
            }
        }
        let piece = Mesh {
            nodes: nodes.iter().map(|&n| mesh.nodes[n]).collect(),
            node_ids: nodes
                .iter()
                .filter_map(|&n| mesh.node_ids.get(n).copied())
                .collect(),
            elements: self
                .elements
                .iter()
                .map(|&e| {
                    let el = &mesh.elements[e];
                    Element {
                        kind: el.kind,
                        nodes: el.nodes.iter().map(|&n| local[n]).collect(),
                        id: el.id,
                    }
                })
                .collect(),
            ..Default::default()
        };
        let restrict = |values: &[f64], components: usize, entities: &[usize]| -> Vec<f64> {
            entities
                .iter()
                .flat_map(|&i| values[components * i..components * (i + 1)].iter().copied())
                .collect()
        };
        let global_node: Vec<f64> = nodes.iter().map(|&n| n as f64).collect();
        let point_values: Vec<Vec<f64>> = point_data
            .iter()
            .map(|f| restrict(f.values, f.components, &nodes))
            .collect();
        let cell_values: Vec<Vec<f64>> = cell_data
            .iter()
            .map(|f| restrict(f.values, f.components, &self.elements))
            .collect();
        let mut points: Vec<vtu::Field> = point_data
            .iter()
            .zip(&point_values)
            .map(|(f, v)| vtu::Field { values: v, ..*f })
            .collect();
        points.push(global_node_field(&global_node));
        let cells: Vec<vtu::Field> = cell_data
            .iter()
            .zip(&cell_values)
            .map(|(f, v)| vtu::Field { values: v, ..*f })
            .collect();
        vtu::write_vtu_with(
            &dir.join(Self::piece_file(file, self.rank)),
            &piece,
            &points,
            &cells,
            options,
        )
    }

    /// Write `file` (`.pvtu`) into `dir`: the arrays' names, types and
    /// components, and the `parts` pieces.
    pub fn write_pvtu(
        &self,
        dir: &Path,
        file: &str,
        point_data: &[vtu::Field],
        cell_data: &[vtu::Field],
    ) -> Result<()> {
        let mut text = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" \
             byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  \
             <PUnstructuredGrid GhostLevel=\"0\">\n",
        );
        let array = |text: &mut String, f: &vtu::Field| {
            let kind = match f.kind {
                vtu::ArrayKind::Float64 => "Float64",
                vtu::ArrayKind::Int64 => "Int64",
            };
            let _ = writeln!(
                text,
                "      <PDataArray type=\"{kind}\" Name=\"{}\" NumberOfComponents=\"{}\"/>",
                xml_escape(f.name),
                f.components
            );
        };
        let empty = [];
        let global = global_node_field(&empty);
        text.push_str("    <PPointData>\n");
        for f in point_data.iter().chain([&global]) {
            array(&mut text, f);
        }
        text.push_str("    </PPointData>\n");
        if !cell_data.is_empty() {
            text.push_str("    <PCellData>\n");
            for f in cell_data {
                array(&mut text, f);
            }
            text.push_str("    </PCellData>\n");
        }
        text.push_str(
            "    <PPoints>\n      <PDataArray type=\"Float64\" Name=\"Points\" \
             NumberOfComponents=\"3\"/>\n    </PPoints>\n",
        );
        for rank in 0..self.parts {
            let _ = writeln!(
                text,
                "    <Piece Source=\"{}\"/>",
                xml_escape(&Self::piece_file(file, rank))
            );
        }
        text.push_str("  </PUnstructuredGrid>\n</VTKFile>\n");
        write_atomically(&dir.join(file), |w| w.write_all(text.as_bytes()))
    }
}

/// The `global_node` point array of a piece.
fn global_node_field(values: &[f64]) -> vtu::Field<'_> {
    vtu::Field {
        name: "global_node",
        components: 1,
        values,
        kind: vtu::ArrayKind::Int64,
    }
}

/// The nodal and cell fields of an increment as VTU arrays over the whole
/// mesh (contact fields left out of a problem without contact): what the
/// [`super::ResultWriter`] and the [`PieceWriter`] write.
pub struct IncrementArrays<'a> {
    nodal: Vec<Array<'a>>,
    cells: Vec<Array<'a>>,
}

/// An array's name, components, number type and values.
type Array<'a> = (&'static str, usize, vtu::ArrayKind, Cow<'a, [f64]>);

impl<'a> IncrementArrays<'a> {
    /// The arrays of `nodal` and `cells`; the element stresses are
    /// computed once for all the fields that need them, and the recovered
    /// nodal fields use `recovery` (the mesh's patch recovery, made here
    /// if `None`).
    pub fn new(
        increment: &'a ConvergedIncrement,
        nodal: &[NodalField],
        cells: &[CellField],
        recovery: Option<&PatchRecovery>,
    ) -> Self {
        let has_contact = !increment.problem.contacts.is_empty();
        let nodal: Vec<NodalField> = nodal
            .iter()
            .copied()
            .filter(|f| has_contact || !f.needs_contact())
            .collect();
        let needs_recovery = nodal.iter().any(|f| f.is_recovered());
        let stresses = if needs_recovery || cells.iter().any(|f| f.needs_stress()) {
            increment.element_stresses()
        } else {
            Vec::new()
        };
        let mut recovered = if needs_recovery {
            let made;
            let recovery = match recovery {
                Some(r) => r,
                None => {
                    made = PatchRecovery::new(&increment.problem.model.mesh);
                    &made
                }
            };
            increment.recovered(&nodal, &stresses, recovery)
        } else {
            vec![Vec::new(); nodal.len()]
        };
        IncrementArrays {
            nodal: nodal
                .iter()
                .zip(recovered.iter_mut())
                .map(|(&f, values)| {
                    let values = if f.is_recovered() {
                        Cow::Owned(std::mem::take(values))
                    } else {
                        increment.nodal(f)
                    };
                    (f.name(), f.components(), f.kind(), values)
                })
                .collect(),
            cells: cells
                .iter()
                .zip(increment.cells_from(cells, &stresses))
                .map(|(f, v)| (f.name(), f.components(), f.kind(), Cow::Owned(v)))
                .collect(),
        }
    }

    /// The arrays of the reference state, `u = 0` before any load (the
    /// t = 0 frame): zero displacements, stresses, strains and contact
    /// fields, the gap NaN (it is first evaluated at the first increment),
    /// the node ids and regions of `mesh`.
    pub fn reference(
        mesh: &Mesh,
        has_contact: bool,
        nodal: &[NodalField],
        cells: &[CellField],
    ) -> IncrementArrays<'static> {
        let n = mesh.num_nodes();
        let nodal = nodal
            .iter()
            .filter(|f| has_contact || !f.needs_contact())
            .map(|&f| {
                let values = match f {
                    NodalField::NodeId => mesh.node_ids.iter().map(|&id| id as f64).collect(),
                    NodalField::Gap => vec![f64::NAN; n],
                    _ => vec![0.0; f.components() * n],
                };
                (f.name(), f.components(), f.kind(), Cow::Owned(values))
            })
            .collect();
        let cells = cells
            .iter()
            .map(|&f| {
                let values = match f {
                    CellField::Region => super::fields::region_indices(mesh),
                    _ => vec![0.0; f.components() * mesh.elements.len()],
                };
                (f.name(), f.components(), f.kind(), Cow::Owned(values))
            })
            .collect();
        IncrementArrays { nodal, cells }
    }

    /// The point arrays.
    pub fn points(&self) -> Vec<vtu::Field<'_>> {
        fields(&self.nodal)
    }

    /// The cell arrays.
    pub fn cells(&self) -> Vec<vtu::Field<'_>> {
        fields(&self.cells)
    }
}

fn fields<'b>(arrays: &'b [Array<'_>]) -> Vec<vtu::Field<'b>> {
    arrays
        .iter()
        .map(|(name, components, kind, values)| vtu::Field {
            name,
            components: *components,
            values,
            kind: *kind,
        })
        .collect()
}

/// The data set file of the last increment in `summary` (empty when
/// `[output] every` left it without one).
pub fn data_set_file(summary: &Summary) -> String {
    summary
        .increments
        .last()
        .map(|i| i.file.clone())
        .unwrap_or_default()
}

/// The result files of a process other than rank 0 in a distributed run:
/// its piece of every `.pvtu` (rank 0's [`super::ResultWriter`] writes
/// the rest).
pub struct PieceWriter {
    pub dir: PathBuf,
    pub pieces: Pieces,
    pub nodal: Vec<NodalField>,
    pub cells: Vec<CellField>,
    pub options: vtu::VtuOptions,
}

impl StepObserver for PieceWriter {
    fn on_increment(&mut self, increment: &ConvergedIncrement, summary: &Summary) -> Result<()> {
        let file = data_set_file(summary);
        if file.is_empty() {
            return Ok(());
        }
        let recovery = self.pieces.recovery.as_deref();
        let arrays = IncrementArrays::new(increment, &self.nodal, &self.cells, recovery);
        self.pieces.write_piece(
            &self.dir,
            &file,
            &increment.problem.model.mesh,
            &arrays.points(),
            &arrays.cells(),
            self.options,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::structured::box_mesh;
    use crate::mesh::ElementKind;

    #[test]
    fn pieces_hold_their_elements_nodes_and_values() {
        let mesh = box_mesh(ElementKind::Hex8, [2, 1, 1], [2.0, 1.0, 1.0]);
        let dir = tempfile::tempdir().unwrap();
        let u: Vec<f64> = (0..3 * mesh.num_nodes()).map(|i| i as f64).collect();
        let fields = [vtu::Field {
            name: "displacement",
            components: 3,
            values: &u,
            kind: vtu::ArrayKind::Float64,
        }];
        for rank in 0..2 {
            let pieces = Pieces {
                rank,
                parts: 2,
                elements: vec![rank],
                recovery: None,
            };
            pieces
                .write_piece(
                    dir.path(),
                    "r_0001.pvtu",
                    &mesh,
                    &fields,
                    &[],
                    Default::default(),
                )
                .unwrap();
            let piece = dir.path().join(format!("r_0001_p{rank}.vtu"));
            let global = vtu::read_point_field(&piece, "global_node").unwrap();
            let d = vtu::read_point_field(&piece, "displacement").unwrap();
            assert_eq!(global.len(), 8);
            let nodes = &mesh.elements[rank].nodes;
            for (k, &g) in global.iter().enumerate() {
                assert!(nodes.contains(&(g as usize)));
                assert_eq!(&d[3 * k..3 * k + 3], &u[3 * g as usize..3 * g as usize + 3]);
            }
        }
        Pieces {
            rank: 0,
            parts: 2,
            elements: vec![0],
            recovery: None,
        }
        .write_pvtu(dir.path(), "r_0001.pvtu", &fields, &[])
        .unwrap();
        let text = std::fs::read_to_string(dir.path().join("r_0001.pvtu")).unwrap();
        assert!(text.contains("<Piece Source=\"r_0001_p1.vtu\"/>"), "{text}");
        assert!(text.contains("Name=\"displacement\" NumberOfComponents=\"3\""));
    }
}
