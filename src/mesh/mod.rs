//! The mesh: reference node coordinates, volume elements grouped into named
//! regions, named boundary surface sets and named node sets, as Gmsh
//! physical groups or Abaqus/CalculiX `.inp` sets give them.
//!
//! Node numbering inside an element follows Gmsh (which, for the linear
//! elements, is also VTK's): Tet4 `0‥3`; Hex8 bottom face `0‥3`
//! counter-clockwise seen from outside… i.e. from below, top face `4‥7`
//! above them; Wedge6 bottom triangle `0‥2`, top `3‥5`. The quadratic
//! elements (Tet10, Hex20, Wedge15) add their mid-side nodes in Gmsh's
//! edge order; VTK and Abaqus order them differently ([`topology`]).

pub mod arrays;
pub mod boundary;
pub mod gmsh;
pub mod inp;
pub mod stl;
pub mod structured;
pub mod topology;

use crate::Result;
use std::path::Path;

/// Reads the mesh file of a case, by its extension: `.inp` (any case) is an
/// Abaqus/CalculiX deck ([`inp::read_inp`]), anything else a Gmsh MSH file
/// ([`gmsh::read_msh`]). Returns the mesh and notes for the user (e.g. the
/// `.inp` keywords that were ignored).
pub fn read_mesh(path: &Path) -> Result<(Mesh, Vec<String>)> {
    read_mesh_with(path, &crate::input::Limits::default())
}

/// [`read_mesh`] within `limits` (what the mesh's files may make the
/// reader produce).
pub fn read_mesh_with(path: &Path, limits: &crate::input::Limits) -> Result<(Mesh, Vec<String>)> {
    let is_inp = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("inp"));
    if is_inp {
        let deck = inp::read_inp_with(path, limits)?;
        Ok((deck.mesh, deck.notes))
    } else {
        Ok((gmsh::read_msh(path)?, Vec::new()))
    }
}

/// Volume element types. Adding a type means a variant here, its node
/// orders and faces in [`topology`], its shape functions and quadrature
/// rule in [`crate::fem`], and its Gmsh/VTK/Abaqus type names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ElementKind {
    /// 4-node linear tetrahedron.
    Tet4,
    /// 8-node trilinear hexahedron.
    Hex8,
    /// 10-node quadratic tetrahedron (Abaqus C3D10).
    Tet10,
    /// 20-node serendipity hexahedron, 3×3×3 Gauss points (C3D20).
    Hex20,
    /// 20-node serendipity hexahedron with 2×2×2 reduced integration
    /// (C3D20R).
    Hex20R,
    /// 6-node linear wedge (prism, C3D6).
    Wedge6,
    /// 15-node quadratic wedge (C3D15).
    Wedge15,
}

