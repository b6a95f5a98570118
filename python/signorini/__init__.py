"""signorini: nonlinear 3D contact mechanics (finite elements, in Rust), from Python.

A case (a case file, its TOML text, or a mesh given as numpy arrays with
the case table as a dict) runs in a :class:`Simulation`; the results come
back as numpy arrays, increment by increment::

    import signorini

    case = signorini.Case.from_file("examples/hertz/case.toml")
    result = signorini.Simulation(case, threads=2).run()
    result.displacement          # (n, 3), the last increment
    result.contact_pressure      # (n,)
    result.reaction_forces["top"]

The solver is the command line's (``signorini run``): the same case gives
the same numbers, and its errors are raised as :class:`CaseError`,
:class:`MeshError` or :class:`ConvergenceError` with the same messages.
"""

from __future__ import annotations

import json
import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Union

import numpy as np

from ._signorini import (
    Case,
    CaseError,
    ConvergenceError,
    Increment,
    MeshError,
    NativeSimulation as _NativeSimulation,
    SignoriniError,
    dict_to_toml,
    fitted_contact_radius,
)

__all__ = [
    "Case",
    "CaseError",
    "ConvergenceError",
    "Increment",
    "MeshError",
    "Result",
    "SignoriniError",
    "Simulation",
    "contact_radius",
    "dict_to_toml",
    "fitted_contact_radius",
]

#: The nodal fields of every :class:`Increment` (the VTU point-data names).
NODAL_FIELDS = (
    "displacement",
    "contact_pressure",
    "gap",
    "contact_status",
    "contact_traction",
    "slip",
    "slip_increment",
)


class Simulation:
    """A case ready to run.

    ``threads``: worker threads of assembly and factorisation (None: one
    per core). ``output``: a folder for the command line's result files
    (VTU, PVD, ``summary.json``, plots); None writes nothing, the results
    stay in memory. ``restart``: the output folder of an earlier run of
    this case (interrupted, say) to resume from its checkpoint
    (``NAME.checkpoint``) rather than from t = 0, as ``signorini run
    --restart DIR``: the run goes on to the state an uninterrupted run
    reaches, and ``output`` must be that folder or None (then the results
    go on in it).
    """

    def __init__(
        self,
        case: Case,
        threads: Optional[int] = None,
        output: Optional[Union[str, os.PathLike]] = None,
        restart: Optional[Union[str, os.PathLike]] = None,
    ) -> None:
        self.case = case
        self._native = _NativeSimulation(case, threads, output, restart)

    def run(
        self,
        callback: Optional[Callable[[Increment], Optional[bool]]] = None,
        stresses: bool = False,
        fields: Sequence[str] = (),
    ) -> "Result":
        """Run every step of the case and return its :class:`Result`.

        ``callback(increment)`` is called with each converged
        :class:`Increment`; returning ``False`` stops the run after it
        (``result.status == "interrupted"``, the increments so far kept).
        The GIL is released while the solver works; Ctrl-C stops the run
        at its next Newton iteration and raises ``KeyboardInterrupt``.
        An exception from the callback stops the run and is raised.
        ``stresses=True`` keeps the element stresses of every increment.
        ``fields`` names other fields to keep at every increment, as
        ``[output] fields`` does (e.g. ``"recovered_von_mises"``,
        ``"principal_stress"``, ``"logarithmic_strain"``); each is then
        :meth:`Increment.field`.

        A failed run raises :class:`ConvergenceError` (or another
        :class:`SignoriniError`); every exception raised here carries the
        partial result as its ``result`` attribute.
        """
        status, increments, summary, error = self._native.run(callback, stresses, list(fields))
        result = Result(self.case, status, list(increments), json.loads(summary))
        if error is not None:
            try:
                error.result = result
            except AttributeError:
                pass
            raise error
        return result


