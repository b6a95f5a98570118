//! Turning the keywords' data into a [`Mesh`]: nodes and elements by their
//! ids, element and node sets by name, surfaces of element faces.

use super::super::boundary::boundary_faces;
use super::super::{Element, ElementKind, Facet, FacetKind, Mesh, NodeSet, Region, SurfaceSet};
use super::element_type::Shape;
use std::collections::HashMap;

/// What an element id stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Member {
    /// Index into the volume elements.
    Volume(usize),
    /// Index into the surface elements.
    Facet(usize),
    /// Index into the line elements.
    Line(usize),
}

/// Sets by name: the first spelling is kept, lookups ignore case (as
/// Abaqus does).
pub(super) struct Named<T> {
    items: Vec<(String, T)>,
    index: HashMap<String, usize>,
}

impl<T: Default> Named<T> {
    fn new() -> Self {
        Named {
            items: Vec::new(),
            index: HashMap::new(),
        }
    }
    pub(super) fn get(&self, name: &str) -> Option<&T> {
        let i = *self.index.get(&name.to_ascii_uppercase())?;
        Some(&self.items[i].1)
    }
    /// The spelling of the set called `name` (case ignored) as first
    /// defined.
    pub(super) fn canonical(&self, name: &str) -> Option<&str> {
        let i = *self.index.get(&name.to_ascii_uppercase())?;
        Some(&self.items[i].0)
    }
    /// The set called `name`, created empty if new.
    pub(super) fn entry(&mut self, name: &str) -> &mut T {
        let key = name.to_ascii_uppercase();
        let i = match self.index.get(&key) {
            Some(&i) => i,
            None => {
                self.items.push((name.to_string(), T::default()));
                self.index.insert(key, self.items.len() - 1);
                self.items.len() - 1
            }
        };
        &mut self.items[i].1
    }
}

/// Ids (of nodes, of elements) → what they stand for, added one at a time
/// as the deck defines them: a table indexed by the id while the ids stay
/// within twice the entries so far (plus [`IdIndex::SLACK`]), which is
/// every deck numbered `1…n` in any order, a hash map for the ids beyond
/// it. The small race's deck (6 121 nodes, 31 769 Tet4) was read in 30 ms
/// of CPU with two hash maps (SipHash hashing 11 % of it), in 22 ms with
/// the tables (medians of 8 runs each, 1-minute load 7.5).
struct IdIndex<T> {
    table: Vec<Option<T>>,
    others: HashMap<u64, T>,
    entries: usize,
}

impl<T: Copy> IdIndex<T> {
    /// Ids below this always go into the table.
    const SLACK: usize = 4096;

    fn new() -> Self {
        IdIndex {
            table: Vec::new(),
            others: HashMap::new(),
            entries: 0,
        }
    }

    fn get(&self, id: u64) -> Option<T> {
        match usize::try_from(id).ok().and_then(|i| self.table.get(i)) {
            Some(slot) => *slot,
            None => self.others.get(&id).copied(),
        }
    }

    /// Adds `id → value`; `false` (and nothing changed) if `id` is taken.
    fn insert(&mut self, id: u64, value: T) -> bool {
        if self.get(id).is_some() {
            return false;
        }
        let bound = 2 * self.entries + Self::SLACK;
        match usize::try_from(id).ok().filter(|&i| i < bound) {
            Some(i) => {
                if i >= self.table.len() {
                    // grown geometrically: amortised O(1) per id
                    let len = (i + 1).max(2 * self.table.len()).min(bound);
                    // ids moved into the table from the map keep their value
                    self.table.resize(len, None);
                    let moved: Vec<u64> = self
                        .others
                        .keys()
                        .copied()
                        .filter(|&k| usize::try_from(k).is_ok_and(|k| k < len))
                        .collect();
                    for k in moved {
                        if let Some(v) = self.others.remove(&k) {
                            self.table[k as usize] = Some(v);
                        }
                    }
                }
                self.table[i] = Some(value);
            }
            None => {
                self.others.insert(id, value);
            }
        }
        self.entries += 1;
        true
    }
}

/// The mesh being read.
pub(super) struct Builder {
    nodes: Vec<[f64; 3]>,
    node_ids: Vec<u64>,
    node_index: IdIndex<usize>,
    elements: Vec<Element>,
    facets: Vec<Facet>,
    lines: Vec<Vec<usize>>,
    element_index: IdIndex<Member>,
    pub(super) element_sets: Named<Vec<Member>>,
    pub(super) node_sets: Named<Vec<usize>>,
    pub(super) surfaces: Named<Vec<Facet>>,
    /// `(surface name, volume element)`: every free face of the element
    /// (a `*SURFACE` line without a face identifier).
    free_faces: Vec<(String, usize)>,
}

impl Builder {
    pub(super) fn new() -> Self {
        Builder {
            nodes: Vec::new(),
            node_ids: Vec::new(),
            node_index: IdIndex::new(),
            elements: Vec::new(),
            facets: Vec::new(),
            lines: Vec::new(),
            element_index: IdIndex::new(),
            element_sets: Named::new(),
            node_sets: Named::new(),
            surfaces: Named::new(),
            free_faces: Vec::new(),
        }
    }

