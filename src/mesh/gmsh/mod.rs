//! Reader for Gmsh MSH files: format versions 4.1 and 2.2, ASCII and binary.
//!
//! ## Why hand-written
//! The `mshio` crate (0.4.2, its latest release, from 2020) reads only MSH
//! 4.1 (ASCII and binary), not 2.2, which many users' meshes and older tools
//! still produce. It also parses only `$Entities`, `$Nodes` and `$Elements`
//! (no `$PhysicalNames`, so no group names), and its parser errors are a
//! backtrace of nom error kinds with slices of the input (printed as hex
//! dumps), not line numbers. A mesh file is user input, so this reader says
//! where a file is wrong: the 1-based line for ASCII data, the byte offset
//! for binary data.
//!
//! ## What it reads
//! - `$MeshFormat` (required, first): version 4.1 or 2.2, file type 0
//!   (ASCII) or 1 (binary, little- or big-endian, detected from the integer
//!   `1` that follows the header line).
//! - `$PhysicalNames`: names of physical groups. A group without a name is
//!   named by its number (`"7"`).
//! - `$Entities` (4.1): the physical groups of every geometric entity; an
//!   entity may be in several groups.
//! - `$Nodes`, `$Elements` (required). Node tags may be sparse.
//! - Any other section (`$PartitionedEntities`, `$Periodic`, `$NodeData`,
//!   `$Comments`, ...) is skipped up to its `$End...` line.
//!
//! Volume elements Tet4 (type 4), Hex8 (5), Wedge6 (6), and the
//! second-order (`-order 2`) Tet10 (11), Hex20 (17) and Wedge15 (18) become
//! [`Element`](super::Element)s, grouped into one [`Region`](super::Region)
//! per 3D physical group (elements in none go to the region `"default"`).
//! Triangles (2, 9) and quadrangles (3, 16) in a 2D physical group become
//! [`Facet`](super::Facet)s of the [`SurfaceSet`](super::SurfaceSet) of that
//! group. The nodes of points and lines (any order) in a 0D or 1D physical
//! group become the [`NodeSet`](super::NodeSet) of that group; points and
//! lines in none are ignored. Other 3D element types are rejected,
//! as are other 2D types in a physical group. Regions and surface sets are
//! ordered by physical tag (node sets by dimension, then tag); groups with
//! the same name are merged.
//!
//! MSH 2.2 writes an element once per physical group it belongs to (with a
//! new element tag each time); a volume element repeated with the same nodes
//! right after itself is therefore read as one element in several regions.
//! Every node of `$Nodes` is kept, in file order, referenced or not.
//!
//! ## Layout
//! - `cursor`: ASCII tokens with line numbers, binary values with byte
//!   offsets, and the located errors.
//! - `v41`, `v22`: the sections that differ between the two versions.
//! - `element_type`: the table of Gmsh element types.
//! - `builder`: the [`Mesh`] assembled from what the sections tell.
//! - here: the entry points, `$MeshFormat`, `$PhysicalNames` and the order
//!   of the sections.

mod builder;
mod cursor;
mod element_type;
mod v22;
mod v41;

use super::Mesh;
use crate::Result;
use builder::Builder;
use cursor::{show, Cursor};
use std::path::Path;

/// Reads a Gmsh MSH file (4.1 or 2.2, ASCII or binary) into a [`Mesh`] with
/// outward-oriented surface sets.
pub fn read_msh(path: &Path) -> Result<Mesh> {
    let data = crate::input::read_bounded(path, "read", crate::input::MAX_MESH_FILE)?;
    parse_msh(&data, path)
}

/// Reads a Gmsh MSH file that may hold surfaces only (a rigid obstacle):
/// no volume elements are required, and facets keep the orientation the
/// file gives them (right-hand normals must point toward the body).
pub fn read_surface_msh(path: &Path) -> Result<Mesh> {
    let data = crate::input::read_bounded(path, "read", crate::input::MAX_MESH_FILE)?;
    parse(&data, path, true)
}

/// Parses the contents of a MSH file; `path` is used only in error messages.
pub fn parse_msh(data: &[u8], path: &Path) -> Result<Mesh> {
    parse(data, path, false)
}

