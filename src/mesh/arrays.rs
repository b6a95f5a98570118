//! A mesh given as arrays in code (a script's numpy arrays, say) rather
//! than read from a file: node coordinates, element connectivities, named
//! regions and surface sets, checked as the Gmsh reader checks a file.
//!
//! Indices are 0-based and the ids that messages show are the indices
//! themselves, so an error names the row of the caller's array.

use super::{Element, ElementKind, Facet, FacetKind, Mesh, Region, SurfaceSet};
use crate::{Error, Result};
use std::path::PathBuf;

/// The name a mesh built from arrays goes by in messages.
pub const ARRAYS: &str = "<arrays>";

fn invalid(message: String) -> Error {
    Error::Mesh {
        path: PathBuf::from(ARRAYS),
        message,
    }
}

/// Checks that every index of `nodes` is below `n` and that none repeats;
/// `what` names the owner ("element 3") in the message.
fn check_nodes(what: &str, nodes: &[usize], n: usize) -> Result<()> {
    for (i, &a) in nodes.iter().enumerate() {
        if a >= n {
            return Err(invalid(format!(
                "{what} refers to node {a}, but the mesh has {n} nodes (indices 0 to {})",
                n.saturating_sub(1)
            )));
        }
        if nodes[..i].contains(&a) {
            return Err(invalid(format!("{what} has node {a} more than once")));
        }
    }
    Ok(())
}

/// Refuses a name that is empty or given twice.
fn check_name(kind: &str, name: &str, seen: &[&str]) -> Result<()> {
    if name.is_empty() {
        return Err(invalid(format!("a {kind} has an empty name")));
    }
    if seen.contains(&name) {
        return Err(invalid(format!("two {kind}s are named '{name}'")));
    }
    Ok(())
}

