"""Type stubs of the compiled module signorini._signorini."""

import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, os.PathLike]

class SignoriniError(Exception):
    """Every error of signorini (the message is the solver's)."""

class CaseError(SignoriniError):
    """Input that cannot be used: the case table (with its key path), the
    mesh, a material, a file."""

class MeshError(CaseError):
    """A mesh that cannot be read or used (a file's line, an array's row)."""

class ConvergenceError(SignoriniError):
    """The solve failed: Newton did not converge after the allowed cuts, a
    singular matrix, an element inverted during the run."""

class Case:
    """A case: a mesh with materials, boundary conditions, loads, contacts
    and steps, validated as the command line validates a case file."""

    @staticmethod
    def from_file(path: _Path) -> "Case":
        """Read a case file (TOML) and the mesh it names."""
    @staticmethod
    def from_toml(text: str, base_dir: _Path = ".") -> "Case":
        """A case from the text of a case file; its paths (the mesh, the
        output folder) are relative to ``base_dir``."""
    @staticmethod
    def from_arrays(
        nodes: npt.ArrayLike,
        spec: Union[str, Mapping[str, Any]],
        *,
        tetrahedra: Optional[npt.ArrayLike] = None,
        hexahedra: Optional[npt.ArrayLike] = None,
        regions: Optional[Mapping[str, npt.ArrayLike]] = None,
        surfaces: Optional[Mapping[str, npt.ArrayLike]] = None,
        base_dir: _Path = ".",
        tetrahedra10: Optional[npt.ArrayLike] = None,
        hexahedra20: Optional[npt.ArrayLike] = None,
        wedges: Optional[npt.ArrayLike] = None,
        wedges15: Optional[npt.ArrayLike] = None,
        node_sets: Optional[Mapping[str, npt.ArrayLike]] = None,
    ) -> "Case":
        """A case around a mesh given as arrays.

        ``nodes`` (n, 3); ``tetrahedra`` (m, 4) and/or ``hexahedra`` (m, 8)
        0-based node indices in Gmsh/VTK order (elements are numbered
        tetrahedra first); ``regions`` {name: element indices} (elements in
        none form the region "default"); ``surfaces`` {name: (k, 3) or
        (k, 4) facet node indices, any orientation}; ``node_sets`` {name:
        node indices} (for ``[[displacement]] nodes =`` and
        ``[[nodal_force]] nodes =``); ``spec`` the rest of
        the case file (materials, displacements, pressures, obstacles,
        contacts, steps, output) as TOML text or a dict, without ``[mesh]``.
        Errors are those of a case file (:class:`CaseError` with the key
        path; :class:`MeshError` naming the array's row)."""
    @property
    def path(self) -> str:
        """The case file (``base_dir/case`` for text or arrays)."""
    @property
    def nodes(self) -> npt.NDArray[np.float64]:
        """Reference node coordinates, (n, 3)."""
    @property
    def cells(self) -> List[Tuple[str, npt.NDArray[np.int64]]]:
        """Element blocks in element order: (meshio type, (m, k) indices)."""
    @property
    def region_names(self) -> List[str]: ...
    @property
    def surface_names(self) -> List[str]: ...
    @property
    def node_set_names(self) -> List[str]: ...
    def surface_nodes(self, name: str) -> npt.NDArray[np.int64]:
        """Sorted node indices of a surface set."""

class Increment:
    """One converged increment: time, step, Newton iterations and its
    fields as numpy arrays (node and element order of the case's mesh)."""

    index: int
    step: int
    step_name: str
    time: float
    increment: float
    iterations: int
    cuts: int
    displacement: npt.NDArray[np.float64]
    """(n, 3)"""
    contact_pressure: npt.NDArray[np.float64]
    """(n,), compressive ≥ 0, 0 off contact surfaces"""
    gap: npt.NDArray[np.float64]
    """(n,), open > 0, NaN off contact surfaces"""
    contact_status: npt.NDArray[np.float64]
    """(n,), 0 open, 1 stick, 2 slip"""
    contact_traction: npt.NDArray[np.float64]
    """(n, 3)"""
    slip: npt.NDArray[np.float64]
    """(n, 3), accumulated"""
    slip_increment: npt.NDArray[np.float64]
    """(n, 3), this increment's slip"""
    reaction_forces: Dict[str, npt.NDArray[np.float64]]
    """{surface set: (3,)}"""
    contact: Dict[str, Dict[str, Any]]
    """{interface: totals as in summary.json}"""
    cauchy_stress: Optional[npt.NDArray[np.float64]]
    """(m, 3, 3), with stresses=True"""
    von_mises: Optional[npt.NDArray[np.float64]]
    """(m,), with stresses=True"""
    fields: Dict[str, npt.NDArray[np.float64]]
    """{VTU name: array} of every field kept"""
    def field(self, name: str) -> npt.NDArray[np.float64]:
        """A field by its VTU name; KeyError naming the fields, or how to
        keep this one (run(fields=[name]))."""

class NativeSimulation:
    def __init__(
        self,
        case: Case,
        threads: Optional[int] = None,
        output: Optional[_Path] = None,
        restart: Optional[_Path] = None,
    ) -> None: ...
    def run(
        self,
        callback: Optional[Callable[[Increment], Optional[bool]]] = None,
        stresses: bool = False,
        fields: List[str] = ...,
    ) -> Tuple[str, List[Increment], str, Optional[BaseException]]: ...

def dict_to_toml(spec: Mapping[str, Any]) -> str:
    """A case table (a dict) as the TOML text of a case file."""

def fitted_contact_radius(r: npt.ArrayLike, p: npt.ArrayLike, threshold: float) -> float:
    """Hertz's contact radius from nodal pressures p at distances r from the
    axis: the least-squares fit of p² = p0² (1 − r²/a²) over p > threshold."""