fn parse(data: &[u8], path: &Path, surface_only: bool) -> Result<Mesh> {
    let mut cur = Cursor::new(data, path);
    let version = read_mesh_format(&mut cur)?;
    let mut b = Builder::default();
    let (mut have_nodes, mut have_elements) = (false, false);
    while let Some((name, offset)) = cur.section_header()? {
        match name {
            b"$PhysicalNames" => read_physical_names(&mut cur, &mut b)?,
            b"$Entities" if version == Version::V41 => v41::read_entities(&mut cur, &mut b)?,
            b"$Nodes" | b"$Elements" | b"$MeshFormat" if seen(name, have_nodes, have_elements) => {
                return Err(cur.syntax(offset, format!("a second {} section", show(name))));
            }
            b"$Nodes" => {
                match version {
                    Version::V41 => v41::read_nodes(&mut cur, &mut b)?,
                    Version::V22 => v22::read_nodes(&mut cur, &mut b)?,
                }
                b.build_node_map(&cur)?;
                have_nodes = true;
            }
            b"$Elements" => {
                if !have_nodes {
                    return Err(cur.syntax(offset, "$Elements comes before $Nodes".into()));
                }
                match version {
                    Version::V41 => v41::read_elements(&mut cur, &mut b)?,
                    Version::V22 => v22::read_elements(&mut cur, &mut b)?,
                }
                have_elements = true;
            }
            _ => cur.skip_section(name, offset)?,
        }
    }
    for (have, section) in [(have_nodes, "$Nodes"), (have_elements, "$Elements")] {
        if !have {
            return Err(cur.invalid(format!("the file has no {section} section")));
        }
    }
    b.finish(&cur, surface_only)
}