impl ElementKind {
    /// Number of nodes.
    pub fn num_nodes(self) -> usize {
        match self {
            ElementKind::Tet4 => 4,
            ElementKind::Hex8 => 8,
            ElementKind::Tet10 => 10,
            ElementKind::Hex20 | ElementKind::Hex20R => 20,
            ElementKind::Wedge6 => 6,
            ElementKind::Wedge15 => 15,
        }
    }
    /// Gmsh element type number.
    pub fn gmsh_type(self) -> i32 {
        match self {
            ElementKind::Tet4 => 4,
            ElementKind::Hex8 => 5,
            ElementKind::Tet10 => 11,
            ElementKind::Hex20 | ElementKind::Hex20R => 17,
            ElementKind::Wedge6 => 6,
            ElementKind::Wedge15 => 18,
        }
    }
    /// The kind of a Gmsh volume element type number, if supported.
    pub fn from_gmsh_type(gmsh_type: i64) -> Option<Self> {
        [
            ElementKind::Tet4,
            ElementKind::Hex8,
            ElementKind::Tet10,
            ElementKind::Hex20,
            ElementKind::Wedge6,
            ElementKind::Wedge15,
        ]
        .into_iter()
        .find(|k| i64::from(k.gmsh_type()) == gmsh_type)
    }
    /// VTK cell type number.
    pub fn vtk_type(self) -> u8 {
        match self {
            ElementKind::Tet4 => 10,
            ElementKind::Hex8 => 12,
            ElementKind::Tet10 => 24,
            ElementKind::Hex20 | ElementKind::Hex20R => 25,
            ElementKind::Wedge6 => 13,
            ElementKind::Wedge15 => 26,
        }
    }
    /// VTK's node order: VTK's node `i` is this crate's (Gmsh's) node
    /// `vtk_order()[i]`. Abaqus/CalculiX number the nodes as VTK does.
    pub fn vtk_order(self) -> &'static [usize] {
        topology::vtk_order(self)
    }
    /// Whether the element has mid-side nodes.
    pub fn is_quadratic(self) -> bool {
        matches!(
            self,
            ElementKind::Tet10 | ElementKind::Hex20 | ElementKind::Hex20R | ElementKind::Wedge15
        )
    }
    /// The element's faces as lists of local node indices, ordered so that
    /// the right-hand rule on the corners gives the outward normal; a
    /// quadratic face lists its corners, then its mid-side nodes in the
    /// order of its edges `(0,1), (1,2), …` (Tri6, Quad8).
    pub fn faces(self) -> &'static [&'static [usize]] {
        topology::faces(self)
    }
}

/// Boundary facet types.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FacetKind {
    /// 3-node linear triangle.
    Tri3,
    /// 4-node bilinear quadrangle.
    Quad4,
    /// 6-node quadratic triangle: corners, then mid-sides `(0,1), (1,2),
    /// (2,0)`.
    Tri6,
    /// 8-node serendipity quadrangle: corners, then mid-sides `(0,1),
    /// (1,2), (2,3), (3,0)`.
    Quad8,
}

impl FacetKind {
    /// Number of nodes.
    pub fn num_nodes(self) -> usize {
        match self {
            FacetKind::Tri3 => 3,
            FacetKind::Quad4 => 4,
            FacetKind::Tri6 => 6,
            FacetKind::Quad8 => 8,
        }
    }
    /// Number of corner nodes (the first ones).
    pub fn num_corners(self) -> usize {
        match self {
            FacetKind::Tri3 | FacetKind::Tri6 => 3,
            FacetKind::Quad4 | FacetKind::Quad8 => 4,
        }
    }
    /// The facet kind of `n` nodes (3, 4, 6 or 8).
    pub fn of_node_count(n: usize) -> Option<Self> {
        match n {
            3 => Some(FacetKind::Tri3),
            4 => Some(FacetKind::Quad4),
            6 => Some(FacetKind::Tri6),
            8 => Some(FacetKind::Quad8),
            _ => None,
        }
    }
    /// Whether the facet has mid-side nodes.
    pub fn is_quadratic(self) -> bool {
        matches!(self, FacetKind::Tri6 | FacetKind::Quad8)
    }
    /// Gmsh element type number.
    pub fn gmsh_type(self) -> i32 {
        match self {
            FacetKind::Tri3 => 2,
            FacetKind::Quad4 => 3,
            FacetKind::Tri6 => 9,
            FacetKind::Quad8 => 16,
        }
    }
    /// VTK cell type number.
    pub fn vtk_type(self) -> u8 {
        match self {
            FacetKind::Tri3 => 5,
            FacetKind::Quad4 => 9,
            FacetKind::Tri6 => 22,
            FacetKind::Quad8 => 23,
        }
    }
}

/// A volume element: its type, node indices (into [`Mesh::nodes`]) and the
/// id the mesh file gave it (used in every message to the user).
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    pub kind: ElementKind,
    pub nodes: Vec<usize>,
    pub id: u64,
}

