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
use pyo3::types::PyList;
use signorini::output::{CellField, ConvergedIncrement, NodalField, StepObserver, Summary};
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
    /// Every nodal field by name: its values, `components()` per node.
    nodal: std::collections::HashMap<NodalField, Vec<f64>>,
    reaction_forces: Vec<(String, [f64; 3])>,
    /// The per-interface totals, as in `summary.json`.
    contact: String,
    /// Cauchy stress (9 per element) and von Mises, if asked for.
    stresses: Option<(Vec<f64>, Vec<f64>)>,
}

impl IncrementData {
    fn new(inc: &ConvergedIncrement, index: usize, stresses: bool) -> Self {
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
    stresses: bool,
    count: usize,
    summary: Option<String>,
}

impl StepObserver for Relay {
    fn on_increment(&mut self, inc: &ConvergedIncrement, _: &Summary) -> signorini::Result<()> {
        self.count += 1;
        let data = IncrementData::new(inc, self.count - 1, self.stresses);
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
    /// {surface set: (3,) total of the residual over its nodes}: the
    /// reaction force where displacements are prescribed.
    reaction_forces: PyObject,
    /// {interface: totals as in summary.json (force, active nodes, ...)}.
    contact: PyObject,
    /// Element-averaged Cauchy stress (m, 3, 3) and von Mises (m,), when
    /// the run was asked for stresses; else None.
    cauchy_stress: Option<PyObject>,
    von_mises: Option<PyObject>,
}

#[pymethods]
impl Increment {
    fn __repr__(&self) -> String {
        format!(
            "Increment(index={}, step='{}', time={}, iterations={})",
            self.index, self.step_name, self.time, self.iterations
        )
    }
}

impl Increment {
    fn new(py: Python<'_>, data: IncrementData) -> PyResult<Self> {
        let json = py.import("json")?;
        let mut nodal = data.nodal;
        // the relay sends every nodal field, taken here by name
        let mut next = |field: NodalField| -> PyResult<PyObject> {
            match nodal.remove(&field) {
                Some(values) => Ok(convert::array(py, values, field.components())?.unbind()),
                None => Err(SignoriniError::new_err(format!(
                    "internal error: the nodal field {} is missing from an increment (please report it)",
                    field.name()
                ))),
            }
        };
        let displacement = next(NodalField::Displacement)?;
        let contact_pressure = next(NodalField::ContactPressure)?;
        let gap = next(NodalField::Gap)?;
        let contact_status = next(NodalField::ContactStatus)?;
        let contact_traction = next(NodalField::ContactTraction)?;
        let slip = next(NodalField::Slip)?;
        let reactions = pyo3::types::PyDict::new(py);
        for (name, force) in data.reaction_forces {
            reactions.set_item(name, convert::array(py, force.to_vec(), 1)?)?;
        }
        let (cauchy_stress, von_mises) = match data.stresses {
            Some((sigma, vm)) => {
                let m = vm.len();
                let sigma = convert::array(py, sigma, 9)?.call_method1("reshape", (m, 3, 3))?;
                (
                    Some(sigma.unbind()),
                    Some(convert::array(py, vm, 1)?.unbind()),
                )
            }
            None => (None, None),
        };
        Ok(Increment {
            index: data.index,
            step: data.step,
            step_name: data.step_name,
            time: data.time,
            increment: data.increment,
            iterations: data.iterations,
            cuts: data.cuts,
            displacement,
            contact_pressure,
            gap,
            contact_status,
            contact_traction,
            slip,
            reaction_forces: reactions.into_any().unbind(),
            contact: json.call_method1("loads", (data.contact,))?.unbind(),
            cauchy_stress,
            von_mises,
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
    stresses: bool,
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
                    stresses,
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
