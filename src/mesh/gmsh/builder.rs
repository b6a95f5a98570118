//! Turning what the sections tell into a [`Mesh`]: the node-tag index, the
//! volume elements and their regions, the facets of the surface sets.

use super::super::{Element, ElementKind, Facet, FacetKind, Mesh, NodeSet, Region, SurfaceSet};
use super::cursor::Cursor;
use super::element_type::ElementInfo;
use crate::Result;
use std::collections::{BTreeMap, HashMap};

/// What a supported element becomes.
enum Target {
    Volume(ElementKind),
    Facet(FacetKind),
}

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
pub(super) struct Builder {
    /// `(dimension, physical tag)` → name, from `$PhysicalNames`.
    pub(super) names: HashMap<(i64, i64), String>,
    /// `(dimension, entity tag)` → physical tags, from `$Entities` (4.1).
    pub(super) entities: HashMap<(i64, i64), Vec<i64>>,
    pub(super) nodes: Vec<[f64; 3]>,
    pub(super) node_ids: Vec<u64>,
    node_map: NodeMap,
    elements: Vec<Element>,
    /// Entity of the last volume element, to merge MSH 2.2 repetitions.
    last_volume_entity: Option<i64>,
    /// 3D physical tag → element indices.
    regions: BTreeMap<i64, Vec<usize>>,
    default_region: Vec<usize>,
    /// 2D physical tag → facets.
    surfaces: BTreeMap<i64, Vec<Facet>>,
    /// `(dimension 0 or 1, physical tag)` → nodes of its points and lines.
    node_groups: BTreeMap<(i64, i64), Vec<usize>>,
    scratch: Vec<usize>,
}

impl Builder {
    pub(super) fn reserve_nodes(&mut self, n: usize) {
        self.nodes.reserve(n);
        self.node_ids.reserve(n);
    }

    /// Indexes the node tags read from `$Nodes`; a tag defined twice is an
    /// error.
    pub(super) fn build_node_map(&mut self, cur: &Cursor) -> Result<()> {
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

    /// The index of node tag `node`, which element `tag` at offset `at`
    /// refers to.
    fn node_index(&self, cur: &Cursor, at: usize, tag: u64, node: u64) -> Result<usize> {
        self.node_map.get(node).ok_or_else(|| {
            cur.syntax(
                at,
                format!("element {tag} refers to node tag {node}, which is not in $Nodes"),
            )
        })
    }

    /// Adds one element (read at offset `at`): a volume element to
    /// [`Mesh::elements`] and its regions, a facet of a 2D physical group to
    /// its surface sets, the nodes of a point or line of a 0D or 1D physical
    /// group to its node sets; other points, lines and 2D elements are
    /// dropped.
    pub(super) fn add_element(
        &mut self,
        cur: &Cursor,
        at: usize,
        element: ElementRead,
    ) -> Result<()> {
        let ElementRead {
            tag,
            element_type,
            info,
            physicals,
            entity,
            node_tags,
        } = element;
        if info.dim < 3 && physicals.is_empty() {
            return Ok(());
        }
        if info.dim < 2 {
            for &node in node_tags {
                let index = self.node_index(cur, at, tag, node)?;
                for &p in physicals {
                    let group = self.node_groups.entry((info.dim as i64, p)).or_default();
                    group.push(index);
                }
            }
            return Ok(());
        }
        let facet = [
            FacetKind::Tri3,
            FacetKind::Quad4,
            FacetKind::Tri6,
            FacetKind::Quad8,
        ]
        .into_iter()
        .find(|k| i64::from(k.gmsh_type()) == element_type);
        let target = match (ElementKind::from_gmsh_type(element_type), facet) {
            (Some(kind), _) => Target::Volume(kind),
            (None, Some(kind)) => Target::Facet(kind),
            (None, None) => {
                let supported = if info.dim == 3 {
                    "the volume elements supported are Tet4 (type 4), Tet10 (11), Hex8 (5), Hex20 \
                     (17), Wedge6 (6) and Wedge15 (18); mesh with -order 1 or -order 2, and \
                     without the complete (Lagrange) variants (Mesh.SecondOrderIncomplete = 1)"
                } else {
                    "the surface elements supported in surface groups are Tri3 (type 2), Quad4 \
                     (3), Tri6 (9) and Quad8 (16)"
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
            let index = self.node_index(cur, at, tag, node)?;
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
    /// that every facet lies on a volume element (unless `surface_only`: a
    /// mesh of surfaces, kept as written).
    pub(super) fn finish(self, cur: &Cursor, surface_only: bool) -> Result<Mesh> {
        if self.elements.is_empty() && !surface_only {
            return Err(cur.invalid(
                "the file has no volume elements (Tet4, Tet10, Hex8, Hex20, Wedge6, Wedge15); mesh the volume (gmsh -3) and, \
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
        let mut node_sets: Vec<NodeSet> = Vec::new();
        for ((dim, tag), nodes) in self.node_groups {
            let name = name(dim, tag);
            match node_sets.iter_mut().find(|s| s.name == name) {
                Some(s) => s.nodes.extend(nodes),
                None => node_sets.push(NodeSet { name, nodes }),
            }
        }
        for set in &mut node_sets {
            set.nodes.sort_unstable();
            set.nodes.dedup();
        }
        let mut mesh = Mesh {
            nodes: self.nodes,
            node_ids: self.node_ids,
            elements: self.elements,
            regions,
            surfaces,
            node_sets,
        };
        let orphans = if surface_only {
            Vec::new()
        } else {
            mesh.orient_surfaces()
        };
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

/// One element as a Gmsh file lists it.
pub(super) struct ElementRead<'a> {
    /// The element's tag.
    pub tag: u64,
    /// Its Gmsh element type and what that type is.
    pub element_type: i64,
    pub info: ElementInfo,
    /// The physical groups of its entity (2.2: its physical tag).
    pub physicals: &'a [i64],
    /// Its elementary entity.
    pub entity: i64,
    /// The tags of its nodes.
    pub node_tags: &'a [u64],
}
