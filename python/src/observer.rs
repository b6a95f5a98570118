//! A run with the GIL released: the simulation goes on a thread of its own
//! and a [`Relay`] observer sends every converged increment to the calling
//! thread, which turns it into an [`Increment`] of numpy arrays, calls the
//! Python callback and answers whether to go on. While it waits, the
//! calling thread (Python's main thread, where signal handlers run) checks
//! for Ctrl-C; Ctrl-C stops the run at its next Newton iteration (the
//! `cancel` flag of `RunOptions`), a callback after its increment, with
//! [`Error::Interrupted`], so the results stay consistent.

use crate::{convert, to_py, SignoriniError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use signorini::output::{
    CellField, ConvergedIncrement, NodalField, OutputField, StepObserver, Summary,
};
use signorini::run::{RunOptions, Simulation};
use signorini::Error;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::Arc;
use std::time::Duration;

/// How often the waiting thread looks for Ctrl-C.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// One converged increment, owned, on its way to the Python thread.
struct IncrementData {
    index: usize,
    step: usize,
    step_name: String,
    time: f64,
    increment: f64,
    iterations: usize,
    cuts: usize,
    /// Every nodal field of [`NodalField::ALL`], in that order: its
    /// values, `components()` per node.
    nodal: Vec<(NodalField, Vec<f64>)>,
    reaction_forces: Vec<(String, [f64; 3])>,
    /// The per-interface totals, as in `summary.json`.
    contact: String,
    /// Cauchy stress (9 per element) and von Mises, if asked for.
    stresses: Option<(Vec<f64>, Vec<f64>)>,
    /// The other fields asked for by name, with their values.
    extra: Vec<(OutputField, Vec<f64>)>,
}

/// What a run keeps of each increment besides the nodal fields of
/// [`NodalField::ALL`], which it always keeps.
pub struct Keep {
    /// The element Cauchy stress and von Mises (`run(stresses=True)`).
    pub stresses: bool,
    /// Other fields by name (`run(fields=[...])`): the recovered nodal
    /// stresses, the element stresses and strains.
    pub fields: Vec<OutputField>,
}

/// The values of `fields` at `inc`: the nodal ones by name, the cell ones
/// together (one stress evaluation for all).
fn extra_fields(inc: &ConvergedIncrement, fields: &[OutputField]) -> Vec<(OutputField, Vec<f64>)> {
    let cells: Vec<CellField> = fields
        .iter()
        .filter_map(|f| match f {
            OutputField::Cell(c) => Some(*c),
            OutputField::Nodal(_) => None,
        })
        .collect();
    let mut cell_values = inc.cells(&cells).into_iter();
    fields
        .iter()
        .map(|&field| {
            let values = match field {
                OutputField::Nodal(n) => inc.nodal(n).into_owned(),
                OutputField::Cell(_) => cell_values.next().unwrap_or_default(),
            };
            (field, values)
        })
        .collect()
}

impl IncrementData {
    fn new(inc: &ConvergedIncrement, index: usize, keep: &Keep) -> Self {
        let stresses = keep.stresses;
        let record = inc.record;
        IncrementData {
            index,
            step: record.step,
            step_name: record.step_name.clone(),
            time: record.time,
            increment: record.increment,
            iterations: record.iterations,
            cuts: record.cuts,
            nodal: NodalField::ALL
                .iter()
                .map(|&f| (f, inc.nodal(f).into_owned()))
                .collect(),
            reaction_forces: inc.reaction_forces(),
            contact: serde_json::to_string(&inc.contact_fields.summaries)
                .unwrap_or_else(|_| "{}".into()),
            stresses: stresses.then(|| {
                let mut cells = inc
                    .cells(&[CellField::CauchyStress, CellField::VonMises])
                    .into_iter();
                let sigma = cells.next().unwrap_or_default();
                let von_mises = cells.next().unwrap_or_default();
                (sigma, von_mises)
            }),
            extra: extra_fields(inc, &keep.fields),
        }
    }
}

/// The answer of the Python thread to an increment.
enum Reply {
    GoOn,
    Stop(String),
}

/// The observer on the run's thread: sends each increment and waits for
/// the answer; keeps the final summary.
struct Relay {
    to_python: mpsc::Sender<IncrementData>,
    from_python: mpsc::Receiver<Reply>,
    keep: Keep,
    count: usize,
    summary: Option<String>,
}

impl StepObserver for Relay {
    fn on_increment(&mut self, inc: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        self.count += 1;
        let data = IncrementData::new(inc, self.count - 1, &self.keep);
        let reply = match self.to_python.send(data) {
            Ok(()) => self.from_python.recv().unwrap_or(Reply::GoOn),
            Err(_) => Reply::Stop("the Python side is gone".into()),
        };
        match reply {
            Reply::GoOn => Ok(()),
            Reply::Stop(reason) => Err(Error::Interrupted { reason }),
        }
    }

    fn on_finish(&mut self, summary: &Summary) -> signorini::Result<()> {
        self.summary = serde_json::to_string(summary).ok();
        Ok(())
    }
}

/// One converged increment: its time, step and Newton iterations, and its
/// fields as numpy arrays (node and element order of the case's mesh).
#[pyclass(module = "signorini._signorini", frozen, get_all)]
pub struct Increment {
    /// 0-based number of the increment in the run.
    index: usize,
    /// 0-based index of the step and its name.
    step: usize,
    step_name: String,
    /// Pseudo-time at the end of the increment, and the increment's size.
    time: f64,
    increment: f64,
    /// Newton iterations, and cuts suffered before it converged.
    iterations: usize,
    cuts: usize,
    /// Displacement, (n, 3).
    displacement: PyObject,
    /// Contact pressure (compressive ≥ 0), (n,); 0 off contact surfaces.
    contact_pressure: PyObject,
    /// Signed gap (open > 0), (n,); NaN off the contact surfaces.
    gap: PyObject,
    /// 0 open, 1 stick (closed, frictionless included), 2 slip, (n,).
    contact_status: PyObject,
    /// Contact traction on the body t_N n + t_T, (n, 3).
    contact_traction: PyObject,
    /// Accumulated slip, (n, 3).
    slip: PyObject,
    /// This increment's slip (accumulated slip now minus before), (n, 3):
    /// nonzero exactly at the nodes that slipped during it.
    slip_increment: PyObject,
    /// {surface set: (3,) total of the residual over its nodes}: the
    /// reaction force where displacements are prescribed.
    reaction_forces: PyObject,
    /// {interface: totals as in summary.json (force, active nodes, ...)}.
    contact: PyObject,
    /// Element-averaged Cauchy stress (m, 3, 3) and von Mises (m,), when
    /// the run was asked for stresses; else None.
    cauchy_stress: Option<PyObject>,
    von_mises: Option<PyObject>,
    /// {field name: array} of every field kept: the nodal fields
    /// (displacement, …, node_id, slip_increment, accumulated_slip), those
    /// asked for with run(fields=[...]), and with stresses=True
    /// cauchy_stress and von_mises. Nodal (n, k) or (n,), cell (m, k) or
    /// (m,); 9 components as (·, 3, 3).
    fields: Py<PyDict>,
}

#[pymethods]
impl Increment {
    /// A field by its VTU name (`[output] fields`): `KeyError` naming the
    /// fields there are, or how to keep this one (`run(fields=[name])`).
    fn field(&self, py: Python<'_>, name: &str) -> PyResult<PyObject> {
        let fields = self.fields.bind(py);
        if let Some(values) = fields.get_item(name)? {
            return Ok(values.unbind());
        }
        let message = match name.parse::<OutputField>() {
            Ok(_) => format!(
                "the field '{name}' was not kept: run(fields=['{name}']) keeps it at every increment"
            ),
            Err(unknown) => unknown,
        };
        Err(pyo3::exceptions::PyKeyError::new_err(message))
    }

    fn __repr__(&self) -> String {
        format!(
            "Increment(index={}, step='{}', time={}, iterations={})",
            self.index, self.step_name, self.time, self.iterations
        )
    }
}

/// `values` as a numpy array of `components` per row: (k,) for one,
/// (k, 3, 3) for nine (a tensor, row-major), (k, components) otherwise.
fn field_array(py: Python<'_>, values: Vec<f64>, components: usize) -> PyResult<PyObject> {
    let array = convert::array(py, values, components)?;
    if components == 9 {
        let rows = array.len()?;
        return Ok(array.call_method1("reshape", (rows, 3, 3))?.unbind());
    }
    Ok(array.unbind())
}

impl Increment {
    fn new(py: Python<'_>, data: IncrementData) -> PyResult<Self> {
        let json = py.import("json")?;
        let fields = PyDict::new(py);
        // every nodal field the relay sends, by name
        for (field, values) in data.nodal {
            fields.set_item(field.name(), field_array(py, values, field.components())?)?;
        }
        for (field, values) in data.extra {
            let components = match field {
                OutputField::Nodal(f) => f.components(),
                OutputField::Cell(f) => f.components(),
            };
            fields.set_item(field.name(), field_array(py, values, components)?)?;
        }
        let (cauchy_stress, von_mises) = match data.stresses {
            Some((sigma, vm)) => {
                let sigma = field_array(py, sigma, 9)?;
                let vm = field_array(py, vm, 1)?;
                fields.set_item(CellField::CauchyStress.name(), sigma.clone_ref(py))?;
                fields.set_item(CellField::VonMises.name(), vm.clone_ref(py))?;
                (Some(sigma), Some(vm))
            }
            None => (None, None),
        };
        let nodal = |field: NodalField| -> PyResult<PyObject> {
            match fields.get_item(field.name())? {
                Some(values) => Ok(values.unbind()),
                None => Err(SignoriniError::new_err(format!(
                    "internal error: the nodal field {} is missing from an increment (please report it)",
                    field.name()
                ))),
            }
        };
        let reactions = PyDict::new(py);
        for (name, force) in data.reaction_forces {
            reactions.set_item(name, convert::array(py, force.to_vec(), 1)?)?;
        }
        Ok(Increment {
            index: data.index,
            step: data.step,
            step_name: data.step_name,
            time: data.time,
            increment: data.increment,
            iterations: data.iterations,
            cuts: data.cuts,
            displacement: nodal(NodalField::Displacement)?,
            contact_pressure: nodal(NodalField::ContactPressure)?,
            gap: nodal(NodalField::Gap)?,
            contact_status: nodal(NodalField::ContactStatus)?,
            contact_traction: nodal(NodalField::ContactTraction)?,
            slip: nodal(NodalField::Slip)?,
            slip_increment: nodal(NodalField::SlipIncrement)?,
            reaction_forces: reactions.into_any().unbind(),
            contact: json.call_method1("loads", (data.contact,))?.unbind(),
            cauchy_stress,
            von_mises,
            fields: fields.unbind(),
        })
    }
}

/// On the Python thread: keep the increment, call the callback, answer.
/// `pending` holds an exception to raise after the run (the callback's,
/// Ctrl-C's); once it is set every further increment is answered Stop.
fn deliver(
    py: Python<'_>,
    data: IncrementData,
    increments: &Py<PyList>,
    callback: Option<&PyObject>,
    pending: &mut Option<PyErr>,
) -> Reply {
    let step = |pending: &mut Option<PyErr>| -> PyResult<Reply> {
        let increment = Py::new(py, Increment::new(py, data)?)?;
        increments.bind(py).append(&increment)?;
        if pending.is_some() {
            return Ok(Reply::Stop("stopped from Python".into()));
        }
        py.check_signals()?;
        if let Some(callback) = callback {
            let answer = callback.call1(py, (increment,))?;
            if !answer.is_none(py) && !answer.is_truthy(py)? {
                return Ok(Reply::Stop("the callback returned False".into()));
            }
        }
        Ok(Reply::GoOn)
    };
    match step(pending) {
        Ok(reply) => reply,
        Err(e) => {
            let reason = if e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
                "Ctrl-C (KeyboardInterrupt)".to_string()
            } else {
                format!("the callback raised {e}")
            };
            *pending = Some(e);
            Reply::Stop(reason)
        }
    }
}