impl Mesh {
    /// A mesh from arrays: `nodes` the reference coordinates; `elements`
    /// each element's kind and node indices (Gmsh/VTK order, see the
    /// module documentation of [`crate::mesh`]); `regions` named lists of
    /// element indices (elements in none form the region `"default"`, as
    /// with the Gmsh reader); `surfaces` named lists of facets, each 3
    /// (triangle) or 4 (quadrangle) node indices of an element face in any
    /// orientation (they are turned outward). Errors name the offending
    /// element, facet or name; inverted elements are found when the
    /// problem is built ([`Error::InvertedElement`]).
    pub fn from_arrays(
        nodes: Vec<[f64; 3]>,
        elements: Vec<(ElementKind, Vec<usize>)>,
        regions: Vec<(String, Vec<usize>)>,
        surfaces: Vec<(String, Vec<Vec<usize>>)>,
    ) -> Result<Mesh> {
        let n = nodes.len();
        if let Some(i) = nodes.iter().position(|x| x.iter().any(|v| !v.is_finite())) {
            return Err(invalid(format!(
                "node {i} has a coordinate that is not finite: {:?}",
                nodes[i]
            )));
        }
        if elements.is_empty() {
            return Err(invalid(
                "the mesh has no volume elements (give tetrahedra or hexahedra)".into(),
            ));
        }
        let elements = elements
            .into_iter()
            .enumerate()
            .map(|(e, (kind, nodes))| {
                if nodes.len() != kind.num_nodes() {
                    return Err(invalid(format!(
                        "element {e} ({kind:?}) has {} nodes; it needs {}",
                        nodes.len(),
                        kind.num_nodes()
                    )));
                }
                check_nodes(&format!("element {e}"), &nodes, n)?;
                Ok(Element {
                    kind,
                    nodes,
                    id: e as u64,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let mut in_region = vec![false; elements.len()];
        let mut named: Vec<&str> = Vec::new();
        for (name, members) in &regions {
            check_name("region", name, &named)?;
            named.push(name);
            for &e in members {
                if e >= elements.len() {
                    return Err(invalid(format!(
                        "region '{name}' refers to element {e}, but the mesh has {} elements (indices 0 to {})",
                        elements.len(),
                        elements.len() - 1
                    )));
                }
                in_region[e] = true;
            }
        }
        let default: Vec<usize> = (0..elements.len()).filter(|&e| !in_region[e]).collect();
        if !default.is_empty() {
            check_name("region", "default", &named)?;
        }
        let mut regions: Vec<Region> = regions
            .into_iter()
            .map(|(name, elements)| Region { name, elements })
            .collect();
        if !default.is_empty() {
            regions.push(Region {
                name: "default".into(),
                elements: default,
            });
        }
        let mut named: Vec<&str> = Vec::new();
        for (name, _) in &surfaces {
            check_name("surface set", name, &named)?;
            named.push(name);
        }
        let surfaces = surfaces
            .into_iter()
            .map(|(name, facets)| {
                let facets = facets
                    .into_iter()
                    .enumerate()
                    .map(|(f, nodes)| {
                        let kind = match FacetKind::of_node_count(nodes.len()) {
                            Some(kind) => kind,
                            None => {
                                return Err(invalid(format!(
                                    "facet {f} of surface '{name}' has {} nodes; a facet has 3 (triangle), 4 (quadrangle), 6 (quadratic triangle) or 8 (quadratic quadrangle)",
                                    nodes.len()
                                )))
                            }
                        };
                        check_nodes(&format!("facet {f} of surface '{name}'"), &nodes, n)?;
                        Ok(Facet {
                            kind,
                            nodes,
                            id: f as u64,
                        })
                    })
                    .collect::<Result<Vec<_>>>()?;
                Ok(SurfaceSet { name, facets })
            })
            .collect::<Result<Vec<_>>>()?;
        let mut mesh = Mesh {
            node_ids: (0..n as u64).collect(),
            nodes,
            elements,
            regions,
            surfaces,
            node_sets: Vec::new(),
        };
        let orphans = mesh.orient_surfaces();
        if let Some(first) = orphans.first() {
            let more = match orphans.len() - 1 {
                0 => String::new(),
                k => format!(" ({k} more such facets)"),
            };
            return Err(invalid(format!(
                "facet {} of surface '{}' is not a face of any volume element{more}",
                first.facet_id, first.surface
            )));
        }
        Ok(mesh)
    }
}

impl Mesh {
    /// The mesh with named node sets given as arrays (`sets`: a name and
    /// 0-based node indices each), as `[[displacement]] nodes =` and
    /// `[[nodal_force]] nodes =` name them; checked as the other arrays:
    /// a name non-empty and not given twice (a node set may share its name
    /// with a surface set, as a Gmsh physical group of another dimension
    /// may), every index below the node count and none twice, no set
    /// empty. The sets follow any the mesh has.
    pub fn with_node_sets(mut self, sets: Vec<(String, Vec<usize>)>) -> Result<Mesh> {
        let n = self.num_nodes();
        let mut named: Vec<String> = self.node_sets.iter().map(|s| s.name.clone()).collect();
        for (name, nodes) in sets {
            let seen: Vec<&str> = named.iter().map(String::as_str).collect();
            check_name("node set", &name, &seen)?;
            if nodes.is_empty() {
                return Err(invalid(format!(
                    "node set '{name}' is empty: give it at least one node index"
                )));
            }
            let mut member = vec![false; n];
            for &a in &nodes {
                if a >= n {
                    return Err(invalid(format!(
                        "node set '{name}' refers to node {a}, but the mesh has {n} nodes (indices 0 to {})",
                        n.saturating_sub(1)
                    )));
                }
                if std::mem::replace(&mut member[a], true) {
                    return Err(invalid(format!(
                        "node set '{name}' has node {a} more than once"
                    )));
                }
            }
            named.push(name.clone());
            self.node_sets.push(super::NodeSet { name, nodes });
        }
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::structured::box_mesh;

    /// Nodes, elements, regions and surface sets, as `from_arrays` takes them.
    type Arrays = (
        Vec<[f64; 3]>,
        Vec<(ElementKind, Vec<usize>)>,
        Vec<(String, Vec<usize>)>,
        Vec<(String, Vec<Vec<usize>>)>,
    );

    /// The arrays of a box mesh, its facets given inside out.
    fn arrays(mesh: &Mesh) -> Arrays {
        let elements = mesh
            .elements
            .iter()
            .map(|e| (e.kind, e.nodes.clone()))
            .collect();
        let regions = mesh
            .regions
            .iter()
            .map(|r| (r.name.clone(), r.elements.clone()))
            .collect();
        let surfaces = mesh
            .surfaces
            .iter()
            .map(|s| {
                let facets = s
                    .facets
                    .iter()
                    .map(|f| {
                        let mut nodes = f.nodes.clone();
                        nodes[1..].reverse();
                        nodes
                    })
                    .collect();
                (s.name.clone(), facets)
            })
            .collect();
        (mesh.nodes.clone(), elements, regions, surfaces)
    }

    #[test]
    fn a_box_from_its_arrays_is_the_box_with_its_facets_turned_outward() {
        for kind in [ElementKind::Tet4, ElementKind::Hex8] {
            let reference = box_mesh(kind, [2, 1, 2], [1.0, 0.5, 2.0]);
            let (nodes, elements, regions, surfaces) = arrays(&reference);
            let mesh = Mesh::from_arrays(nodes, elements, regions, surfaces).unwrap();
            assert_eq!(mesh.nodes, reference.nodes);
            assert_eq!(mesh.regions, reference.regions);
            for (a, b) in mesh.elements.iter().zip(&reference.elements) {
                assert_eq!(a.nodes, b.nodes);
            }
            for (a, b) in mesh.surfaces.iter().zip(&reference.surfaces) {
                assert_eq!(a.name, b.name);
                let na: Vec<_> = a.facets.iter().map(|f| f.nodes.clone()).collect();
                let nb: Vec<_> = b.facets.iter().map(|f| f.nodes.clone()).collect();
                assert_eq!(na, nb);
            }
        }
    }

    fn message(result: Result<Mesh>) -> String {
        result.unwrap_err().to_string()
    }

    #[test]
    fn bad_arrays_are_errors_naming_the_row() {
        let reference = box_mesh(ElementKind::Tet4, [1, 1, 1], [1.0, 1.0, 1.0]);
        let (nodes, elements, regions, surfaces) = arrays(&reference);

        let mut bad = elements.clone();
        bad[3].1[2] = 99;
        let m = message(Mesh::from_arrays(
            nodes.clone(),
            bad,
            regions.clone(),
            surfaces.clone(),
        ));
        assert!(
            m.contains("element 3 refers to node 99, but the mesh has 8 nodes"),
            "{m}"
        );

        let mut bad = elements.clone();
        bad[1].1[1] = bad[1].1[0];
        let m = message(Mesh::from_arrays(
            nodes.clone(),
            bad,
            regions.clone(),
            surfaces.clone(),
        ));
        assert!(m.contains("element 1 has node"), "{m}");

        let mut bad = surfaces.clone();
        bad[2].1[1] = vec![1, 2, 4]; // not a face of any of the cube's tetrahedra
        let m = message(Mesh::from_arrays(
            nodes.clone(),
            elements.clone(),
            regions.clone(),
            bad,
        ));
        assert!(
            m.contains(&format!(
                "facet 1 of surface '{}' is not a face of any volume element",
                surfaces[2].0
            )),
            "{m}"
        );

        let mut bad = regions.clone();
        bad[0].1.push(6);
        let m = message(Mesh::from_arrays(
            nodes.clone(),
            elements.clone(),
            bad,
            surfaces.clone(),
        ));
        assert!(
            m.contains("region 'body' refers to element 6, but the mesh has 6 elements"),
            "{m}"
        );

        let mut bad = nodes.clone();
        bad[5][1] = f64::NAN;
        let m = message(Mesh::from_arrays(bad, elements, regions, surfaces));
        assert!(
            m.contains("node 5 has a coordinate that is not finite"),
            "{m}"
        );
    }

    #[test]
    fn node_sets_from_arrays_are_named_and_checked() {
        let reference = box_mesh(ElementKind::Hex8, [1, 1, 1], [1.0, 1.0, 1.0]);
        let (nodes, elements, regions, surfaces) = arrays(&reference);
        let mesh = || {
            Mesh::from_arrays(
                nodes.clone(),
                elements.clone(),
                regions.clone(),
                surfaces.clone(),
            )
            .unwrap()
        };
        let with = mesh()
            .with_node_sets(vec![("corner".into(), vec![0]), ("tip".into(), vec![7, 6])])
            .unwrap();
        assert_eq!(with.node_set("corner").unwrap().nodes, [0]);
        assert_eq!(with.node_set("tip").unwrap().nodes, [7, 6]);
        assert_eq!(with.node_set_names(), ["corner", "tip"]);
        let bad = |sets: Vec<(String, Vec<usize>)>| message(mesh().with_node_sets(sets));
        let m = bad(vec![("tip".into(), vec![8])]);
        assert!(
            m.contains(
                "node set 'tip' refers to node 8, but the mesh has 8 nodes (indices 0 to 7)"
            ),
            "{m}"
        );
        let m = bad(vec![("tip".into(), vec![3, 3])]);
        assert!(
            m.contains("node set 'tip' has node 3 more than once"),
            "{m}"
        );
        let m = bad(vec![("a".into(), vec![1]), ("a".into(), vec![2])]);
        assert!(m.contains("two node sets are named 'a'"), "{m}");
        let m = bad(vec![("a".into(), vec![])]);
        assert!(m.contains("node set 'a' is empty"), "{m}");
        let m = bad(vec![(String::new(), vec![1])]);
        assert!(m.contains("a node set has an empty name"), "{m}");
    }
}
