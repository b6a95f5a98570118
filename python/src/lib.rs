//! `signorini._signorini`: the compiled half of the Python package. It
//! wraps the library's [`signorini::case::Case`] and
//! [`signorini::run::Simulation`] and adds no mechanics: arrays in (a mesh
//! as numpy arrays, a case table as a dict or TOML text), every converged
//! increment out as numpy arrays through a [`StepObserver`], the crate's
//! [`Error`] as Python exceptions with the same messages.
//!
//! A run goes on a thread of its own with the GIL released; the calling
//! (main) thread waits for its increments, calls the Python callback with
//! each, and checks for Ctrl-C while it waits, so that a run stops cleanly
//! after the increment in progress.

mod convert;
mod observer;

use numpy::{PyArray1, PyArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use signorini::mesh::{ElementKind, Mesh};
use signorini::output::OutputField;
use signorini::run::{RunOptions, Simulation as RustSimulation};
use signorini::Error;
use std::path::PathBuf;

create_exception!(
    signorini,
    SignoriniError,
    PyException,
    "Every error of signorini (the message is the solver's)."
);
create_exception!(
    signorini,
    CaseError,
    SignoriniError,
    "Input that cannot be used: the case table (with its key path), the mesh, a material, a file."
);
create_exception!(
    signorini,
    MeshError,
    CaseError,
    "A mesh that cannot be read or used (a file's line, an array's row)."
);
create_exception!(
    signorini,
    ConvergenceError,
    SignoriniError,
    "The solve failed: Newton did not converge after the allowed cuts, a singular matrix, an element inverted during the run."
);

/// The Python exception of a solver error, with the same message.
pub(crate) fn to_py(error: Error) -> PyErr {
    let message = error.to_string();
    match error {
        Error::MeshSyntax { .. } | Error::Mesh { .. } => MeshError::new_err(message),
        Error::InvertedElement {
            in_reference: false,
            ..
        }
        | Error::LinearSolver(_)
        | Error::NoConvergence { .. } => ConvergenceError::new_err(message),
        Error::Interrupted { .. } => SignoriniError::new_err(message),
        _ => CaseError::new_err(message),
    }
}

/// A case: a mesh with materials, boundary conditions, loads, contacts and
/// steps, validated as the command line validates a case file.
#[pyclass(module = "signorini._signorini", frozen)]
pub struct Case {
    inner: signorini::case::Case,
}

#[pymethods]
impl Case {
    /// Read a case file (TOML) and the mesh it names.
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Self> {
        let inner = signorini::case::load(&path).map_err(to_py)?;
        Ok(Case { inner })
    }

    /// A case from the text of a case file; its paths (the mesh, the
    /// output folder) are relative to `base_dir`.
    #[staticmethod]
    #[pyo3(signature = (text, base_dir = PathBuf::from(".")))]
    fn from_toml(text: &str, base_dir: PathBuf) -> PyResult<Self> {
        let inner = signorini::case::from_toml(text, &base_dir).map_err(to_py)?;
        Ok(Case { inner })
    }

    /// A case around a mesh given as arrays. `nodes` (n, 3) float;
    /// `tetrahedra` (m, 4), `hexahedra` (m, 8), `tetrahedra10` (m, 10),
    /// `hexahedra20` (m, 20), `wedges` (m, 6) and/or `wedges15` (m, 15)
    /// node indices (0-based, VTK's order, as meshio gives them; elements
    /// are numbered in that order of the arguments); `regions`
    /// {name: element indices} (elements in none form the region
    /// "default"); `surfaces` {name: (k, 3), (k, 4), (k, 6) or (k, 8) facet
    /// node indices};
    /// `node_sets` {name: node indices} (for `[[displacement]] nodes =`
    /// and `[[nodal_force]] nodes =`); `spec` the rest of the case file as
    /// TOML text or a dict (without `[mesh]`). Errors are those of a case
    /// file.
    #[staticmethod]
    #[pyo3(signature = (nodes, spec, *, tetrahedra = None, hexahedra = None, regions = None, surfaces = None, base_dir = PathBuf::from("."), tetrahedra10 = None, hexahedra20 = None, wedges = None, wedges15 = None, node_sets = None))]
    #[allow(clippy::too_many_arguments)]
    fn from_arrays(
        nodes: &Bound<'_, PyAny>,
        spec: &Bound<'_, PyAny>,
        tetrahedra: Option<&Bound<'_, PyAny>>,
        hexahedra: Option<&Bound<'_, PyAny>>,
        regions: Option<&Bound<'_, PyDict>>,
        surfaces: Option<&Bound<'_, PyDict>>,
        base_dir: PathBuf,
        tetrahedra10: Option<&Bound<'_, PyAny>>,
        hexahedra20: Option<&Bound<'_, PyAny>>,
        wedges: Option<&Bound<'_, PyAny>>,
        wedges15: Option<&Bound<'_, PyAny>>,
        node_sets: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let nodes: Vec<[f64; 3]> = convert::rows(nodes, "nodes")?;
        let mut elements: Vec<(ElementKind, Vec<usize>)> = Vec::new();
        if let Some(t) = tetrahedra {
            let rows: Vec<[usize; 4]> = convert::index_rows(t, "tetrahedra")?;
            elements.extend(rows.iter().map(|r| (ElementKind::Tet4, r.to_vec())));
        }
        if let Some(h) = hexahedra {
            let rows: Vec<[usize; 8]> = convert::index_rows(h, "hexahedra")?;
            elements.extend(rows.iter().map(|r| (ElementKind::Hex8, r.to_vec())));
        }
        // the other kinds in VTK's (meshio's) node order, then
        // tetrahedra10, hexahedra20, wedges, wedges15
        let more = [
            (tetrahedra10, ElementKind::Tet10, "tetrahedra10"),
            (hexahedra20, ElementKind::Hex20, "hexahedra20"),
            (wedges, ElementKind::Wedge6, "wedges"),
            (wedges15, ElementKind::Wedge15, "wedges15"),
        ];
        for (array, kind, name) in more {
            if let Some(a) = array {
                let rows = convert::facets(a, name, &[kind.num_nodes()])?;
                elements.extend(
                    rows.iter()
                        .map(|r| (kind, signorini::mesh::topology::from_vtk_order(kind, r))),
                );
            }
        }
        let mut region_list = Vec::new();
        for (name, members) in regions.into_iter().flat_map(|d| d.iter()) {
            let name: String = name.extract()?;
            let members = convert::indices(&members, &format!("regions['{name}']"))?;
            region_list.push((name, members));
        }
        let mut surface_list = Vec::new();
        for (name, facets) in surfaces.into_iter().flat_map(|d| d.iter()) {
            let name: String = name.extract()?;
            let facets = convert::facets(&facets, &format!("surfaces['{name}']"), &[3, 4, 6, 8])?;
            surface_list.push((name, facets));
        }
        let mut node_set_list = Vec::new();
        for (name, members) in node_sets.into_iter().flat_map(|d| d.iter()) {
            let name: String = name.extract()?;
            let members = convert::indices(&members, &format!("node_sets['{name}']"))?;
            node_set_list.push((name, members));
        }
        let mesh = Mesh::from_arrays(nodes, elements, region_list, surface_list)
            .and_then(|mesh| mesh.with_node_sets(node_set_list))
            .map_err(to_py)?;
        let text = convert::spec_text(spec)?;
        let inner = signorini::case::from_mesh(&text, &base_dir, mesh).map_err(to_py)?;
        Ok(Case { inner })
    }

    /// The case file (or `base_dir/case` for a case from text or arrays).
    #[getter]
    fn path(&self) -> PathBuf {
        self.inner.path.clone()
    }

    /// Reference node coordinates, (n, 3).
    #[getter]
    fn nodes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let flat: Vec<f64> = self.inner.mesh.nodes.iter().flatten().copied().collect();
        convert::array(py, flat, 3)
    }

    /// The elements as consecutive blocks of one kind, in element order:
    /// a list of (meshio cell type "tetra", "hexahedron", "tetra10",
    /// "hexahedron20", "wedge" or "wedge15", (m, k) node indices in VTK's
    /// order).
    #[getter]
    fn cells<'py>(&self, py: Python<'py>) -> PyResult<Vec<(&'static str, Bound<'py, PyAny>)>> {
        let mut blocks: Vec<(ElementKind, Vec<i64>)> = Vec::new();
        for e in &self.inner.mesh.elements {
            // meshio's node order is VTK's
            let nodes = e.kind.vtk_order().iter().map(|&a| e.nodes[a] as i64);
            match blocks.last_mut() {
                Some((kind, block)) if *kind == e.kind => block.extend(nodes),
                _ => blocks.push((e.kind, nodes.collect())),
            }
        }
        blocks
            .into_iter()
            .map(|(kind, nodes)| {
                let name = match kind {
                    ElementKind::Tet4 => "tetra",
                    ElementKind::Hex8 => "hexahedron",
                    ElementKind::Tet10 => "tetra10",
                    ElementKind::Hex20 | ElementKind::Hex20R => "hexahedron20",
                    ElementKind::Wedge6 => "wedge",
                    ElementKind::Wedge15 => "wedge15",
                };
                let k = kind.num_nodes();
                let rows = nodes.len() / k;
                let array = PyArray1::from_vec(py, nodes).reshape([rows, k])?;
                Ok((name, array.into_any()))
            })
            .collect()
    }

    /// Names of the volume regions.
    #[getter]
    fn region_names(&self) -> Vec<String> {
        self.inner.mesh.region_names()
    }

    /// Names of the surface sets.
    #[getter]
    fn surface_names(&self) -> Vec<String> {
        self.inner.mesh.surface_names()
    }

    /// Names of the node sets.
    #[getter]
    fn node_set_names(&self) -> Vec<String> {
        self.inner.mesh.node_set_names()
    }

    /// Sorted node indices of a surface set.
    fn surface_nodes<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let mesh = &self.inner.mesh;
        let surface = mesh.surface(name).ok_or_else(|| {
            CaseError::new_err(format!(
                "the mesh has no surface set named '{name}'; it has: {}",
                mesh.surface_names().join(", ")
            ))
        })?;
        let nodes: Vec<i64> = mesh
            .surface_nodes(surface)
            .iter()
            .map(|&n| n as i64)
            .collect();
        Ok(PyArray1::from_vec(py, nodes).into_any())
    }

    fn __repr__(&self) -> String {
        format!(
            "Case('{}', {} nodes, {} elements)",
            self.inner.path.display(),
            self.inner.mesh.num_nodes(),
            self.inner.mesh.elements.len()
        )
    }
}

