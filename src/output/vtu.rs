//! VTK XML UnstructuredGrid (`.vtu`) files of the reference mesh with point
//! and cell data.
//!
//! The file holds the reference coordinates `X` as points; results such as
//! the displacement are point data (ParaView: *Warp By Vector* with the
//! `displacement` field shows the deformed configuration). Every array is
//! written as inline base64 binary (`format="binary"`, `header_type="UInt64"`,
//! little endian). Uncompressed, each array's base64 text encodes an 8-byte
//! byte count followed by the raw values. Compressed (zlib, VTK's
//! `vtkZLibDataCompressor`, what runs write by default), each array is cut
//! into blocks of 32 KiB, each block deflated, and the text is the base64
//! of the header `[blocks, block size, last partial block size (0 if
//! full), compressed size of each block]` followed by the base64 of the
//! compressed blocks (two base64 runs, as VTK writes them). Readers:
//! ParaView/VTK, meshio.
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
    /// The array's type in the file (integer arrays hold whole numbers).
    pub kind: ArrayKind,
}

/// The number type of an array in the file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ArrayKind {
    #[default]
    Float64,
    /// Whole numbers (node ids, region indices, status codes).
    Int64,
}

/// How the file is written.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct VtuOptions {
    /// zlib compression of every array.
    pub compress: bool,
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
    write_vtu_with(path, mesh, point_data, cell_data, VtuOptions::default())
}

/// [`write_vtu`], compressed or not as `options` says.
pub fn write_vtu_with(
    path: &Path,
    mesh: &Mesh,
    point_data: &[Field],
    cell_data: &[Field],
    options: VtuOptions,
) -> crate::Result<()> {
    let arrays = MeshArrays::new(mesh, options).map_err(|e| crate::Error::io("write", path, e))?;
    write_vtu_on(path, &arrays, point_data, cell_data)
}

/// The points and cells of a mesh as every VTU file of it holds them (the
/// `<Points>` and `<Cells>` elements, encoded): the same bytes at every
/// increment of a run, so a series encodes them once
/// ([`super::writer::ResultWriter`], beside the solve).
#[derive(Debug)]
pub struct MeshArrays {
    num_points: usize,
    num_cells: usize,
    options: VtuOptions,
    /// The encoded `<Points>` and `<Cells>` elements.
    text: Vec<u8>,
}

impl MeshArrays {
    /// The encoded points and cells of `mesh` (reference configuration,
    /// every volume element); an error if an element has the wrong number
    /// of nodes or refers to a node that does not exist.
    pub fn new(mesh: &Mesh, options: VtuOptions) -> io::Result<Self> {
        let num_points = mesh.nodes.len();
        let num_cells = mesh.elements.len();
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
                return Err(invalid_input(message));
            }
        }
        let compress = options.compress;
        let mut text = Vec::new();
        let w: &mut dyn Write = &mut text;
        writeln!(w, "      <Points>")?;
        data_array(
            w,
            compress,
            ("Float64", "Points", 3),
            mesh.nodes.iter().flat_map(|x| x.iter().copied()),
            3 * num_points,
        )?;
        writeln!(w, "      </Points>")?;

        writeln!(w, "      <Cells>")?;
        let connectivity_len: usize = mesh.elements.iter().map(|e| e.nodes.len()).sum();
        data_array(
            w,
            compress,
            ("Int64", "connectivity", 1),
            // VTK's node order ([`ElementKind::vtk_order`]: the mid-side
            // nodes of the quadratic cells differ from Gmsh's)
            mesh.elements
                .iter()
                .flat_map(|e| e.kind.vtk_order().iter().map(|&a| e.nodes[a] as i64)),
            connectivity_len,
        )?;
        data_array(
            w,
            compress,
            ("Int64", "offsets", 1),
            mesh.elements.iter().scan(0i64, |end, e| {
                *end += e.nodes.len() as i64;
                Some(*end)
            }),
            num_cells,
        )?;
        data_array(
            w,
            compress,
            ("UInt8", "types", 1),
            mesh.elements.iter().map(|e| e.kind.vtk_type()),
            num_cells,
        )?;
        writeln!(w, "      </Cells>")?;
        Ok(MeshArrays {
            num_points,
            num_cells,
            options,
            text,
        })
    }
}

