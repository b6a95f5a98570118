//! VTK XML UnstructuredGrid (`.vtu`) files of the reference mesh with point
//! and cell data.
//!
//! The file holds the reference coordinates `X` as points; results such as
//! the displacement are point data (ParaView: *Warp By Vector* with the
//! `displacement` field shows the deformed configuration). Every array is
//! written as inline base64 binary (`format="binary"`, `header_type="UInt64"`,
//! little endian, uncompressed): each array's base64 text encodes an 8-byte
//! byte count followed by the raw values. Readers: ParaView/VTK, meshio.
//!
//! Arrays with 9 components are full 3×3 tensors in row-major order
//! (`T11 T12 T13 T21 … T33`), which ParaView recognises as tensors.

use std::io::{self, Write};
use std::path::Path;

use base64::engine::general_purpose::STANDARD;
use base64::write::EncoderWriter;

use super::{invalid_input, write_atomically, xml_escape};
use crate::mesh::Mesh;

/// A named data array: `values` holds `components` numbers per point (or
/// per cell), entity by entity (`[u0x, u0y, u0z, u1x, …]`).
#[derive(Clone, Copy, Debug)]
pub struct Field<'a> {
    /// Array name shown in ParaView.
    pub name: &'a str,
    /// Numbers per entity: 1 scalar, 3 vector, 6 symmetric tensor (Voigt),
    /// 9 full tensor (row-major).
    pub components: usize,
    /// `components × count` values.
    pub values: &'a [f64],
}