/// A problem built from a case, ready to run (the Python `Simulation`
/// wraps it).
#[pyclass(module = "signorini._signorini")]
struct NativeSimulation {
    inner: RustSimulation,
    options: RunOptions,
}

#[pymethods]
impl NativeSimulation {
    #[new]
    #[pyo3(signature = (case, threads = None, output = None, restart = None))]
    fn new(
        case: &Case,
        threads: Option<usize>,
        output: Option<PathBuf>,
        restart: Option<PathBuf>,
    ) -> PyResult<Self> {
        if threads == Some(0) {
            return Err(CaseError::new_err(
                "threads must be at least 1 (or None: one per core)",
            ));
        }
        let inner = RustSimulation::from_case(&case.inner).map_err(to_py)?;
        Ok(NativeSimulation {
            inner,
            options: RunOptions {
                output,
                threads,
                cancel: None,
                restart,
            },
        })
    }

    /// Run every step. Returns (status, increments, summary JSON, error):
    /// the error (not raised) when the run failed, the increments
    /// converged before it kept. `fields`: names of the fields to keep
    /// besides the nodal ones every increment has (the recovered nodal
    /// stresses, the element stresses and strains), as `[output] fields`
    /// names them.
    #[pyo3(signature = (callback = None, stresses = false, fields = Vec::new()))]
    fn run(
        &mut self,
        py: Python<'_>,
        callback: Option<PyObject>,
        stresses: bool,
        fields: Vec<String>,
    ) -> PyResult<(String, Py<PyList>, String, Option<PyObject>)> {
        let fields = fields
            .iter()
            .map(|name| name.parse::<OutputField>().map_err(CaseError::new_err))
            .collect::<PyResult<Vec<_>>>()?;
        let keep = observer::Keep { stresses, fields };
        observer::run(py, &mut self.inner, &self.options, callback, keep)
    }
}