/// A boundary facet. After [`Mesh::orient_surfaces`] its node order gives,
/// by the right-hand rule, the outward normal of the body.
#[derive(Clone, Debug, PartialEq)]
pub struct Facet {
    pub kind: FacetKind,
    pub nodes: Vec<usize>,
    pub id: u64,
}

/// A named volume region (a 3D physical group): indices into
/// [`Mesh::elements`].
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    pub name: String,
    pub elements: Vec<usize>,
}

/// A named surface set (a 2D physical group).
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceSet {
    pub name: String,
    pub facets: Vec<Facet>,
}

/// A named node set (a 0D or 1D Gmsh physical group, an `.inp` `*NSET`):
/// sorted, distinct indices into [`Mesh::nodes`].
#[derive(Clone, Debug, PartialEq)]
pub struct NodeSet {
    pub name: String,
    pub nodes: Vec<usize>,
}

/// A mesh in the reference configuration.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Reference coordinates `X` of every node.
    pub nodes: Vec<[f64; 3]>,
    /// The mesh file's tag of every node (same indexing as `nodes`).
    pub node_ids: Vec<u64>,
    /// Volume elements.
    pub elements: Vec<Element>,
    /// Named volume regions. Volume elements in no 3D physical group are
    /// collected in a region named `"default"`.
    pub regions: Vec<Region>,
    /// Named boundary surface sets.
    pub surfaces: Vec<SurfaceSet>,
    /// Named node sets.
    pub node_sets: Vec<NodeSet>,
}

impl Mesh {
    /// Number of nodes.
    pub fn num_nodes(&self) -> usize {
        self.nodes.len()
    }
    /// The region called `name`.
    pub fn region(&self, name: &str) -> Option<&Region> {
        self.regions.iter().find(|r| r.name == name)
    }
    /// The surface set called `name`.
    pub fn surface(&self, name: &str) -> Option<&SurfaceSet> {
        self.surfaces.iter().find(|s| s.name == name)
    }
    /// The node set called `name`.
    pub fn node_set(&self, name: &str) -> Option<&NodeSet> {
        self.node_sets.iter().find(|s| s.name == name)
    }
    /// Names of all node sets, for error messages.
    pub fn node_set_names(&self) -> Vec<String> {
        self.node_sets.iter().map(|s| s.name.clone()).collect()
    }
    /// Names of all regions, for error messages.
    pub fn region_names(&self) -> Vec<String> {
        self.regions.iter().map(|r| r.name.clone()).collect()
    }
    /// Names of all surface sets, for error messages.
    pub fn surface_names(&self) -> Vec<String> {
        self.surfaces.iter().map(|s| s.name.clone()).collect()
    }
    /// Empty the node list of every element not in `keep` (a mask over
    /// the elements): a process of a distributed run holds the
    /// connectivity of the elements it reads and no other
    /// (`Model::hold_elements`). Indices, kinds, ids, regions, surface
    /// sets and nodes stay, so every element keeps its index; an element
    /// without nodes is one this process does not hold
    /// ([`Mesh::holds_element`]).
    pub fn release_elements(&mut self, keep: &[bool]) {
        for (element, _) in self.elements.iter_mut().zip(keep).filter(|(_, &k)| !k) {
            element.nodes = Vec::new();
        }
    }

    /// Whether this mesh holds element `e`'s connectivity (all of them,
    /// unless [`Mesh::release_elements`] emptied some).
    pub fn holds_element(&self, e: usize) -> bool {
        !self.elements[e].nodes.is_empty()
    }

    /// The number of elements whose connectivity this mesh holds.
    pub fn held_elements(&self) -> usize {
        self.elements.iter().filter(|e| !e.nodes.is_empty()).count()
    }

    /// Sorted, deduplicated node indices of a surface set.
    pub fn surface_nodes(&self, surface: &SurfaceSet) -> Vec<usize> {
        let mut nodes: Vec<usize> = surface
            .facets
            .iter()
            .flat_map(|f| f.nodes.iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }
}