/// Writes `mesh` (reference configuration, every volume element) with the
/// given point and cell data to `path` as a `.vtu` file, atomically.
///
/// Fails, naming the field, if a field's length is not `components ×` the
/// number of points (cells), if it has no components or no name, or if two
/// fields of the same kind share a name; fails if an element refers to a
/// node that does not exist. Nothing is written in those cases.
pub fn write_vtu(
    path: &Path,
    mesh: &Mesh,
    point_data: &[Field],
    cell_data: &[Field],
) -> crate::Result<()> {
    let num_points = mesh.nodes.len();
    let num_cells = mesh.elements.len();
    validate(path, "point", point_data, num_points)?;
    validate(path, "cell", cell_data, num_cells)?;
    for element in &mesh.elements {
        let bad_count = element.nodes.len() != element.kind.num_nodes();
        if bad_count || element.nodes.iter().any(|&n| n >= num_points) {
            let message = if bad_count {
                format!(
                    "element {} has {} nodes, a {:?} has {}",
                    element.id,
                    element.nodes.len(),
                    element.kind,
                    element.kind.num_nodes()
                )
            } else {
                format!(
                    "element {} refers to a node index beyond the {} nodes of the mesh",
                    element.id, num_points
                )
            };
            return Err(crate::Error::io("write", path, invalid_input(message)));
        }
    }

    write_atomically(path, |w| {
        writeln!(w, r#"<?xml version="1.0"?>"#)?;
        writeln!(
            w,
            r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">"#
        )?;
        writeln!(w, "  <UnstructuredGrid>")?;
        writeln!(
            w,
            r#"    <Piece NumberOfPoints="{num_points}" NumberOfCells="{num_cells}">"#
        )?;

        writeln!(w, "      <Points>")?;
        data_array(
            w,
            "Float64",
            "Points",
            3,
            mesh.nodes.iter().flat_map(|x| x.iter().copied()),
            3 * num_points,
        )?;
        writeln!(w, "      </Points>")?;

        writeln!(w, "      <Cells>")?;
        let connectivity_len: usize = mesh.elements.iter().map(|e| e.nodes.len()).sum();
        data_array(
            w,
            "Int64",
            "connectivity",
            1,
            mesh.elements
                .iter()
                .flat_map(|e| e.nodes.iter().map(|&n| n as i64)),
            connectivity_len,
        )?;
        data_array(
            w,
            "Int64",
            "offsets",
            1,
            mesh.elements.iter().scan(0i64, |end, e| {
                *end += e.nodes.len() as i64;
                Some(*end)
            }),
            num_cells,
        )?;
        data_array(
            w,
            "UInt8",
            "types",
            1,
            mesh.elements.iter().map(|e| e.kind.vtk_type()),
            num_cells,
        )?;
        writeln!(w, "      </Cells>")?;

        for (tag, fields) in [("PointData", point_data), ("CellData", cell_data)] {
            if fields.is_empty() {
                continue;
            }
            writeln!(w, "      <{tag}>")?;
            for field in fields {
                data_array(
                    w,
                    "Float64",
                    field.name,
                    field.components,
                    field.values.iter().copied(),
                    field.values.len(),
                )?;
            }
            writeln!(w, "      </{tag}>")?;
        }

        writeln!(w, "    </Piece>")?;
        writeln!(w, "  </UnstructuredGrid>")?;
        writeln!(w, "</VTKFile>")?;
        Ok(())
    })
}

/// Checks names, component counts and lengths of the fields of one kind.
fn validate(path: &Path, kind: &str, fields: &[Field], count: usize) -> crate::Result<()> {
    let fail = |message: String| Err(crate::Error::io("write", path, invalid_input(message)));
    for (i, field) in fields.iter().enumerate() {
        if field.name.is_empty() {
            return fail(format!("{kind} field number {} has an empty name", i + 1));
        }
        if field.components == 0 {
            return fail(format!("{kind} field '{}' has 0 components", field.name));
        }
        let expected = field.components.checked_mul(count);
        if expected != Some(field.values.len()) {
            return fail(format!(
                "{kind} field '{}' has {} values, expected {} components × {count} {kind}s = {}",
                field.name,
                field.values.len(),
                field.components,
                expected.map_or_else(|| "too many".to_string(), |n| n.to_string()),
            ));
        }
        if fields[..i].iter().any(|f| f.name == field.name) {
            return fail(format!("two {kind} fields are named '{}'", field.name));
        }
    }
    Ok(())
}

/// A number that goes into a binary data array, little endian.
trait Scalar: Copy {
    const SIZE: usize;
    fn push_le(self, buffer: &mut Vec<u8>);
}

impl Scalar for f64 {
    const SIZE: usize = 8;
    fn push_le(self, buffer: &mut Vec<u8>) {
        buffer.extend_from_slice(&self.to_le_bytes());
    }
}

impl Scalar for i64 {
    const SIZE: usize = 8;
    fn push_le(self, buffer: &mut Vec<u8>) {
        buffer.extend_from_slice(&self.to_le_bytes());
    }
}

impl Scalar for u8 {
    const SIZE: usize = 1;
    fn push_le(self, buffer: &mut Vec<u8>) {
        buffer.push(self);
    }
}

/// Writes one `<DataArray>` of `len` values: base64 of the UInt64 byte count
/// followed by the values, as one base64 stream.
fn data_array<T: Scalar>(
    w: &mut dyn Write,
    vtk_type: &str,
    name: &str,
    components: usize,
    values: impl Iterator<Item = T>,
    len: usize,
) -> io::Result<()> {
    write!(
        w,
        "        <DataArray type=\"{vtk_type}\" Name=\"{}\" \
         NumberOfComponents=\"{components}\" format=\"binary\">\n          ",
        xml_escape(name)
    )?;
    {
        const CHUNK: usize = 3 * 16 * 1024;
        let mut encoder = EncoderWriter::new(&mut *w, &STANDARD);
        let mut buffer = Vec::with_capacity(CHUNK + 8);
        buffer.extend_from_slice(&((len * T::SIZE) as u64).to_le_bytes());
        let mut written = 0usize;
        for value in values {
            value.push_le(&mut buffer);
            written += 1;
            if buffer.len() >= CHUNK {
                encoder.write_all(&buffer)?;
                buffer.clear();
            }
        }
        encoder.write_all(&buffer)?;
        encoder.finish()?;
        if written != len {
            return Err(io::Error::other(format!(
                "internal error: array '{name}' has {written} values, announced {len}"
            )));
        }
    }
    writeln!(w)?;
    writeln!(w, "        </DataArray>")?;
    Ok(())
}