/// A case table (a dict) as the TOML text of a case file.
#[pyfunction]
fn dict_to_toml(spec: &Bound<'_, PyAny>) -> PyResult<String> {
    convert::spec_text(spec)
}

/// Hertz's contact radius from nodal pressures `p` at distances `r` from
/// the axis: the least-squares fit of `p² = p₀² (1 − r²/a²)` (a line in
/// `r²`) over the nodes with `p > threshold`, `a = √(−c₀/c₁)`
/// (`signorini::contact::hertz::fitted_contact_radius`).
#[pyfunction]
fn fitted_contact_radius(r: Vec<f64>, p: Vec<f64>, threshold: f64) -> PyResult<f64> {
    if r.len() != p.len() {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "r has {} values and p {}; give one pressure per radius",
            r.len(),
            p.len()
        )));
    }
    let nodes: Vec<(f64, f64)> = r.into_iter().zip(p).collect();
    Ok(signorini::contact::hertz::fitted_contact_radius(
        &nodes, threshold,
    ))
}

#[pymodule]
fn _signorini(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<Case>()?;
    m.add_class::<NativeSimulation>()?;
    m.add_class::<observer::Increment>()?;
    m.add_function(wrap_pyfunction!(dict_to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(fitted_contact_radius, m)?)?;
    m.add("SignoriniError", py.get_type::<SignoriniError>())?;
    m.add("CaseError", py.get_type::<CaseError>())?;
    m.add("MeshError", py.get_type::<MeshError>())?;
    m.add("ConvergenceError", py.get_type::<ConvergenceError>())?;
    Ok(())
}
