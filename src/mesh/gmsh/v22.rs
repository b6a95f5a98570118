//! The MSH 2.2 sections `$Nodes` and `$Elements`: the counts are ASCII
//! lines, the records ASCII lines or binary values.

use super::builder::Builder;
use super::builder::ElementRead;
use super::cursor::Cursor;
use super::element_type::element_info;
use crate::Result;

/// `$Nodes`: the number of nodes (an ASCII line), then per node
/// `tag x y z` (binary: an int and three doubles).
pub(super) fn read_nodes(cur: &mut Cursor, b: &mut Builder) -> Result<()> {
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

/// `$Elements`: the number of elements (an ASCII line), then in ASCII
/// one `tag type numTags tags... nodeTags...` line per element, where the
/// first tag is the physical group (0: none) and the second the elementary
/// entity; in binary, blocks of `type numElements numTags` headers followed
/// by `tag tags... nodeTags...` ints per element.
pub(super) fn read_elements(cur: &mut Cursor, b: &mut Builder) -> Result<()> {
    let (count, _) = cur.ascii_int("the number of elements")?;
    let count = u64::try_from(count).unwrap_or(0);
    if cur.binary_file() {
        read_elements_binary(cur, b, count)?;
    } else {
        read_elements_ascii(cur, b, count)?;
    }
    cur.expect("$EndElements")
}

/// The ASCII `$Elements` (2.2) lines.
fn read_elements_ascii(cur: &mut Cursor, b: &mut Builder, count: u64) -> Result<()> {
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
        info.node_tags(cur, at, tag, element_type, nodes, &mut node_tags)?;
        let (physical, entity) = physical_and_entity(element_tags);
        let tag = u64::try_from(tag).unwrap_or(0);
        b.add_element(
            cur,
            at,
            ElementRead {
                tag,
                element_type,
                info,
                physicals: physical,
                entity,
                node_tags: &node_tags,
            },
        )?;
    }
    Ok(())
}

/// The binary `$Elements` (2.2) blocks.
fn read_elements_binary(cur: &mut Cursor, b: &mut Builder, count: u64) -> Result<()> {
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
            let (physical, entity) = physical_and_entity(&tags);
            let tag = u64::try_from(tag).unwrap_or(0);
            b.add_element(
                cur,
                at,
                ElementRead {
                    tag,
                    element_type,
                    info,
                    physicals: physical,
                    entity,
                    node_tags: &node_tags,
                },
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

/// The physical group (none for tag 0) and the elementary entity of an
/// element, from its first two tags.
fn physical_and_entity(tags: &[i64]) -> (&[i64], i64) {
    let physical: &[i64] = match tags.first() {
        Some(&p) if p != 0 => &tags[..1],
        _ => &[],
    };
    (physical, tags.get(1).copied().unwrap_or(0))
}
