"""A cube built in Python from numpy arrays against the command line on
the same mesh written as a .msh file; and the errors of bad input."""

import numpy as np
import pytest

import signorini
from conftest import hex_cube, read_vtu_point_field, run_cli, write_msh22

# the case table of a cube held at its bottom, pressed on top (5 on 1 × 1),
# neo-Hookean, in two increments
SPEC = {
    "material": [
        {"region": "body", "model": "neo_hookean", "youngs_modulus": 100.0, "poisson_ratio": 0.3}
    ],
    "displacement": [{"surface": "bottom", "x": 0.0, "y": 0.0, "z": 0.0}],
    "pressure": [{"surface": "top", "value": 5.0}],
    "step": [{"name": "load", "end_time": 1.0, "initial_increment": 0.5, "max_increment": 0.5}],
    "output": {"name": "cube"},
}


def cube_case(spec=SPEC):
    nodes, hexes, surfaces = hex_cube()
    return signorini.Case.from_arrays(
        nodes, spec, hexahedra=hexes, regions={"body": np.arange(len(hexes))}, surfaces=surfaces
    )


def test_cube_from_arrays_gives_the_cli_result(cli, tmp_path):
    nodes, hexes, surfaces = hex_cube()
    write_msh22(tmp_path / "cube.msh", nodes, hexes, {"body": range(len(hexes))}, surfaces)
    text = '[mesh]\nfile = "cube.msh"\n\n' + signorini.dict_to_toml(SPEC)
    (tmp_path / "case.toml").write_text(text)
    run_cli(cli, tmp_path / "case.toml", tmp_path / "out")

    result = signorini.Simulation(cube_case(), threads=2).run()
    assert result.status == "completed"
    assert [i.time for i in result.increments] == [0.5, 1.0]
    for k, inc in enumerate(result.increments):
        vtu = tmp_path / "out" / f"cube_{k + 1:04d}.vtu"
        u_cli = read_vtu_point_field(vtu, "displacement").reshape(-1, 3)
        scale = np.abs(u_cli).max()
        assert np.abs(inc.displacement - u_cli).max() <= 1e-12 * scale
    # compressed by about p/E: the top sinks by 0.04–0.05
    top = result.case.surface_nodes("top")
    assert -0.06 < result.displacement[top, 2].mean() < -0.03
    # the bottom carries the press of 5: r = f_int - f_ext there is +5 e_z
    assert np.allclose(result.reaction_forces["bottom"], [0.0, 0.0, 5.0], atol=1e-8)


def test_a_bad_case_table_raises_case_error_with_the_key_path():
    spec = dict(SPEC, material=[dict(SPEC["material"][0], youngs_modulus="stiff")])
    with pytest.raises(signorini.CaseError, match=r"at key 'material\[0\]\.youngs_modulus'"):
        cube_case(spec)
    spec = dict(SPEC, pressure=[{"surface": "lid", "value": 5.0}])
    with pytest.raises(
        signorini.CaseError,
        match=r"pressure\[0\]\.surface: the mesh has no surface set .* named 'lid'; it has: bottom, top",
    ):
        signorini.Simulation(cube_case(spec))
    spec = dict(SPEC, material=[dict(SPEC["material"][0], poisson_ratio=0.5)])
    with pytest.raises(signorini.CaseError, match=r"material\[0\]"):
        signorini.Simulation(cube_case(spec))
    with pytest.raises(signorini.CaseError, match=r"line 5: at key 'step\[0\]\.end_time'"):
        signorini.Case.from_toml('[mesh]\nfile = "x.msh"\n[[step]]\nname = "a"\nend_time = "one"\n')


def test_bad_arrays_raise_mesh_error_naming_the_row():
    nodes, hexes, surfaces = hex_cube()
    bad = hexes.copy()
    bad[4, 2] = 1000
    with pytest.raises(signorini.MeshError, match=r"element 4 refers to node 1000, but the mesh has 64 nodes"):
        signorini.Case.from_arrays(nodes, SPEC, hexahedra=bad, surfaces=surfaces)
    with pytest.raises(signorini.MeshError, match=r"needs shape \(m, 8\)"):
        signorini.Case.from_arrays(nodes, SPEC, hexahedra=hexes[:, :4], surfaces=surfaces)
    # an inverted element: top and bottom swapped
    bad = hexes.copy()
    bad[0] = np.roll(bad[0], 4)
    case = signorini.Case.from_arrays(nodes, SPEC, hexahedra=bad, regions={"body": range(27)}, surfaces=surfaces)
    with pytest.raises(signorini.CaseError, match=r"element 0 \(mesh id\) is inverted"):
        signorini.Simulation(case)
    assert issubclass(signorini.MeshError, signorini.CaseError)