/// Whether a `$Nodes`/`$Elements`/`$MeshFormat` header repeats one already read.
fn seen(name: &[u8], have_nodes: bool, have_elements: bool) -> bool {
    match name {
        b"$Nodes" => have_nodes,
        b"$Elements" => have_elements,
        _ => true, // $MeshFormat was read first
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Version {
    V22,
    V41,
}

/// `$MeshFormat`: `version file-type data-size`, for binary files followed by
/// the integer 1 that tells the byte order.
fn read_mesh_format(cur: &mut Cursor) -> Result<Version> {
    let (first, offset) = cur.token("the $MeshFormat header")?;
    if first != b"$MeshFormat" {
        return Err(cur.syntax(
            offset,
            format!(
                "expected $MeshFormat at the start of a Gmsh MSH file, found '{}'",
                show(first)
            ),
        ));
    }
    let (tok, offset) = cur.token("the MSH version number")?;
    let version = match tok {
        b"4.1" => Version::V41,
        b"2.2" => Version::V22,
        _ => {
            return Err(cur.syntax(
                offset,
                format!(
                    "MSH format version {} is not supported; supported versions are 4.1 and 2.2 \
                     (in Gmsh: File > Export, or `gmsh -format msh41` / `-format msh22`)",
                    show(tok)
                ),
            ))
        }
    };
    let (file_type, offset) = cur.ascii_int("the file type (0 for ASCII, 1 for binary)")?;
    let (data_size, ds_offset) = cur.ascii_int("the data size")?;
    match file_type {
        0 => {}
        1 => {
            if version == Version::V41 && data_size != 4 && data_size != 8 {
                return Err(cur.syntax(
                    ds_offset,
                    format!("expected data size 4 or 8 (bytes in a size_t), found {data_size}"),
                ));
            }
            if version == Version::V41 {
                cur.size_t = data_size as usize;
            }
            cur.binary_file = true;
            cur.begin_binary("$MeshFormat")?;
            let at = cur.pos;
            let one = cur.bytes(4, "the endianness check integer 1")?;
            let one: [u8; 4] = [one[0], one[1], one[2], one[3]];
            if i32::from_le_bytes(one) == 1 {
                cur.big_endian = false;
            } else if i32::from_be_bytes(one) == 1 {
                cur.big_endian = true;
            } else {
                return Err(cur.syntax(
                    at,
                    format!("expected the integer 1 (endianness check), found bytes {one:02x?}"),
                ));
            }
            cur.end_binary();
        }
        _ => {
            return Err(cur.syntax(
                offset,
                format!("expected file type 0 (ASCII) or 1 (binary), found {file_type}"),
            ))
        }
    }
    cur.expect("$EndMeshFormat")?;
    Ok(version)
}

/// `$PhysicalNames` (ASCII in every file type): `count`, then per group
/// `dimension tag "name"`.
fn read_physical_names(cur: &mut Cursor, b: &mut Builder) -> Result<()> {
    let (count, _) = cur.ascii_int("the number of physical names")?;
    for _ in 0..count {
        let (dim, _) = cur.ascii_int("the dimension of a physical group")?;
        let (tag, _) = cur.ascii_int("the tag of a physical group")?;
        let name = cur.quoted_name()?;
        b.names.insert((dim, tag), name);
    }
    cur.expect("$EndPhysicalNames")
}
#[cfg(test)]
mod tests {
    use super::*;

    /// Writes binary values in the chosen byte order and `size_t` width.
    struct Writer {
        out: Vec<u8>,
        big_endian: bool,
        size_t: usize,
    }

    impl Writer {
        fn text(&mut self, s: &str) -> &mut Self {
            self.out.extend_from_slice(s.as_bytes());
            self
        }
        fn int(&mut self, v: i32) -> &mut Self {
            let b = if self.big_endian {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            };
            self.out.extend_from_slice(&b);
            self
        }
        fn size(&mut self, v: u64) -> &mut Self {
            let b = if self.big_endian {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            };
            if self.size_t == 4 {
                let skip = if self.big_endian { 4 } else { 0 };
                self.out.extend_from_slice(&b[skip..skip + 4]);
            } else {
                self.out.extend_from_slice(&b);
            }
            self
        }
        fn float(&mut self, v: f64) -> &mut Self {
            let b = if self.big_endian {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            };
            self.out.extend_from_slice(&b);
            self
        }
    }

    const TET: [[f64; 3]; 4] = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];

    /// One tet (nodes 11..14, element 5) in physical volume 1, MSH 4.1 binary.
    fn tet_41_binary(big_endian: bool, size_t: usize) -> Vec<u8> {
        let mut w = Writer {
            out: Vec::new(),
            big_endian,
            size_t,
        };
        w.text(&format!("$MeshFormat\n4.1 1 {size_t}\n")).int(1);
        w.text("\n$EndMeshFormat\n$Entities\n");
        w.size(0).size(0).size(0).size(1).int(1);
        for c in [0., 0., 0., 1., 1., 1.] {
            w.float(c);
        }
        w.size(1).int(1).size(0).text("\n$EndEntities\n$Nodes\n");
        w.size(1)
            .size(4)
            .size(11)
            .size(14)
            .int(3)
            .int(1)
            .int(0)
            .size(4);
        for tag in 11..=14 {
            w.size(tag);
        }
        for x in TET.iter().flatten() {
            w.float(*x);
        }
        w.text("\n$EndNodes\n$Elements\n");
        w.size(1)
            .size(1)
            .size(5)
            .size(5)
            .int(3)
            .int(1)
            .int(4)
            .size(1)
            .size(5);
        for tag in 11..=14 {
            w.size(tag);
        }
        w.text("\n$EndElements\n");
        w.out
    }

    /// The same tet in MSH 2.2 binary.
    fn tet_22_binary(big_endian: bool) -> Vec<u8> {
        let mut w = Writer {
            out: Vec::new(),
            big_endian,
            size_t: 8,
        };
        w.text("$MeshFormat\n2.2 1 8\n").int(1);
        w.text("\n$EndMeshFormat\n$Nodes\n4\n");
        for (tag, x) in (11..).zip(TET) {
            w.int(tag).float(x[0]).float(x[1]).float(x[2]);
        }
        w.text("\n$EndNodes\n$Elements\n1\n");
        w.int(4).int(1).int(2).int(5).int(1).int(1);
        for tag in 11..=14 {
            w.int(tag);
        }
        w.text("\n$EndElements\n");
        w.out
    }

    fn check_tet(mesh: &Mesh) {
        assert_eq!(mesh.node_ids, [11, 12, 13, 14]);
        assert_eq!(mesh.nodes, TET);
        assert_eq!(mesh.elements.len(), 1);
        assert_eq!(mesh.elements[0].id, 5);
        assert_eq!(mesh.elements[0].nodes, [0, 1, 2, 3]);
        assert_eq!(mesh.region_names(), ["1"]);
    }

    #[test]
    fn binary_byte_orders_and_size_t_widths() {
        let path = Path::new("tet.msh");
        for big_endian in [false, true] {
            for size_t in [4, 8] {
                let mesh = parse_msh(&tet_41_binary(big_endian, size_t), path);
                check_tet(&mesh.unwrap_or_else(|e| panic!("{big_endian} {size_t}: {e}")));
            }
            check_tet(&parse_msh(&tet_22_binary(big_endian), path).unwrap());
        }
    }

    #[test]
    fn binary_missing_node_gives_byte_offset() {
        let mut bytes = tet_41_binary(false, 8);
        let n = bytes.len();
        // the last node tag of the element, just before "\n$EndElements\n"
        let at = n - 14 - 8;
        bytes[at..at + 8].copy_from_slice(&99u64.to_le_bytes());
        let e = parse_msh(&bytes, Path::new("tet.msh"))
            .unwrap_err()
            .to_string();
        let element_at = at - 4 * 8;
        assert!(e.contains(&format!("byte offset {element_at}")), "{e}");
        assert!(e.contains("element 5 refers to node tag 99"), "{e}");
    }
}