    /// Adds node `id`; `Err` with the message if the id is taken.
    pub(super) fn add_node(&mut self, id: u64, x: [f64; 3]) -> Result<usize, String> {
        if !self.node_index.insert(id, self.nodes.len()) {
            return Err(format!("node {id} is defined twice"));
        }
        self.nodes.push(x);
        self.node_ids.push(id);
        Ok(self.nodes.len() - 1)
    }

    /// The index of node `id`.
    pub(super) fn node(&self, id: u64) -> Option<usize> {
        self.node_index.get(id)
    }

    /// The element with id `id`.
    pub(super) fn element(&self, id: u64) -> Option<Member> {
        self.element_index.get(id)
    }

    /// The volume element at `index`.
    pub(super) fn volume(&self, index: usize) -> &Element {
        &self.elements[index]
    }

    /// Adds element `id` of `shape` on the nodes with ids `node_ids`.
    pub(super) fn add_element(
        &mut self,
        id: u64,
        shape: Shape,
        node_ids: &[u64],
    ) -> Result<Member, String> {
        if self.element_index.get(id).is_some() {
            return Err(format!("element {id} is defined twice"));
        }
        let mut nodes = Vec::with_capacity(node_ids.len());
        for &n in node_ids {
            let index = self.node(n).ok_or_else(|| {
                format!("element {id} refers to node {n}, which no *NODE defines (before it)")
            })?;
            if nodes.contains(&index) {
                return Err(format!("element {id} has node {n} more than once"));
            }
            nodes.push(index);
        }
        let member = match shape {
            Shape::Volume(kind) => {
                let nodes = super::element_type::from_abaqus_order(kind, nodes);
                self.elements.push(Element { kind, nodes, id });
                Member::Volume(self.elements.len() - 1)
            }
            Shape::Facet(kind) => {
                self.facets.push(Facet { kind, nodes, id });
                Member::Facet(self.facets.len() - 1)
            }
            Shape::Line => {
                self.lines.push(nodes);
                Member::Line(self.lines.len() - 1)
            }
        };
        self.element_index.insert(id, member);
        Ok(member)
    }

    /// The numbers of nodes and of volume elements read so far.
    pub(super) fn counts(&self) -> (usize, usize) {
        (self.nodes.len(), self.elements.len())
    }

    /// The nodes of the elements of a set.
    pub(super) fn member_nodes(&self, members: &[Member]) -> Vec<usize> {
        members
            .iter()
            .flat_map(|m| match *m {
                Member::Volume(e) => self.elements[e].nodes.iter(),
                Member::Facet(f) => self.facets[f].nodes.iter(),
                Member::Line(l) => self.lines[l].iter(),
            })
            .copied()
            .collect()
    }

    /// Adds face `local` (outward local node indices) of volume element
    /// `element` to surface `name`.
    pub(super) fn add_face(&mut self, name: &str, element: usize, local: &[usize]) {
        let el = &self.elements[element];
        let facet = Facet {
            kind: FacetKind::of_node_count(local.len()).unwrap_or(FacetKind::Quad4),
            nodes: local.iter().map(|&a| el.nodes[a]).collect(),
            id: el.id,
        };
        self.surfaces.entry(name).push(facet);
    }

    /// Adds every free face of volume element `element` to surface `name`
    /// (found when the mesh is complete).
    pub(super) fn add_free_faces(&mut self, name: &str, element: usize) {
        self.surfaces.entry(name);
        self.free_faces.push((name.to_string(), element));
    }

    /// The mesh: regions from the element sets with volume elements (those
    /// in none in `"default"`), surface sets from the `*SURFACE`s and the
    /// element sets with surface elements, node sets from the `*NSET`s and
    /// the element sets with line elements. Sets keep the order of their
    /// first definition. Surfaces are oriented outward; a surface element
    /// on no volume element's face is returned as an error message.
    pub(super) fn finish(mut self) -> Result<Mesh, String> {
        if self.elements.is_empty() {
            return Err("the deck has no C3D4 or C3D8 volume elements".into());
        }
        let regions = self.regions_and_set_members();
        let mut mesh = Mesh {
            nodes: self.nodes,
            node_ids: self.node_ids,
            elements: self.elements,
            regions,
            surfaces: Vec::new(),
            node_sets: Vec::new(),
        };
        free_face_surfaces(&self.free_faces, &mut self.surfaces, &mesh);
        mesh.surfaces = self
            .surfaces
            .items
            .into_iter()
            .map(|(name, facets)| SurfaceSet { name, facets })
            .collect();
        mesh.node_sets = self
            .node_sets
            .items
            .into_iter()
            .map(|(name, mut nodes)| {
                nodes.sort_unstable();
                nodes.dedup();
                NodeSet { name, nodes }
            })
            .collect();
        let orphans = mesh.orient_surfaces();
        if let Some(first) = orphans.first() {
            return Err(format!(
                "surface element {} of element set '{}' is not a face of any volume element{}",
                first.facet_id,
                first.surface,
                match orphans.len() - 1 {
                    0 => String::new(),
                    n => format!(" ({n} more such elements)"),
                }
            ));
        }
        Ok(mesh)
    }

