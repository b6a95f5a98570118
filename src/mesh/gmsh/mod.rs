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
//! Volume elements Tet4 (type 4) and Hex8 (type 5) become [`Element`]s,
//! grouped into one [`Region`] per 3D physical group (elements in none go to
//! the region `"default"`). Triangles (2) and quadrangles (3) in a 2D physical
//! group become [`Facet`]s of the [`SurfaceSet`] of that group. Points and
//! lines are ignored. Other 3D element types are rejected, as are other 2D
//! types in a physical group. Regions and surface sets are ordered by physical
//! tag; groups with the same name are merged.
//!
//! MSH 2.2 writes an element once per physical group it belongs to (with a
//! new element tag each time); a volume element repeated with the same nodes
//! right after itself is therefore read as one element in several regions.
//! Every node of `$Nodes` is kept, in file order, referenced or not.

use super::{Element, ElementKind, Facet, FacetKind, Mesh, Region, SurfaceSet};
use crate::{Error, Result};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// Reads a Gmsh MSH file (4.1 or 2.2, ASCII or binary) into a [`Mesh`] with
/// outward-oriented surface sets.
pub fn read_msh(path: &Path) -> Result<Mesh> {
    let data = std::fs::read(path).map_err(|e| Error::io("read", path, e))?;
    parse_msh(&data, path)
}