/// [`write_vtu_with`] on a mesh's points and cells encoded before, with
/// the point and cell data in the same form (compressed or not).
pub fn write_vtu_on(
    path: &Path,
    mesh: &MeshArrays,
    point_data: &[Field],
    cell_data: &[Field],
) -> crate::Result<()> {
    let (num_points, num_cells) = (mesh.num_points, mesh.num_cells);
    validate(path, "point", point_data, num_points)?;
    validate(path, "cell", cell_data, num_cells)?;
    let compress = mesh.options.compress;
    // every array encoded side by side (their sizes differ: the stress is
    // most of the bytes), then written in order
    let encoded: Vec<Vec<u8>> = {
        use rayon::prelude::*;
        point_data
            .par_iter()
            .chain(cell_data.par_iter())
            .map(|field| {
                let mut text = Vec::new();
                field_array(&mut text, compress, field)?;
                Ok(text)
            })
            .collect::<io::Result<_>>()
            .map_err(|e| crate::Error::io("write", path, e))?
    };
    let (point_text, cell_text) = encoded.split_at(point_data.len());
    write_atomically(path, |w| {
        writeln!(w, r#"<?xml version="1.0"?>"#)?;
        let compressor = if compress {
            r#" compressor="vtkZLibDataCompressor""#
        } else {
            ""
        };
        writeln!(
            w,
            r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64"{compressor}>"#
        )?;
        writeln!(w, "  <UnstructuredGrid>")?;
        writeln!(
            w,
            r#"    <Piece NumberOfPoints="{num_points}" NumberOfCells="{num_cells}">"#
        )?;
        w.write_all(&mesh.text)?;

        for (tag, texts) in [("PointData", point_text), ("CellData", cell_text)] {
            if texts.is_empty() {
                continue;
            }
            writeln!(w, "      <{tag}>")?;
            for text in texts {
                w.write_all(text)?;
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
        if field.kind == ArrayKind::Int64
            && !field
                .values
                .iter()
                .all(|v| v.fract() == 0.0 && v.abs() < 9.0e15)
        {
            return fail(format!(
                "{kind} field '{}' is an integer array but holds a value that is not a whole number",
                field.name
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

/// The `<DataArray>` element of `field`, in its number type.
fn field_array(w: &mut dyn Write, compress: bool, field: &Field) -> io::Result<()> {
    let (name, components, len) = (field.name, field.components, field.values.len());
    match field.kind {
        ArrayKind::Float64 => data_array(
            w,
            compress,
            ("Float64", name, components),
            field.values.iter().copied(),
            len,
        ),
        ArrayKind::Int64 => data_array(
            w,
            compress,
            ("Int64", name, components),
            field.values.iter().map(|&v| v as i64),
            len,
        ),
    }
}

/// Writes one `<DataArray>` of `len` values: uncompressed, base64 of the
/// UInt64 byte count followed by the values, as one base64 stream;
/// compressed, see the module docs.
fn data_array<T: Scalar>(
    w: &mut dyn Write,
    compress: bool,
    (vtk_type, name, components): (&str, &str, usize),
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
    let mut written = 0usize;
    let mut counted = values.inspect(|_| written += 1);
    if compress {
        write_compressed(w, &mut counted, len * T::SIZE)?;
    } else {
        const CHUNK: usize = 3 * 16 * 1024;
        let mut encoder = EncoderWriter::new(&mut *w, &STANDARD);
        let mut buffer = Vec::with_capacity(CHUNK + 8);
        buffer.extend_from_slice(&((len * T::SIZE) as u64).to_le_bytes());
        for value in counted.by_ref() {
            value.push_le(&mut buffer);
            if buffer.len() >= CHUNK {
                encoder.write_all(&buffer)?;
                buffer.clear();
            }
        }
        encoder.write_all(&buffer)?;
        encoder.finish()?;
    }
    drop(counted);
    if written != len {
        return Err(io::Error::other(format!(
            "internal error: array '{name}' has {written} values, announced {len}"
        )));
    }
    writeln!(w)?;
    writeln!(w, "        </DataArray>")?;
    Ok(())
}

/// Uncompressed bytes per block of a compressed array (VTK's default).
const BLOCK: usize = 32 * 1024;

/// The compressed form of an array of `bytes` bytes (module docs): the
/// blocks deflated side by side, then the header and the blocks written as
/// two base64 runs.
fn write_compressed<T: Scalar>(
    w: &mut dyn Write,
    values: &mut dyn Iterator<Item = T>,
    bytes: usize,
) -> io::Result<()> {
    use flate2::{write::ZlibEncoder, Compression};
    use rayon::prelude::*;
    let mut raw = Vec::with_capacity(bytes);
    for value in values {
        value.push_le(&mut raw);
    }
    // the blocks are independent: deflated side by side, in order
    let blocks: Vec<Vec<u8>> = raw
        .par_chunks(BLOCK)
        .map(|block| {
            let mut z = ZlibEncoder::new(Vec::new(), Compression::fast());
            z.write_all(block)?;
            z.finish()
        })
        .collect::<io::Result<_>>()?;
    let mut header: Vec<u8> = Vec::with_capacity(8 * (3 + blocks.len()));
    for n in [blocks.len(), BLOCK, bytes % BLOCK]
        .into_iter()
        .chain(blocks.iter().map(Vec::len))
    {
        header.extend_from_slice(&(n as u64).to_le_bytes());
    }
    let mut encoder = EncoderWriter::new(&mut *w, &STANDARD);
    encoder.write_all(&header)?;
    encoder.finish()?;
    drop(encoder);
    let mut encoder = EncoderWriter::new(&mut *w, &STANDARD);
    for block in &blocks {
        encoder.write_all(block)?;
    }
    encoder.finish()?;
    Ok(())
}

/// Reads the point-data array `name` of a `.vtu` file written by
/// [`write_vtu_with`], compressed or not, `Float64` or `Int64` (as `f64`),
/// for scripts and tests that check results (ParaView and meshio read
/// every array). Fails, naming the file and the array, if the file cannot
/// be read or holds no such array.
pub fn read_point_field(path: &Path, name: &str) -> crate::Result<Vec<f64>> {
    let fail = |message: String| crate::Error::io("read", path, invalid_input(message));
    let text = std::fs::read_to_string(path).map_err(|e| crate::Error::io("read", path, e))?;
    let compressed = text.contains(r#"compressor="vtkZLibDataCompressor""#);
    let point_data = text
        .find("<PointData>")
        .ok_or_else(|| fail("no <PointData> section".into()))?;
    let end = text[point_data..]
        .find("</PointData>")
        .map_or(text.len(), |e| point_data + e);
    let section = &text[point_data..end];
    let (start, integer) = [("Float64", false), ("Int64", true)]
        .iter()
        .find_map(|(t, integer)| {
            let tag = format!("<DataArray type=\"{t}\" Name=\"{}\"", xml_escape(name));
            section.find(&tag).map(|s| (s, *integer))
        })
        .ok_or_else(|| fail(format!("no Float64 or Int64 point-data array '{name}'")))?;
    let open_end = start + section[start..].find('>').unwrap_or(0) + 1;
    let close = section[open_end..]
        .find("</DataArray>")
        .map(|c| open_end + c)
        .ok_or_else(|| fail(format!("array '{name}' is not closed")))?;
    let bytes = decode_array(section[open_end..close].trim(), compressed)
        .map_err(|e| fail(format!("array '{name}': {e}")))?;
    Ok(bytes
        .chunks_exact(8)
        .map(|c| {
            let b: [u8; 8] = c.try_into().unwrap_or_default();
            if integer {
                i64::from_le_bytes(b) as f64
            } else {
                f64::from_le_bytes(b)
            }
        })
        .collect())
}

/// The raw bytes of an array's base64 text (module docs for both forms).
fn decode_array(text: &str, compressed: bool) -> Result<Vec<u8>, String> {
    use base64::Engine;
    let text: String = text.split_whitespace().collect();
    if !compressed {
        let bytes = STANDARD.decode(&text).map_err(|e| e.to_string())?;
        if bytes.len() < 8 || (bytes.len() - 8) % 8 != 0 {
            return Err(format!("{} bytes", bytes.len()));
        }
        return Ok(bytes[8..].to_vec());
    }
    let word = |bytes: &[u8], i: usize| -> Result<usize, String> {
        bytes
            .get(8 * i..8 * i + 8)
            .and_then(|b| b.try_into().ok())
            .map(|b| u64::from_le_bytes(b) as usize)
            .ok_or_else(|| "a truncated header".to_string())
    };
    // the header's own base64 run: first its block count, then all of it
    let first = STANDARD
        .decode(text.get(..12).ok_or("a truncated header")?)
        .map_err(|e| e.to_string())?;
    let blocks = word(&first, 0)?;
    let header_len = (8 * (3 + blocks)).div_ceil(3) * 4;
    let header = STANDARD
        .decode(text.get(..header_len).ok_or("a truncated header")?)
        .map_err(|e| e.to_string())?;
    let data = STANDARD
        .decode(&text[header_len..])
        .map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    let mut at = 0;
    for b in 0..blocks {
        let size = word(&header, 3 + b)?;
        let block = data.get(at..at + size).ok_or("a truncated block")?;
        let mut z = flate2::read::ZlibDecoder::new(block);
        std::io::Read::read_to_end(&mut z, &mut out).map_err(|e| e.to_string())?;
        at += size;
    }
    Ok(out)
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
                kind: ArrayKind::Float64,
            }],
            &[
                Field {
                    name: "stress",
                    components: 9,
                    values: &stress,
                    kind: ArrayKind::Float64,
                },
                Field {
                    name: "element id",
                    components: 1,
                    values: &id,
                    kind: ArrayKind::Float64,
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
            .flat_map(|e| e.kind.vtk_order().iter().map(|&a| e.nodes[a] as i64))
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

    /// The quadratic cells (and the wedge) with their VTK types and node
    /// order ([`ElementKind::vtk_order`]).
    #[test]
    fn quadratic_and_wedge_round_trips() {
        for kind in [
            ElementKind::Tet10,
            ElementKind::Hex20,
            ElementKind::Wedge6,
            ElementKind::Wedge15,
        ] {
            round_trip(kind);
        }
    }

    /// In a written Tet10, VTK's node 8 is the middle of the edge 1–3 and
    /// node 9 of 2–3 (vtkQuadraticTetra), in Gmsh's order the other way
    /// round.
    #[test]
    fn tet10_mid_side_nodes_where_vtk_expects_them() {
        let mesh = box_mesh(ElementKind::Tet10, [1, 1, 1], [1.0, 1.0, 1.0]);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("tet10.vtu");
        write_vtu(&path, &mesh, &[], &[]).unwrap();
        let (_, _, arrays) = read_vtu(&path);
        let connectivity = find(&arrays, "Cells", "connectivity").i64s();
        let x = |i: i64| mesh.nodes[i as usize];
        for cell in connectivity.chunks(10) {
            for (m, [a, b]) in [(8, [1, 3]), (9, [2, 3])] {
                let mid: [f64; 3] = std::array::from_fn(|d| 0.5 * (x(cell[a])[d] + x(cell[b])[d]));
                assert_eq!(x(cell[m]), mid);
            }
        }
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
                kind: ArrayKind::Float64,
            }],
            &[Field {
                name: "cauchy_stress",
                components: 9,
                values: &short,
                kind: ArrayKind::Float64,
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
                kind: ArrayKind::Float64,
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
                kind: ArrayKind::Float64,
            }],
            &[],
        )
        .unwrap_err();
        assert!(err.to_string().contains("'z'"), "{err}");
        let f = Field {
            name: "u",
            components: 3,
            values: &good,
            kind: ArrayKind::Float64,
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
                kind: ArrayKind::Float64,
            }],
            &[],
        )
        .unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains(r#"Name="a&lt;&quot;b&quot;&gt;&amp;c""#));
    }
}