class Result:
    """What a run leaves: every converged increment and the run's summary.

    The field attributes (``displacement``, ``contact_pressure``, ``gap``,
    ``contact_status``, ``contact_traction``, ``slip``, ``reaction_forces``,
    ``contact``) are those of the last increment; :meth:`history` stacks a
    field over all increments.
    """

    def __init__(
        self,
        case: Case,
        status: str,
        increments: List[Increment],
        summary: Dict[str, Any],
    ) -> None:
        self.case = case
        #: "completed", "interrupted" (the callback or Ctrl-C) or "failed".
        self.status = status
        #: Every converged increment, in order.
        self.increments = increments
        #: The run's summary, as the command line's ``summary.json``.
        self.summary = summary

    def __repr__(self) -> str:
        return f"Result(status={self.status!r}, increments={len(self.increments)})"

    def __len__(self) -> int:
        return len(self.increments)

    @property
    def last(self) -> Increment:
        """The last converged increment."""
        if not self.increments:
            raise SignoriniError("the run has no converged increment")
        return self.increments[-1]

    @property
    def times(self) -> np.ndarray:
        """The time of every increment."""
        return np.array([i.time for i in self.increments])

    def history(self, field: str) -> np.ndarray:
        """A field kept at every increment (see :meth:`Increment.field`:
        the nodal ones of ``NODAL_FIELDS`` and more, ``von_mises`` /
        ``cauchy_stress`` with stresses=True, those of ``run(fields=...)``)
        over the increments: shape (increments, ...)."""
        return np.stack([i.field(field) for i in self.increments])

    def field(self, name: str) -> np.ndarray:
        """A field of the last increment by its VTU name (see
        :meth:`Increment.field`)."""
        return self.last.field(name)

    def reaction_history(self, surface: str) -> np.ndarray:
        """The reaction force on a surface set at every increment, (k, 3)."""
        return np.stack([i.reaction_forces[surface] for i in self.increments])

    def contact_history(self, interface: str, key: str = "force") -> np.ndarray:
        """A per-interface total (``force``, ``active_nodes``, …, as in
        ``summary.json``) at every increment."""
        return np.array([i.contact[interface][key] for i in self.increments])

    @property
    def displacement(self) -> np.ndarray:
        """Displacement of the last increment, (n, 3)."""
        return self.last.displacement

    @property
    def contact_pressure(self) -> np.ndarray:
        """Contact pressure of the last increment, (n,)."""
        return self.last.contact_pressure

    @property
    def gap(self) -> np.ndarray:
        """Signed gap of the last increment, (n,) (NaN off contact surfaces)."""
        return self.last.gap

    @property
    def contact_status(self) -> np.ndarray:
        """Contact status of the last increment (0 open, 1 stick, 2 slip), (n,)."""
        return self.last.contact_status

    @property
    def contact_traction(self) -> np.ndarray:
        """Contact traction of the last increment, (n, 3)."""
        return self.last.contact_traction

    @property
    def slip(self) -> np.ndarray:
        """Accumulated slip of the last increment, (n, 3)."""
        return self.last.slip

    @property
    def slip_increment(self) -> np.ndarray:
        """The last increment's slip (accumulated slip now minus before), (n, 3)."""
        return self.last.slip_increment

    @property
    def reaction_forces(self) -> Dict[str, np.ndarray]:
        """Reaction force per surface set at the last increment."""
        return self.last.reaction_forces

    @property
    def contact(self) -> Dict[str, Dict[str, Any]]:
        """Per-interface totals at the last increment (as in summary.json)."""
        return self.last.contact

    @property
    def von_mises(self) -> Optional[np.ndarray]:
        """Von Mises stress per element at the last increment (with stresses=True)."""
        return self.last.von_mises

    @property
    def cauchy_stress(self) -> Optional[np.ndarray]:
        """Cauchy stress per element at the last increment, (m, 3, 3) (with stresses=True)."""
        return self.last.cauchy_stress

    def to_meshio(self, increment: int = -1):
        """The mesh with the fields of one increment (default: the last) as
        a ``meshio.Mesh`` (point data named as in the VTU files)."""
        import meshio

        inc = self.increments[increment]
        point_data = {f: np.asarray(getattr(inc, f)) for f in NODAL_FIELDS}
        cell_data = {}
        cells = self.case.cells
        if inc.von_mises is not None:
            blocks = np.cumsum([0] + [len(c) for _, c in cells])
            sigma = inc.cauchy_stress.reshape(-1, 9)
            cell_data["cauchy_stress"] = [sigma[a:b] for a, b in zip(blocks, blocks[1:])]
            cell_data["von_mises"] = [inc.von_mises[a:b] for a, b in zip(blocks, blocks[1:])]
        return meshio.Mesh(
            self.case.nodes, cells, point_data=point_data, cell_data=cell_data
        )

    def to_pyvista(self, increment: int = -1):
        """The mesh with the fields of one increment as a
        ``pyvista.UnstructuredGrid``."""
        import pyvista

        return pyvista.from_meshio(self.to_meshio(increment))


def contact_radius(case: Case, increment: Increment, threshold: float, pressure=None) -> float:
    """The radius of a contact patch about the z axis (Hertz's a): the fit
    of ``p² = p0² (1 − r²/a²)`` over the secondary nodes (finite gap) with
    ``p > threshold``, r their distance from the axis in the deformed state
    (:func:`fitted_contact_radius`; examples/hertz/README.md), p the nodal
    ``pressure`` (an array over all nodes), by default the
    ``contact_pressure`` (with dual mortar, the default, the force over the
    node's current area: on examples/hertz the fit reads 1.5 % short of
    Hertz's a; the force over the reference area, which Hertz's small-strain
    theory compares with, is ``contact_traction``'s normal component, on a
    plane ``z = 0`` its ``[:, 2]``, and reads 1.0 % short)."""
    secondary = np.isfinite(increment.gap)
    x = case.nodes + increment.displacement
    r = np.hypot(x[:, 0], x[:, 1])[secondary]
    p = increment.contact_pressure if pressure is None else np.asarray(pressure)
    return fitted_contact_radius(r, p[secondary], threshold)