/// Runs `simulation` with the GIL released (see the module documentation).
/// Returns the status ("completed", "interrupted" or "failed"), the list of
/// [`Increment`]s, the summary as JSON, and the exception to raise, if
/// any (the run's error, the callback's, Ctrl-C's): not raised here, so
/// that the caller can attach the partial result to it.
pub fn run(
    py: Python<'_>,
    simulation: &mut Simulation,
    options: &RunOptions,
    callback: Option<PyObject>,
    keep: Keep,
) -> PyResult<(String, Py<PyList>, String, Option<PyObject>)> {
    let increments = PyList::empty(py).unbind();
    let list = increments.clone_ref(py);
    // Ctrl-C sets it: the run stops between two Newton iterations
    let cancel = Arc::new(AtomicBool::new(false));
    let options = &RunOptions {
        cancel: Some(Arc::clone(&cancel)),
        ..options.clone()
    };
    let (to_python, from_run) = mpsc::channel();
    let (to_run, from_python) = mpsc::channel();
    let (joined, pending) = py.allow_threads(move || {
        let mut pending: Option<PyErr> = None;
        let joined = std::thread::scope(|s| {
            let worker = s.spawn(move || {
                let mut relay = Relay {
                    to_python,
                    from_python,
                    keep,
                    count: 0,
                    summary: None,
                };
                let result = simulation.run(options, &mut relay);
                (result, relay.summary)
            });
            loop {
                match from_run.recv_timeout(SIGNAL_POLL) {
                    Ok(data) => {
                        let reply = Python::with_gil(|py| {
                            deliver(py, data, &list, callback.as_ref(), &mut pending)
                        });
                        // the run waits for this answer; it cannot be gone
                        let _ = to_run.send(reply);
                    }
                    Err(RecvTimeoutError::Timeout) => {
                        if pending.is_none() {
                            // Ctrl-C during an increment: stop at the next
                            // Newton iteration
                            pending = Python::with_gil(|py| py.check_signals().err());
                            if pending.is_some() {
                                cancel.store(true, Ordering::Relaxed);
                            }
                        }
                    }
                    Err(RecvTimeoutError::Disconnected) => break,
                }
            }
            worker.join()
        });
        (joined, pending)
    });
    let (result, summary) = joined.map_err(|_| {
        SignoriniError::new_err("the solver's thread panicked (a bug: please report it)")
    })?;
    let summary = summary.unwrap_or_else(|| "{}".into());
    let (status, error) = match result {
        Ok(outcome) => (outcome.summary.status, None),
        Err(Error::Interrupted { .. }) => ("interrupted".to_string(), None),
        Err(e) => ("failed".to_string(), Some(to_py(e))),
    };
    let error = pending.or(error).map(|e| e.into_value(py).into_any());
    Ok((status, increments, summary, error))
}
