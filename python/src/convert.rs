//! Python values in and out: numpy arrays of a mesh to Rust vectors (with
//! their shapes checked), Rust vectors to numpy arrays (moved, not copied),
//! and a case table given as a dict to the TOML text of a case file.

use crate::{CaseError, MeshError};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList, PyString, PyTuple};

/// `obj` as a C-contiguous numpy array of `dtype`, with its shape.
fn numpy_array<'py, T: numpy::Element + Copy>(
    obj: &Bound<'py, PyAny>,
    dtype: &str,
    what: &str,
) -> PyResult<(Vec<T>, Vec<usize>)> {
    let py = obj.py();
    let np = py.import("numpy")?;
    let array = np
        .call_method1("ascontiguousarray", (obj, dtype))
        .map_err(|e| MeshError::new_err(format!("{what}: not an array of {dtype}: {e}")))?;
    let array = array.downcast::<PyArrayDyn<T>>()?;
    let shape = array.shape().to_vec();
    let values = array.readonly().as_slice()?.to_vec();
    Ok((values, shape))
}

/// A (n, K) float array as rows.
pub fn rows<const K: usize>(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[f64; K]>> {
    let (values, shape) = numpy_array::<f64>(obj, "float64", what)?;
    if shape.len() != 2 || shape[1] != K {
        return Err(MeshError::new_err(format!(
            "{what}: the array has shape {shape:?}; it needs shape (n, {K})"
        )));
    }
    Ok(values
        .chunks(K)
        .map(|c| std::array::from_fn(|i| c[i]))
        .collect())
}

/// Non-negative integers as indices; `what` names the array in the message.
fn to_indices(values: Vec<i64>, what: &str) -> PyResult<Vec<usize>> {
    values
        .into_iter()
        .map(|v| {
            usize::try_from(v).map_err(|_| {
                MeshError::new_err(format!("{what}: index {v} is negative; indices start at 0"))
            })
        })
        .collect()
}

/// A (m, K) integer array as rows of indices.
pub fn index_rows<const K: usize>(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[usize; K]>> {
    let (values, shape) = numpy_array::<i64>(obj, "int64", what)?;
    if shape.len() != 2 || shape[1] != K {
        return Err(MeshError::new_err(format!(
            "{what}: the array has shape {shape:?}; it needs shape (m, {K})"
        )));
    }
    let values = to_indices(values, what)?;
    Ok(values
        .chunks(K)
        .map(|c| std::array::from_fn(|i| c[i]))
        .collect())
}

/// A 1-D integer array of indices.
pub fn indices(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<usize>> {
    let (values, shape) = numpy_array::<i64>(obj, "int64", what)?;
    if shape.len() != 1 {
        return Err(MeshError::new_err(format!(
            "{what}: the array has shape {shape:?}; it needs one dimension"
        )));
    }
    to_indices(values, what)
}

/// Rows of indices: a (k, w) integer array with `w` one of `widths`, or a
/// sequence of rows (of mixed widths: triangles and quadrangles, linear
/// or quadratic).
pub fn facets(obj: &Bound<'_, PyAny>, what: &str, widths: &[usize]) -> PyResult<Vec<Vec<usize>>> {
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        return obj
            .try_iter()?
            .enumerate()
            .map(|(i, row)| indices(&row?, &format!("{what}[{i}]")))
            .collect();
    }
    let (values, shape) = numpy_array::<i64>(obj, "int64", what)?;
    if shape.len() != 2 || !widths.contains(&shape[1]) {
        let needed: Vec<String> = widths.iter().map(|w| format!("(k, {w})")).collect();
        return Err(MeshError::new_err(format!(
            "{what}: the array has shape {shape:?}; it needs shape {}",
            needed.join(" or ")
        )));
    }
    let values = to_indices(values, what)?;
    Ok(values.chunks(shape[1]).map(<[usize]>::to_vec).collect())
}

/// `values` (`components` per node or element) as a numpy array that owns
/// them: (n,) for one component, else (n, components).
pub fn array(py: Python<'_>, values: Vec<f64>, components: usize) -> PyResult<Bound<'_, PyAny>> {
    let rows = values.len() / components.max(1);
    let array = PyArray1::from_vec(py, values);
    if components == 1 {
        Ok(array.into_any())
    } else {
        Ok(array.reshape([rows, components])?.into_any())
    }
}

/// A Python value of a case table as a TOML value; `key` is its path for
/// the message.
fn toml_value(obj: &Bound<'_, PyAny>, key: &str) -> PyResult<toml::Value> {
    if obj.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(obj.extract()?));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(obj.extract()?));
    }
    if let Ok(dict) = obj.downcast::<PyDict>() {
        return Ok(toml::Value::Table(toml_table(dict, key)?));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let items = obj
            .try_iter()?
            .enumerate()
            .map(|(i, item)| toml_value(&item?, &format!("{key}[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    if let Ok(i) = obj.extract::<i64>() {
        return Ok(toml::Value::Integer(i));
    }
    if let Ok(x) = obj.extract::<f64>() {
        return Ok(toml::Value::Float(x));
    }
    if obj.hasattr("tolist")? {
        // a numpy array or scalar
        return toml_value(&obj.call_method0("tolist")?, key);
    }
    Err(CaseError::new_err(format!(
        "{key}: a value of type {} has no TOML form; use a str, int, float, bool, list or dict",
        obj.get_type().name()?
    )))
}

fn toml_table(dict: &Bound<'_, PyDict>, key: &str) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (k, v) in dict.iter() {
        let name: String = k.extract().map_err(|_| {
            CaseError::new_err(format!("{key}: the keys of a case table are strings"))
        })?;
        let path = if key.is_empty() {
            name.clone()
        } else {
            format!("{key}.{name}")
        };
        if v.is_none() {
            continue; // an absent key, as in a case file
        }
        table.insert(name, toml_value(&v, &path)?);
    }
    Ok(table)
}

/// The case table as TOML text: `spec` itself if it is a str, else a dict
/// written as TOML (keys with value None left out).
pub fn spec_text(spec: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(text) = spec.extract::<String>() {
        return Ok(text);
    }
    let dict = spec.downcast::<PyDict>().map_err(|_| {
        CaseError::new_err("spec: give the case table as a dict or as TOML text (a str)")
    })?;
    let table = toml_table(dict, "")?;
    toml::to_string(&table).map_err(|e| CaseError::new_err(format!("spec: {e}")))
}
