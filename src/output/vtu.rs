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
    // One component is VTK's default; leaving the attribute out makes
    // meshio read scalars as 1-D arrays.
    let components = if components == 1 {
        String::new()
    } else {
        format!(" NumberOfComponents=\"{components}\"")
    };
    write!(
        w,
        "        <DataArray type=\"{vtk_type}\" Name=\"{}\"{components} format=\"binary\">\n          ",
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

/// Reads the `Float64` point-data array `name` of a `.vtu` file written by
/// [`write_vtu`] (for scripts and tests that check results; ParaView and
/// meshio read every array). Fails, naming the file and the array, if the
/// file cannot be read or holds no such array.
pub fn read_point_field(path: &Path, name: &str) -> crate::Result<Vec<f64>> {
    let fail = |message: String| crate::Error::io("read", path, invalid_input(message));
    let text = std::fs::read_to_string(path).map_err(|e| crate::Error::io("read", path, e))?;
    let point_data = text
        .find("<PointData>")
        .ok_or_else(|| fail("no <PointData> section".into()))?;
    let end = text[point_data..]
        .find("</PointData>")
        .map_or(text.len(), |e| point_data + e);
    let section = &text[point_data..end];
    let tag = format!("<DataArray type=\"Float64\" Name=\"{}\"", xml_escape(name));
    let start = section
        .find(&tag)
        .ok_or_else(|| fail(format!("no Float64 point-data array '{name}'")))?;
    let open_end = start + section[start..].find('>').unwrap_or(0) + 1;
    let close = section[open_end..]
        .find("</DataArray>")
        .map(|c| open_end + c)
        .ok_or_else(|| fail(format!("array '{name}' is not closed")))?;
    use base64::Engine;
    let bytes = STANDARD
        .decode(section[open_end..close].trim())
        .map_err(|e| fail(format!("array '{name}': {e}")))?;
    if bytes.len() < 8 || (bytes.len() - 8) % 8 != 0 {
        return Err(fail(format!("array '{name}' has {} bytes", bytes.len())));
    }
    Ok(bytes[8..]
        .chunks_exact(8)
        .map(|c| {
            let mut b = [0u8; 8];
            b.copy_from_slice(c); // chunks_exact(8): 8 bytes
            f64::from_le_bytes(b)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::structured::box_mesh;
    use crate::mesh::ElementKind;
    use base64::Engine;
    use std::collections::HashMap;

    /// One `<DataArray>` read back: its section, attributes and raw bytes.
    struct Array {
        section: String,
        attributes: HashMap<String, String>,
        bytes: Vec<u8>,
    }

    impl Array {
        fn f64s(&self) -> Vec<f64> {
            assert_eq!(self.attributes["type"], "Float64");
            self.bytes
                .chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
                .collect()
        }
        fn i64s(&self) -> Vec<i64> {
            assert_eq!(self.attributes["type"], "Int64");
            self.bytes
                .chunks_exact(8)
                .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
                .collect()
        }
        fn components(&self) -> usize {
            self.attributes
                .get("NumberOfComponents")
                .map_or(1, |n| n.parse().unwrap())
        }
    }

    /// Attributes of the tag that starts at the beginning of `tag`.
    fn attributes(tag: &str) -> HashMap<String, String> {
        let tag = &tag[..tag.find('>').unwrap()];
        let mut map = HashMap::new();
        let mut rest = tag;
        while let Some(eq) = rest.find("=\"") {
            let key = rest[..eq].rsplit(' ').next().unwrap().to_string();
            let value_start = eq + 2;
            let value_len = rest[value_start..].find('"').unwrap();
            map.insert(key, rest[value_start..value_start + value_len].to_string());
            rest = &rest[value_start + value_len + 1..];
        }
        map
    }

    /// A minimal reader for what [`write_vtu`] writes.
    fn read_vtu(path: &Path) -> (HashMap<String, String>, HashMap<String, String>, Vec<Array>) {
        let text = std::fs::read_to_string(path).unwrap();
        assert!(text.starts_with("<?xml"));
        let vtk_file = attributes(&text[text.find("<VTKFile").unwrap()..]);
        let piece = attributes(&text[text.find("<Piece").unwrap()..]);
        let mut arrays = Vec::new();
        let mut at = 0;
        while let Some(start) = text[at..].find("<DataArray ") {
            let start = at + start;
            let open_end = start + text[start..].find('>').unwrap() + 1;
            let close = open_end + text[open_end..].find("</DataArray>").unwrap();
            let before = &text[..start];
            let section = ["<Points>", "<Cells>", "<PointData>", "<CellData>"]
                .iter()
                .max_by_key(|s| before.rfind(*s).map_or(-1, |i| i as i64))
                .unwrap()
                .trim_matches(|c| c == '<' || c == '>')
                .to_string();
            let attrs = attributes(&text[start..]);
            assert_eq!(attrs["format"], "binary");
            let decoded = base64::engine::general_purpose::STANDARD
                .decode(text[open_end..close].trim())
                .unwrap();
            let header = u64::from_le_bytes(decoded[..8].try_into().unwrap()) as usize;
            assert_eq!(header, decoded.len() - 8, "byte count header of {attrs:?}");
            arrays.push(Array {
                section,
                attributes: attrs,
                bytes: decoded[8..].to_vec(),
            });
            at = close;
        }
        (vtk_file, piece, arrays)
    }

    fn find<'a>(arrays: &'a [Array], section: &str, name: &str) -> &'a Array {
        arrays
            .iter()
            .find(|a| a.section == section && a.attributes["Name"] == name)
            .unwrap_or_else(|| panic!("no array {name} in {section}"))
    }

    fn round_trip(kind: ElementKind) {
        let mesh = box_mesh(kind, [2, 2, 2], [1.0, 1.0, 1.0]);
        let (np, nc) = (mesh.nodes.len(), mesh.elements.len());
        // Values that do not survive a decimal round trip, plus extremes.
        let mut displacement: Vec<f64> =
            (0..3 * np).map(|i| (i as f64 * 0.7).sin() / 3.0).collect();
        displacement[0] = f64::MIN_POSITIVE;
        displacement[1] = -1e300;
        let stress: Vec<f64> = (0..9 * nc).map(|i| (i as f64).sqrt() * 1e5 - 7.0).collect();
        let id: Vec<f64> = (0..nc).map(|i| mesh.elements[i].id as f64).collect();

        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.vtu");
        write_vtu(
            &path,
            &mesh,
            &[Field {
                name: "displacement",
                components: 3,
                values: &displacement,
            }],
            &[
                Field {
                    name: "stress",
                    components: 9,
                    values: &stress,
                },
                Field {
                    name: "element id",
                    components: 1,
                    values: &id,
                },
            ],
        )
        .unwrap();

        let (vtk_file, piece, arrays) = read_vtu(&path);
        assert_eq!(vtk_file["type"], "UnstructuredGrid");
        assert_eq!(vtk_file["header_type"], "UInt64");
        assert_eq!(vtk_file["byte_order"], "LittleEndian");
        assert_eq!(piece["NumberOfPoints"], np.to_string());
        assert_eq!(piece["NumberOfCells"], nc.to_string());
        assert_eq!(arrays.len(), 7);

        let points = find(&arrays, "Points", "Points");
        assert_eq!(points.components(), 3);
        let expected: Vec<f64> = mesh.nodes.iter().flatten().copied().collect();
        assert_eq!(points.f64s(), expected);

        let connectivity = find(&arrays, "Cells", "connectivity").i64s();
        let expected: Vec<i64> = mesh
            .elements
            .iter()
            .flat_map(|e| e.nodes.iter().map(|&n| n as i64))
            .collect();
        assert_eq!(connectivity, expected);
        let offsets = find(&arrays, "Cells", "offsets").i64s();
        let n = kind.num_nodes() as i64;
        assert_eq!(offsets, (1..=nc as i64).map(|i| i * n).collect::<Vec<_>>());
        let types = find(&arrays, "Cells", "types");
        assert_eq!(types.attributes["type"], "UInt8");
        assert_eq!(types.bytes, vec![kind.vtk_type(); nc]);

        let u = find(&arrays, "PointData", "displacement");
        assert_eq!(u.components(), 3);
        assert_eq!(u.f64s(), displacement);
        let s = find(&arrays, "CellData", "stress");
        assert_eq!(s.components(), 9);
        assert_eq!(s.f64s(), stress);
        let e = find(&arrays, "CellData", "element id");
        assert!(!e.attributes.contains_key("NumberOfComponents"));
        assert_eq!(e.components(), 1);
        assert_eq!(e.f64s(), id);
        // Only the target is left in the folder (the temporary was renamed).
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn hex8_round_trip() {
        round_trip(ElementKind::Hex8);
    }

    #[test]
    fn tet4_round_trip() {
        round_trip(ElementKind::Tet4);
    }

    #[test]
    fn mesh_without_data() {
        let mesh = box_mesh(ElementKind::Hex8, [1, 1, 1], [2.0, 1.0, 1.0]);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bare.vtu");
        write_vtu(&path, &mesh, &[], &[]).unwrap();
        let (_, piece, arrays) = read_vtu(&path);
        assert_eq!(piece["NumberOfPoints"], "8");
        assert_eq!(piece["NumberOfCells"], "1");
        assert_eq!(arrays.len(), 4);
    }

    #[test]
    fn wrong_length_is_an_error_naming_the_field() {
        let mesh = box_mesh(ElementKind::Hex8, [2, 2, 2], [1.0, 1.0, 1.0]);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bad.vtu");
        let good = vec![0.0; 3 * 27];
        let short = vec![0.0; 9 * 8 - 1];
        let err = write_vtu(
            &path,
            &mesh,
            &[Field {
                name: "displacement",
                components: 3,
                values: &good,
            }],
            &[Field {
                name: "cauchy_stress",
                components: 9,
                values: &short,
            }],
        )
        .unwrap_err();
        let message = err.to_string();
        assert!(message.contains("cauchy_stress"), "{message}");
        assert!(message.contains("71 values"), "{message}");
        assert!(message.contains("72"), "{message}");
        assert!(!path.exists());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);

        // A point field sized for cells.
        let err = write_vtu(
            &path,
            &mesh,
            &[Field {
                name: "pressure",
                components: 1,
                values: &[0.0; 8],
            }],
            &[],
        )
        .unwrap_err();
        assert!(err.to_string().contains("point field 'pressure'"), "{err}");

        // Zero components and duplicate names.
        let err = write_vtu(
            &path,
            &mesh,
            &[Field {
                name: "z",
                components: 0,
                values: &[],
            }],
            &[],
        )
        .unwrap_err();
        assert!(err.to_string().contains("'z'"), "{err}");
        let f = Field {
            name: "u",
            components: 3,
            values: &good,
        };
        let err = write_vtu(&path, &mesh, &[f, f], &[]).unwrap_err();
        assert!(err.to_string().contains("'u'"), "{err}");
        assert!(!path.exists());
    }

    #[test]
    fn bad_connectivity_is_an_error() {
        let mut mesh = box_mesh(ElementKind::Tet4, [1, 1, 1], [1.0, 1.0, 1.0]);
        mesh.elements[0].nodes[2] = 1000;
        let dir = tempfile::tempdir().unwrap();
        let err = write_vtu(&dir.path().join("m.vtu"), &mesh, &[], &[]).unwrap_err();
        assert!(err.to_string().contains("node index"), "{err}");
    }

    #[test]
    fn field_names_are_escaped() {
        let mesh = box_mesh(ElementKind::Tet4, [1, 1, 1], [1.0, 1.0, 1.0]);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("e.vtu");
        let values = vec![1.0; mesh.nodes.len()];
        write_vtu(
            &path,
            &mesh,
            &[Field {
                name: "a<\"b\">&c",
                components: 1,
                values: &values,
            }],
            &[],
        )
        .unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains(r#"Name="a&lt;&quot;b&quot;&gt;&amp;c""#));
    }
}