/// Parses the contents of a MSH file; `path` is used only in error messages.
pub fn parse_msh(data: &[u8], path: &Path) -> Result<Mesh> {
    let mut cur = Cursor::new(data, path);
    let version = read_mesh_format(&mut cur)?;
    let mut b = Builder::default();
    let (mut have_nodes, mut have_elements) = (false, false);
    while let Some((name, offset)) = cur.section_header()? {
        match name {
            b"$PhysicalNames" => read_physical_names(&mut cur, &mut b)?,
            b"$Entities" if version == Version::V41 => read_entities_41(&mut cur, &mut b)?,
            b"$Nodes" | b"$Elements" | b"$MeshFormat" if seen(name, have_nodes, have_elements) => {
                return Err(cur.syntax(offset, format!("a second {} section", show(name))));
            }
            b"$Nodes" => {
                match version {
                    Version::V41 => read_nodes_41(&mut cur, &mut b)?,
                    Version::V22 => read_nodes_22(&mut cur, &mut b)?,
                }
                b.build_node_map(&cur)?;
                have_nodes = true;
            }
            b"$Elements" => {
                if !have_nodes {
                    return Err(cur.syntax(offset, "$Elements comes before $Nodes".into()));
                }
                match version {
                    Version::V41 => read_elements_41(&mut cur, &mut b)?,
                    Version::V22 => read_elements_22(&mut cur, &mut b)?,
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
    b.finish(&cur)
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

// ---------------------------------------------------------------------------
// Sections
// ---------------------------------------------------------------------------

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

/// `$Entities` (4.1): the counts of points, curves, surfaces and volumes,
/// then each entity with its bounding box (a point: its coordinates), its
/// physical tags and (not for points) its bounding entities.
fn read_entities_41(cur: &mut Cursor, b: &mut Builder) -> Result<()> {
    cur.begin_binary("$Entities")?;
    let mut counts = [0u64; 4];
    for (dim, count) in counts.iter_mut().enumerate() {
        *count = cur.size(&format!("the number of entities of dimension {dim}"))?;
    }
    for (dim, &count) in counts.iter().enumerate() {
        for _ in 0..count {
            let tag = cur.int("an entity tag")?;
            let coordinates = if dim == 0 { 3 } else { 6 };
            for _ in 0..coordinates {
                cur.float("an entity bounding-box coordinate")?;
            }
            let n_physical = cur.size("the number of physical tags of an entity")?;
            let mut physicals = Vec::new();
            for _ in 0..n_physical {
                physicals.push(cur.int("a physical tag")?);
            }
            if dim > 0 {
                let n_bounding = cur.size("the number of bounding entities")?;
                for _ in 0..n_bounding {
                    cur.int("a bounding entity tag")?;
                }
            }
            b.entities.insert((dim as i64, tag), physicals);
        }
    }
    cur.end_binary();
    cur.expect("$EndEntities")
}

/// `$Nodes` (4.1): `numEntityBlocks numNodes minNodeTag maxNodeTag`, then per
/// block `entityDim entityTag parametric numNodesInBlock`, the block's node
/// tags, then their coordinates `x y z` (followed by `entityDim` parametric
/// coordinates if `parametric` is 1).
fn read_nodes_41(cur: &mut Cursor, b: &mut Builder) -> Result<()> {
    cur.begin_binary("$Nodes")?;
    let blocks = cur.size("the number of node blocks")?;
    let total = cur.size("the number of nodes")?;
    cur.size("the smallest node tag")?;
    cur.size("the largest node tag")?;
    b.reserve_nodes(cur.capacity(total));
    for _ in 0..blocks {
        let at = cur.pos;
        let dim = cur.int("the entity dimension of a node block")?;
        cur.int("the entity tag of a node block")?;
        let parametric = cur.int("the parametric flag of a node block (0 or 1)")?;
        let n = cur.size("the number of nodes in a block")?;
        if !(0..=3).contains(&dim) || !(0..=1).contains(&parametric) {
            return Err(cur.syntax(
                at,
                format!(
                    "expected a node block header with entity dimension 0-3 and \
                     parametric flag 0 or 1, found dimension {dim} and flag {parametric}"
                ),
            ));
        }
        let first = b.node_ids.len();
        for _ in 0..n {
            let tag = cur.size("a node tag")?;
            b.node_ids.push(tag);
        }
        let extra = if parametric == 1 { dim } else { 0 };
        for i in first..b.node_ids.len() {
            let x = cur.coordinate("x", b.node_ids[i])?;
            let y = cur.coordinate("y", b.node_ids[i])?;
            let z = cur.coordinate("z", b.node_ids[i])?;
            for _ in 0..extra {
                cur.float("a parametric coordinate")?;
            }
            b.nodes.push([x, y, z]);
        }
    }
    if b.nodes.len() as u64 != total {
        return Err(cur.syntax(
            cur.pos,
            format!(
                "the $Nodes header announces {total} nodes but its blocks hold {}",
                b.nodes.len()
            ),
        ));
    }
    cur.end_binary();
    cur.expect("$EndNodes")
}

/// `$Nodes` (2.2): the number of nodes (an ASCII line), then per node
/// `tag x y z` (binary: an int and three doubles).
fn read_nodes_22(cur: &mut Cursor, b: &mut Builder) -> Result<()> {
    let (count, _) = cur.ascii_int("the number of nodes")?;
    let count = u64::try_from(count).unwrap_or(0);
    b.reserve_nodes(cur.capacity(count));
    cur.begin_binary("$Nodes")?;
    for _ in 0..count {
        let at = cur.pos;
        let tag = cur.int("a node tag")?;
        let tag = u64::try_from(tag)
            .map_err(|_| cur.syntax(at, format!("expected a positive node tag, found {tag}")))?;
        let x = cur.coordinate("x", tag)?;
        let y = cur.coordinate("y", tag)?;
        let z = cur.coordinate("z", tag)?;
        b.node_ids.push(tag);
        b.nodes.push([x, y, z]);
    }
    cur.end_binary();
    cur.expect("$EndNodes")
}

/// `$Elements` (4.1): `numEntityBlocks numElements minElementTag
/// maxElementTag`, then per block `entityDim entityTag elementType
/// numElementsInBlock` and one `elementTag nodeTag...` per element. The
/// physical groups of an element are those of its entity (`$Entities`).
fn read_elements_41(cur: &mut Cursor, b: &mut Builder) -> Result<()> {
    cur.begin_binary("$Elements")?;
    let blocks = cur.size("the number of element blocks")?;
    let total = cur.size("the number of elements")?;
    cur.size("the smallest element tag")?;
    cur.size("the largest element tag")?;
    let mut read = 0u64;
    let mut line = Vec::new();
    let mut node_tags = Vec::new();
    for _ in 0..blocks {
        let at = cur.pos;
        let entity_dim = cur.int("the entity dimension of an element block")?;
        let entity_tag = cur.int("the entity tag of an element block")?;
        let element_type = cur.int("the element type of an element block")?;
        let n = cur.size("the number of elements in a block")?;
        let info = element_info(element_type)
            .ok_or_else(|| cur.syntax(at, format!("unknown Gmsh element type {element_type}")))?;
        let physicals = b
            .entities
            .get(&(entity_dim, entity_tag))
            .cloned()
            .unwrap_or_default();
        if cur.binary && info.dim < 2 {
            // points and lines are ignored: skip the whole block at once
            let bytes = n
                .checked_mul(1 + info.nodes as u64)
                .and_then(|k| k.checked_mul(cur.size_t as u64))
                .and_then(|k| usize::try_from(k).ok())
                .unwrap_or(usize::MAX);
            cur.bytes(bytes, "the elements of a block of points or lines")?;
            read += n;
            continue;
        }
        for _ in 0..n {
            let (tag, at) = if cur.binary {
                let at = cur.pos;
                let tag = cur.size("an element tag")?;
                node_tags.clear();
                for _ in 0..info.nodes {
                    node_tags.push(cur.size("a node tag of an element")?);
                }
                (tag, at)
            } else {
                let at = cur.int_line(&mut line, "an element line (element tag, node tags)")?;
                let (&tag, nodes) = line.split_first().unwrap_or((&0, &[]));
                if nodes.len() != info.nodes {
                    return Err(cur.syntax(
                        at,
                        format!(
                            "expected {} node tags for element {tag} of type {element_type}, found {}",
                            info.nodes,
                            nodes.len()
                        ),
                    ));
                }
                node_tags.clear();
                node_tags.extend(nodes.iter().map(|&t| u64::try_from(t).unwrap_or(0)));
                (u64::try_from(tag).unwrap_or(0), at)
            };
            b.add_element(
                cur,
                at,
                tag,
                element_type,
                info,
                &physicals,
                entity_tag,
                &node_tags,
            )?;
            read += 1;
        }
    }
    if read != total {
        return Err(cur.syntax(
            cur.pos,
            format!("the $Elements header announces {total} elements but its blocks hold {read}"),
        ));
    }
    cur.end_binary();
    cur.expect("$EndElements")
}

/// `$Elements` (2.2): the number of elements (an ASCII line), then in ASCII
/// one `tag type numTags tags... nodeTags...` line per element, where the
/// first tag is the physical group (0: none) and the second the elementary
/// entity; in binary, blocks of `type numElements numTags` headers followed
/// by `tag tags... nodeTags...` ints per element.
fn read_elements_22(cur: &mut Cursor, b: &mut Builder) -> Result<()> {
    let (count, _) = cur.ascii_int("the number of elements")?;
    let count = u64::try_from(count).unwrap_or(0);
    if cur.binary_file() {
        read_elements_22_binary(cur, b, count)?;
    } else {
        read_elements_22_ascii(cur, b, count)?;
    }
    cur.expect("$EndElements")
}

/// The ASCII `$Elements` (2.2) lines.
fn read_elements_22_ascii(cur: &mut Cursor, b: &mut Builder, count: u64) -> Result<()> {
    let mut node_tags = Vec::new();
    let mut line = Vec::new();
    for _ in 0..count {
        let at = cur.int_line(
            &mut line,
            "an element line (tag type numTags tags... nodes...)",
        )?;
        let (tag, element_type, n_tags) = match line[..] {
            [tag, element_type, n_tags, ..] if n_tags >= 0 => (tag, element_type, n_tags as usize),
            _ => {
                return Err(cur.syntax(
                    at,
                    "expected an element line 'tag type numTags tags... nodeTags...'".into(),
                ))
            }
        };
        let info = element_info(element_type).ok_or_else(|| {
            cur.syntax(
                at,
                format!("unknown Gmsh element type {element_type} of element {tag}"),
            )
        })?;
        let rest = line.get(3..).unwrap_or(&[]);
        let (element_tags, nodes) = rest.split_at(n_tags.min(rest.len()));
        if element_tags.len() != n_tags {
            return Err(cur.syntax(
                at,
                format!(
                    "expected {n_tags} tags for element {tag}, found {}",
                    element_tags.len()
                ),
            ));
        }
        if nodes.len() != info.nodes {
            return Err(cur.syntax(
                at,
                format!(
                    "expected {} node tags for element {tag} of type {element_type}, found {}",
                    info.nodes,
                    nodes.len()
                ),
            ));
        }
        let physical: &[i64] = match element_tags.first() {
            Some(&p) if p != 0 => &element_tags[..1],
            _ => &[],
        };
        let entity = element_tags.get(1).copied().unwrap_or(0);
        node_tags.clear();
        node_tags.extend(nodes.iter().map(|&t| u64::try_from(t).unwrap_or(0)));
        let tag = u64::try_from(tag).unwrap_or(0);
        b.add_element(
            cur,
            at,
            tag,
            element_type,
            info,
            physical,
            entity,
            &node_tags,
        )?;
    }
    Ok(())
}

/// The binary `$Elements` (2.2) blocks.
fn read_elements_22_binary(cur: &mut Cursor, b: &mut Builder, count: u64) -> Result<()> {
    let mut read = 0u64;
    let mut node_tags = Vec::new();
    let mut tags = Vec::new();
    cur.begin_binary("$Elements")?;
    while read < count {
        let at = cur.pos;
        let element_type = cur.int("the element type of a block header")?;
        let n = cur.int("the number of elements of a block header")?;
        let n_tags = cur.int("the number of tags of a block header")?;
        let info = element_info(element_type)
            .ok_or_else(|| cur.syntax(at, format!("unknown Gmsh element type {element_type}")))?;
        if n < 0 || n_tags < 0 {
            return Err(cur.syntax(
                at,
                format!("expected non-negative counts in an element block header, found {n} elements with {n_tags} tags"),
            ));
        }
        for _ in 0..n {
            let at = cur.pos;
            let tag = cur.int("an element tag")?;
            tags.clear();
            for _ in 0..n_tags {
                tags.push(cur.int("an element's tag")?);
            }
            node_tags.clear();
            for _ in 0..info.nodes {
                node_tags.push(u64::try_from(cur.int("a node tag of an element")?).unwrap_or(0));
            }
            let physical: &[i64] = match tags.first() {
                Some(&p) if p != 0 => &tags[..1],
                _ => &[],
            };
            let tag = u64::try_from(tag).unwrap_or(0);
            let entity = tags.get(1).copied().unwrap_or(0);
            b.add_element(
                cur,
                at,
                tag,
                element_type,
                info,
                physical,
                entity,
                &node_tags,
            )?;
        }
        read += n as u64;
    }
    if read != count {
        return Err(cur.syntax(
            cur.pos,
            format!("the $Elements section announces {count} elements but its blocks hold {read}"),
        ));
    }
    cur.end_binary();
    Ok(())
}

// ---------------------------------------------------------------------------
// Element types
// ---------------------------------------------------------------------------

/// Dimension, node count and shape of a Gmsh element type.
#[derive(Clone, Copy, Debug)]
struct ElementInfo {
    dim: u8,
    nodes: usize,
    shape: &'static str,
}

/// The Gmsh element types with a fixed number of nodes (`GmshDefines.h`).
/// The reader must know the node count of every type it may have to skip.
fn element_info(element_type: i64) -> Option<ElementInfo> {
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

/// What a supported element becomes.
enum Target {
    Volume(ElementKind),
    Facet(FacetKind),
}

// ---------------------------------------------------------------------------
// Building the mesh
// ---------------------------------------------------------------------------

/// File node tag → index into [`Mesh::nodes`]: a table when the tags are
/// dense enough, a hash map when they are sparse.
#[derive(Default)]
enum NodeMap {
    #[default]
    Empty,
    Dense {
        min: u64,
        index: Vec<usize>,
    },
    Sparse(HashMap<u64, usize>),
}

impl NodeMap {
    fn get(&self, tag: u64) -> Option<usize> {
        match self {
            NodeMap::Empty => None,
            NodeMap::Dense { min, index } => {
                let slot = usize::try_from(tag.checked_sub(*min)?).ok()?;
                index.get(slot).copied().filter(|&i| i != usize::MAX)
            }
            NodeMap::Sparse(map) => map.get(&tag).copied(),
        }
    }
}

/// The mesh being read, plus what the sections before `$Elements` told.
#[derive(Default)]
struct Builder {
    /// `(dimension, physical tag)` → name, from `$PhysicalNames`.
    names: HashMap<(i64, i64), String>,
    /// `(dimension, entity tag)` → physical tags, from `$Entities` (4.1).
    entities: HashMap<(i64, i64), Vec<i64>>,
    nodes: Vec<[f64; 3]>,
    node_ids: Vec<u64>,
    node_map: NodeMap,
    elements: Vec<Element>,
    /// Entity of the last volume element, to merge MSH 2.2 repetitions.
    last_volume_entity: Option<i64>,
    /// 3D physical tag → element indices.
    regions: BTreeMap<i64, Vec<usize>>,
    default_region: Vec<usize>,
    /// 2D physical tag → facets.
    surfaces: BTreeMap<i64, Vec<Facet>>,
    scratch: Vec<usize>,
}

impl Builder {
    fn reserve_nodes(&mut self, n: usize) {
        self.nodes.reserve(n);
        self.node_ids.reserve(n);
    }

    /// Indexes the node tags read from `$Nodes`; a tag defined twice is an
    /// error.
    fn build_node_map(&mut self, cur: &Cursor) -> Result<()> {
        let (Some(&min), Some(&max)) = (self.node_ids.iter().min(), self.node_ids.iter().max())
        else {
            self.node_map = NodeMap::Empty;
            return Ok(());
        };
        let n = self.node_ids.len();
        let duplicate =
            |tag: u64| cur.invalid(format!("node tag {tag} is defined twice in $Nodes"));
        let span = usize::try_from(max - min)
            .ok()
            .filter(|&s| s <= 2 * n + 1024);
        self.node_map = match span {
            Some(span) => {
                let mut index = vec![usize::MAX; span + 1];
                for (i, &tag) in self.node_ids.iter().enumerate() {
                    let slot = &mut index[(tag - min) as usize];
                    if *slot != usize::MAX {
                        return Err(duplicate(tag));
                    }
                    *slot = i;
                }
                NodeMap::Dense { min, index }
            }
            None => {
                let mut map = HashMap::with_capacity(n);
                for (i, &tag) in self.node_ids.iter().enumerate() {
                    if map.insert(tag, i).is_some() {
                        return Err(duplicate(tag));
                    }
                }
                NodeMap::Sparse(map)
            }
        };
        Ok(())
    }

    /// Adds one element read at offset `at`: a volume element to
    /// [`Mesh::elements`] and its regions, a facet of a 2D physical group to
    /// its surface sets; points, lines and unassigned 2D elements are
    /// dropped.
    #[allow(clippy::too_many_arguments)]
    fn add_element(
        &mut self,
        cur: &Cursor,
        at: usize,
        tag: u64,
        element_type: i64,
        info: ElementInfo,
        physicals: &[i64],
        entity: i64,
        node_tags: &[u64],
    ) -> Result<()> {
        if info.dim < 2 || (info.dim == 2 && physicals.is_empty()) {
            return Ok(());
        }
        let target = match element_type {
            4 => Target::Volume(ElementKind::Tet4),
            5 => Target::Volume(ElementKind::Hex8),
            2 => Target::Facet(FacetKind::Tri3),
            3 => Target::Facet(FacetKind::Quad4),
            _ => {
                let supported = if info.dim == 3 {
                    "only Tet4 (type 4) and Hex8 (type 5) volume elements are supported now"
                } else {
                    "only Tri3 (type 2) and Quad4 (type 3) elements are supported now in surface groups"
                };
                return Err(cur.invalid(format!(
                    "{}: element {tag} is a {}-node {} (Gmsh element type {element_type}); {supported}",
                    cur.location(at),
                    info.nodes,
                    info.shape
                )));
            }
        };
        self.scratch.clear();
        for &node in node_tags {
            let index = self.node_map.get(node).ok_or_else(|| {
                cur.syntax(
                    at,
                    format!("element {tag} refers to node tag {node}, which is not in $Nodes"),
                )
            })?;
            if self.scratch.contains(&index) {
                return Err(cur.invalid(format!(
                    "{}: element {tag} has node {node} more than once",
                    cur.location(at)
                )));
            }
            self.scratch.push(index);
        }
        match target {
            Target::Volume(kind) => {
                let repeated = self.last_volume_entity == Some(entity)
                    && self
                        .elements
                        .last()
                        .is_some_and(|e| e.kind == kind && e.nodes == self.scratch);
                if !repeated {
                    self.elements.push(Element {
                        kind,
                        nodes: self.scratch.clone(),
                        id: tag,
                    });
                    self.last_volume_entity = Some(entity);
                    if physicals.is_empty() {
                        self.default_region.push(self.elements.len() - 1);
                    }
                }
                let index = self.elements.len() - 1;
                for &p in physicals {
                    let members = self.regions.entry(p).or_default();
                    if members.last() != Some(&index) {
                        members.push(index);
                    }
                }
            }
            Target::Facet(kind) => {
                for &p in physicals {
                    self.surfaces.entry(p).or_default().push(Facet {
                        kind,
                        nodes: self.scratch.clone(),
                        id: tag,
                    });
                }
            }
        }
        Ok(())
    }

    /// Names the regions and surface sets, orients the surfaces and checks
    /// that every facet lies on a volume element.
    fn finish(self, cur: &Cursor) -> Result<Mesh> {
        if self.elements.is_empty() {
            return Err(cur.invalid(
                "the file has no Tet4 or Hex8 volume elements; mesh the volume (gmsh -3) and, \
                 if the model has physical groups, put the volume in a Physical Volume \
                 (Gmsh then saves only elements of physical groups)"
                    .into(),
            ));
        }
        let names = &self.names;
        let name = |dim: i64, tag: i64| {
            names
                .get(&(dim, tag))
                .cloned()
                .unwrap_or_else(|| tag.to_string())
        };
        let mut regions: Vec<Region> = Vec::new();
        let groups = self.regions.into_iter().map(|(tag, e)| (name(3, tag), e));
        let default =
            (!self.default_region.is_empty()).then(|| ("default".to_string(), self.default_region));
        for (name, elements) in groups.chain(default) {
            match regions.iter_mut().find(|r| r.name == name) {
                Some(r) => r.elements.extend(elements),
                None => regions.push(Region { name, elements }),
            }
        }
        let mut surfaces: Vec<SurfaceSet> = Vec::new();
        for (tag, facets) in self.surfaces {
            let name = name(2, tag);
            match surfaces.iter_mut().find(|s| s.name == name) {
                Some(s) => s.facets.extend(facets),
                None => surfaces.push(SurfaceSet { name, facets }),
            }
        }
        let mut mesh = Mesh {
            nodes: self.nodes,
            node_ids: self.node_ids,
            elements: self.elements,
            regions,
            surfaces,
        };
        let orphans = mesh.orient_surfaces();
        if let Some(first) = orphans.first() {
            let more = match orphans.len() - 1 {
                0 => String::new(),
                n => format!(" ({n} more such facets)"),
            };
            return Err(cur.invalid(format!(
                "facet {} of surface '{}' is not a face of any volume element{more}",
                first.facet_id, first.surface
            )));
        }
        Ok(mesh)
    }
}

// ---------------------------------------------------------------------------
// The cursor: ASCII tokens with line numbers, binary values with offsets
// ---------------------------------------------------------------------------

/// A position in the file. ASCII is read as whitespace-separated tokens and
/// errors give the 1-based line (computed from the offset only when an error
/// is reported); binary payloads are read as fixed-size values and errors
/// give the byte offset.
struct Cursor<'a> {
    data: &'a [u8],
    pos: usize,
    path: &'a Path,
    /// The file is binary (`$MeshFormat` file type 1).
    binary_file: bool,
    /// The cursor is inside a binary payload.
    binary: bool,
    big_endian: bool,
    /// Bytes in a `size_t` (4.1 binary).
    size_t: usize,
    /// The section whose binary payload is being read, and where it starts.
    section: &'static str,
    section_start: usize,
}

impl<'a> Cursor<'a> {
    fn new(data: &'a [u8], path: &'a Path) -> Self {
        Cursor {
            data,
            pos: 0,
            path,
            binary_file: false,
            binary: false,
            big_endian: false,
            size_t: 8,
            section: "",
            section_start: 0,
        }
    }

    fn binary_file(&self) -> bool {
        self.binary_file
    }

    // -- errors -----------------------------------------------------------

    fn line_of(&self, at: usize) -> usize {
        let end = at.min(self.data.len());
        1 + self.data[..end].iter().filter(|&&c| c == b'\n').count()
    }

    /// Where offset `at` is, for messages.
    fn location(&self, at: usize) -> String {
        if self.binary {
            format!("byte offset {at} (binary {} data)", self.section)
        } else {
            format!("line {}", self.line_of(at))
        }
    }

    /// A syntax error at offset `at`: its line for ASCII, its byte offset
    /// (and the line of the section header) for binary data.
    fn syntax(&self, at: usize, message: String) -> Error {
        let (line, message) = if self.binary {
            (
                self.line_of(self.section_start),
                format!(
                    "in the binary {} data, at byte offset {at}: {message}",
                    self.section
                ),
            )
        } else if self.binary_file {
            (self.line_of(at), format!("{message} (byte offset {at})"))
        } else {
            (self.line_of(at), message)
        };
        Error::MeshSyntax {
            path: self.path.to_path_buf(),
            line,
            message,
        }
    }

    fn invalid(&self, message: String) -> Error {
        Error::Mesh {
            path: self.path.to_path_buf(),
            message,
        }
    }

    fn end_of_file(&self, what: &str) -> Error {
        self.syntax(
            self.data.len(),
            format!("unexpected end of file (truncated?): expected {what}"),
        )
    }

    // -- ASCII --------------------------------------------------------------

    fn skip_whitespace(&mut self) {
        while let Some(c) = self.data.get(self.pos) {
            if !c.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
    }

    /// The next whitespace-separated token and its offset.
    fn token(&mut self, what: &str) -> Result<(&'a [u8], usize)> {
        self.skip_whitespace();
        let start = self.pos;
        if start >= self.data.len() {
            return Err(self.end_of_file(what));
        }
        let len = self.data[start..]
            .iter()
            .position(|c| c.is_ascii_whitespace())
            .unwrap_or(self.data.len() - start);
        self.pos = start + len;
        Ok((&self.data[start..start + len], start))
    }

    /// An integer token.
    fn ascii_int(&mut self, what: &str) -> Result<(i64, usize)> {
        let (tok, at) = self.token(what)?;
        match parse_int(tok) {
            Some(v) => Ok((v, at)),
            None => Err(self.syntax(at, format!("expected {what}, found '{}'", show(tok)))),
        }
    }

    /// The keyword `keyword` as the next token.
    fn expect(&mut self, keyword: &str) -> Result<()> {
        let (tok, at) = self.token(keyword)?;
        if tok == keyword.as_bytes() {
            Ok(())
        } else {
            Err(self.syntax(at, format!("expected {keyword}, found '{}'", show(tok))))
        }
    }

    /// The integers of the next non-blank line into `out`; returns the
    /// line's offset.
    fn int_line(&mut self, out: &mut Vec<i64>, what: &str) -> Result<usize> {
        self.skip_whitespace();
        let start = self.pos;
        if start >= self.data.len() {
            return Err(self.end_of_file(what));
        }
        out.clear();
        loop {
            while matches!(self.data.get(self.pos), Some(b' ' | b'\t' | b'\r')) {
                self.pos += 1;
            }
            match self.data.get(self.pos) {
                None => break,
                Some(b'\n') => {
                    self.pos += 1;
                    break;
                }
                Some(_) => {}
            }
            let at = self.pos;
            let len = self.data[at..]
                .iter()
                .position(|c| c.is_ascii_whitespace())
                .unwrap_or(self.data.len() - at);
            let tok = &self.data[at..at + len];
            self.pos = at + len;
            match parse_int(tok) {
                Some(v) => out.push(v),
                None => {
                    return Err(self.syntax(at, format!("expected {what}, found '{}'", show(tok))))
                }
            }
        }
        Ok(start)
    }

    /// A physical group name: `"..."` (or a bare word) up to the end of the
    /// line.
    fn quoted_name(&mut self) -> Result<String> {
        while matches!(self.data.get(self.pos), Some(b' ' | b'\t')) {
            self.pos += 1;
        }
        if self.data.get(self.pos) != Some(&b'"') {
            let (tok, _) = self.token("a physical group name")?;
            return Ok(String::from_utf8_lossy(tok).into_owned());
        }
        let start = self.pos + 1;
        let rest = self.data.get(start..).unwrap_or(&[]);
        match rest.iter().position(|&c| c == b'"' || c == b'\n') {
            Some(len) if rest[len] == b'"' => {
                self.pos = start + len + 1;
                Ok(String::from_utf8_lossy(&rest[..len]).into_owned())
            }
            _ => Err(self.syntax(
                self.pos,
                "expected a physical group name in double quotes, found no closing quote on the line"
                    .into(),
            )),
        }
    }

    /// The next section header (`$Name`) and its offset, or `None` at the end
    /// of the file.
    fn section_header(&mut self) -> Result<Option<(&'a [u8], usize)>> {
        self.skip_whitespace();
        if self.pos >= self.data.len() {
            return Ok(None);
        }
        let (tok, at) = self.token("a section header")?;
        if tok.first() != Some(&b'$') {
            return Err(self.syntax(
                at,
                format!(
                    "expected a section header such as $Nodes or $Elements, found '{}'",
                    show(tok)
                ),
            ));
        }
        Ok(Some((tok, at)))
    }

    /// Skips an unknown section `name` (header at `at`) up to its `$End` line.
    fn skip_section(&mut self, name: &[u8], at: usize) -> Result<()> {
        let mut end = b"$End".to_vec();
        end.extend_from_slice(name.get(1..).unwrap_or(&[]));
        let rest = self.data.get(self.pos..).unwrap_or(&[]);
        match rest.windows(end.len()).position(|w| w == end.as_slice()) {
            Some(i) => {
                self.pos += i + end.len();
                Ok(())
            }
            None => Err(self.syntax(
                at,
                format!(
                    "section {} has no {} line (truncated file?)",
                    show(name),
                    show(&end)
                ),
            )),
        }
    }

    // -- binary ---------------------------------------------------------------

    /// In a binary file, consumes the end of the header line and switches to
    /// binary values for `section`; in an ASCII file does nothing.
    fn begin_binary(&mut self, section: &'static str) -> Result<()> {
        if !self.binary_file {
            return Ok(());
        }
        while matches!(self.data.get(self.pos), Some(b' ' | b'\t' | b'\r')) {
            self.pos += 1;
        }
        match self.data.get(self.pos) {
            Some(b'\n') => self.pos += 1,
            Some(_) => {
                return Err(self.syntax(
                    self.pos,
                    format!("expected the end of the line before the binary {section} data"),
                ))
            }
            None => return Err(self.end_of_file(&format!("the binary {section} data"))),
        }
        self.binary = true;
        self.section = section;
        self.section_start = self.pos;
        Ok(())
    }

    fn end_binary(&mut self) {
        self.binary = false;
    }

    /// The next `n` bytes of binary data.
    fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8]> {
        let at = self.pos;
        match at.checked_add(n).and_then(|end| self.data.get(at..end)) {
            Some(bytes) => {
                self.pos = at + n;
                Ok(bytes)
            }
            None => Err(self.syntax(
                at,
                format!(
                    "unexpected end of file (truncated?): expected {what} ({n} bytes), {} bytes left",
                    self.data.len().saturating_sub(at)
                ),
            )),
        }
    }

    fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        let b = self.bytes(N, what)?;
        let mut a = [0u8; N];
        a.copy_from_slice(b);
        if self.big_endian {
            a.reverse();
        }
        Ok(a) // little-endian from here on
    }

    // -- values: binary or ASCII -----------------------------------------------

    /// An `int` (binary: 4 bytes).
    fn int(&mut self, what: &str) -> Result<i64> {
        if self.binary {
            Ok(i32::from_le_bytes(self.array(what)?) as i64)
        } else {
            Ok(self.ascii_int(what)?.0)
        }
    }

    /// A `size_t` (binary: the `$MeshFormat` data size) or a non-negative
    /// integer.
    fn size(&mut self, what: &str) -> Result<u64> {
        if self.binary {
            if self.size_t == 4 {
                Ok(u32::from_le_bytes(self.array(what)?) as u64)
            } else {
                Ok(u64::from_le_bytes(self.array(what)?))
            }
        } else {
            let (v, at) = self.ascii_int(what)?;
            u64::try_from(v).map_err(|_| {
                self.syntax(
                    at,
                    format!("expected {what} (a non-negative integer), found {v}"),
                )
            })
        }
    }

    /// A `double`.
    fn float(&mut self, what: &str) -> Result<f64> {
        if self.binary {
            Ok(f64::from_le_bytes(self.array(what)?))
        } else {
            let (tok, at) = self.token(what)?;
            parse_float(tok)
                .ok_or_else(|| self.syntax(at, format!("expected {what}, found '{}'", show(tok))))
        }
    }

    /// A finite coordinate of node `tag` (the message is built only on error).
    fn coordinate(&mut self, axis: &str, tag: u64) -> Result<f64> {
        let at = self.pos;
        let what = "a node coordinate";
        let value = if self.binary {
            f64::from_le_bytes(self.array(what)?)
        } else {
            let (tok, at) = self.token(what)?;
            match parse_float(tok) {
                Some(v) => v,
                None => {
                    return Err(self.syntax(
                        at,
                        format!(
                            "expected the {axis} coordinate of node {tag}, found '{}'",
                            show(tok)
                        ),
                    ))
                }
            }
        };
        if value.is_finite() {
            Ok(value)
        } else {
            Err(self.syntax(
                at,
                format!("the {axis} coordinate of node {tag} is {value}"),
            ))
        }
    }

    /// A capacity to reserve for `count` items announced by the file, bounded
    /// by the file size so that a corrupt count cannot exhaust memory.
    fn capacity(&self, count: u64) -> usize {
        usize::try_from(count)
            .unwrap_or(usize::MAX)
            .min(self.data.len() / 8)
    }
}

fn parse_int(tok: &[u8]) -> Option<i64> {
    let (negative, digits) = match tok.split_first()? {
        (b'-', rest) => (true, rest),
        (b'+', rest) => (false, rest),
        _ => (false, tok),
    };
    if digits.is_empty() {
        return None;
    }
    let mut v: i64 = 0;
    for &c in digits {
        if !c.is_ascii_digit() {
            return None;
        }
        v = v.checked_mul(10)?.checked_add((c - b'0') as i64)?;
    }
    Some(if negative { -v } else { v })
}

fn parse_float(tok: &[u8]) -> Option<f64> {
    std::str::from_utf8(tok).ok()?.parse().ok()
}

/// A token for an error message: lossy UTF-8, at most 40 characters.
fn show(tok: &[u8]) -> String {
    let s = String::from_utf8_lossy(tok);
    match s.char_indices().nth(40) {
        Some((i, _)) => format!("{}...", &s[..i]),
        None => s.into_owned(),
    }
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

    #[test]
    fn integers() {
        assert_eq!(parse_int(b"-12"), Some(-12));
        assert_eq!(parse_int(b"+7"), Some(7));
        for bad in [&b""[..], b"-", b"1.0", b"1e3", b"99999999999999999999"] {
            assert_eq!(parse_int(bad), None);
        }
    }

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