    /// The regions (the element sets with volume elements, and `default`
    /// for the elements in none), and the element sets' surface facets and
    /// line elements added to the surfaces and node sets of their names.
    fn regions_and_set_members(&mut self) -> Vec<Region> {
        let mut in_region = vec![false; self.elements.len()];
        let mut regions = Vec::new();
        let mut element_set_facets = Vec::new();
        let mut element_set_nodes = Vec::new();
        for (name, members) in &self.element_sets.items {
            let (mut volumes, mut facets, mut lines) = (Vec::new(), Vec::new(), Vec::new());
            for &m in members {
                match m {
                    Member::Volume(e) => volumes.push(e),
                    Member::Facet(f) => facets.push(self.facets[f].clone()),
                    Member::Line(_) => lines.push(m),
                }
            }
            volumes.sort_unstable();
            volumes.dedup();
            if !volumes.is_empty() {
                volumes.iter().for_each(|&e| in_region[e] = true);
                regions.push(Region {
                    name: name.clone(),
                    elements: volumes,
                });
            }
            if !facets.is_empty() {
                element_set_facets.push((name.clone(), facets));
            }
            if !lines.is_empty() {
                element_set_nodes.push((name.clone(), self.member_nodes(&lines)));
            }
        }
        let default: Vec<usize> = (0..self.elements.len())
            .filter(|&e| !in_region[e])
            .collect();
        if !default.is_empty() {
            regions.push(Region {
                name: "default".into(),
                elements: default,
            });
        }
        for (name, facets) in element_set_facets {
            self.surfaces.entry(&name).extend(facets);
        }
        for (name, nodes) in element_set_nodes {
            self.node_sets.entry(&name).extend(nodes);
        }
        regions
    }
}

/// The faces of `*SURFACE, TYPE=ELEMENT` lines without a face label
/// (`free_faces`, name and element): every boundary face of those
/// elements, in `surfaces`.
fn free_face_surfaces(
    free_faces: &[(String, usize)],
    surfaces: &mut Named<Vec<Facet>>,
    mesh: &Mesh,
) {
    if free_faces.is_empty() {
        return;
    }
    let mut by_element: HashMap<usize, Vec<&str>> = HashMap::new();
    for (name, e) in free_faces {
        by_element.entry(*e).or_default().push(name);
    }
    let mut faces: Vec<_> = boundary_faces(mesh)
        .into_values()
        .filter(|f| by_element.contains_key(&f.element))
        .collect();
    faces.sort_by(|a, b| (a.element, &a.nodes).cmp(&(b.element, &b.nodes)));
    for face in faces {
        for name in &by_element[&face.element] {
            let kind = FacetKind::of_node_count(face.nodes.len()).unwrap_or(FacetKind::Quad4);
            let id = mesh.elements[face.element].id;
            surfaces.entry(name).push(Facet {
                kind,
                nodes: face.nodes.clone(),
                id,
            });
        }
    }
}

/// The Abaqus name of a volume element kind.
pub(super) fn kind_name(kind: ElementKind) -> &'static str {
    match kind {
        ElementKind::Tet4 => "C3D4",
        ElementKind::Hex8 => "C3D8",
        ElementKind::Tet10 => "C3D10",
        ElementKind::Hex20 => "C3D20",
        ElementKind::Hex20R => "C3D20R",
        ElementKind::Wedge6 => "C3D6",
        ElementKind::Wedge15 => "C3D15",
    }
}

#[cfg(test)]
mod tests {
    use super::IdIndex;

    /// Ids in any order, small and huge (a table and the map), each found
    /// with its value; an id taken twice is refused and keeps its value;
    /// ids first beyond the table's bound move into it as it grows.
    #[test]
    fn ids_find_their_values() {
        let mut index = IdIndex::new();
        let huge = [u64::MAX, 1 << 40, 9_000_000, 21_000];
        for (k, &id) in huge.iter().enumerate() {
            assert!(index.insert(id, 1_000_000 + k));
        }
        // 20 000 ids from 1, reversed in blocks, then one beyond the gap
        let ids: Vec<u64> = (0..20_000u64)
            .map(|i| (i / 100) * 100 + 100 - i % 100)
            .collect();
        for (k, &id) in ids.iter().enumerate() {
            assert!(index.insert(id, k));
        }
        assert!(!index.insert(ids[7], 99));
        assert!(!index.insert(1 << 40, 99));
        for (k, &id) in ids.iter().enumerate() {
            assert_eq!(index.get(id), Some(k));
        }
        for (k, &id) in huge.iter().enumerate() {
            assert_eq!(index.get(id), Some(1_000_000 + k));
        }
        assert_eq!(index.get(0), None);
        assert_eq!(index.get(20_001), None);
        // 21 000 went to the map first, then into the grown table
        assert!(index.table.len() > 21_000 && !index.others.contains_key(&21_000));
    }
}
