//! The MSH 4.1 sections: `$Entities`, and `$Nodes` and `$Elements` in
//! entity blocks. Every value is ASCII or binary as the file type says.

use super::builder::Builder;
use super::builder::ElementRead;
use super::cursor::Cursor;
use super::element_type::{element_info, ElementInfo};
use crate::Result;

/// `$Entities`: the counts of points, curves, surfaces and volumes,
/// then each entity with its bounding box (a point: its coordinates), its
/// physical tags and (not for points) its bounding entities.
pub(super) fn read_entities(cur: &mut Cursor, b: &mut Builder) -> Result<()> {
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

/// `$Nodes`: `numEntityBlocks numNodes minNodeTag maxNodeTag`, then per
/// block `entityDim entityTag parametric numNodesInBlock`, the block's node
/// tags, then their coordinates `x y z` (followed by `entityDim` parametric
/// coordinates if `parametric` is 1).
pub(super) fn read_nodes(cur: &mut Cursor, b: &mut Builder) -> Result<()> {
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

/// `$Elements`: `numEntityBlocks numElements minElementTag
/// maxElementTag`, then per block `entityDim entityTag elementType
/// numElementsInBlock` and one `elementTag nodeTag...` per element. The
/// physical groups of an element are those of its entity (`$Entities`).
pub(super) fn read_elements(cur: &mut Cursor, b: &mut Builder) -> Result<()> {
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
            skip_binary_block(cur, info, n)?;
            read += n;
            continue;
        }
        for _ in 0..n {
            let (tag, at) = read_element(cur, element_type, info, &mut line, &mut node_tags)?;
            b.add_element(
                cur,
                at,
                ElementRead {
                    tag,
                    element_type,
                    info,
                    physicals: &physicals,
                    entity: entity_tag,
                    node_tags: &node_tags,
                },
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

/// Skips a binary block of `n` points or lines (which the mesh ignores)
/// at once.
fn skip_binary_block(cur: &mut Cursor, info: ElementInfo, n: u64) -> Result<()> {
    let bytes = n
        .checked_mul(1 + info.nodes as u64)
        .and_then(|k| k.checked_mul(cur.size_t as u64))
        .and_then(|k| usize::try_from(k).ok())
        .unwrap_or(usize::MAX);
    cur.bytes(bytes, "the elements of a block of points or lines")?;
    Ok(())
}

/// One element of a block, `elementTag nodeTag...`, into `node_tags`
/// (ASCII: through the scratch `line`); returns its tag and offset.
fn read_element(
    cur: &mut Cursor,
    element_type: i64,
    info: ElementInfo,
    line: &mut Vec<i64>,
    node_tags: &mut Vec<u64>,
) -> Result<(u64, usize)> {
    if cur.binary {
        let at = cur.pos;
        let tag = cur.size("an element tag")?;
        node_tags.clear();
        for _ in 0..info.nodes {
            node_tags.push(cur.size("a node tag of an element")?);
        }
        Ok((tag, at))
    } else {
        let at = cur.int_line(line, "an element line (element tag, node tags)")?;
        let (&tag, nodes) = line.split_first().unwrap_or((&0, &[]));
        info.node_tags(cur, at, tag, element_type, nodes, node_tags)?;
        Ok((u64::try_from(tag).unwrap_or(0), at))
    }
}
