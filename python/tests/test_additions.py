"""Node sets in Case.from_arrays, any field by name (Increment.field,
run(fields=...)), and a restart from an interrupted run's checkpoint."""

import numpy as np
import pytest

import signorini
from conftest import hex_cube

MATERIAL = [{"region": "body", "model": "linear_elastic", "youngs_modulus": 100.0, "poisson_ratio": 0.3}]
HELD = {"surface": "bottom", "x": 0.0, "y": 0.0, "z": 0.0}


def cube(spec, node_sets=None):
    nodes, hexes, surfaces = hex_cube()
    return signorini.Case.from_arrays(
        nodes, spec, hexahedra=hexes, regions={"body": np.arange(len(hexes))},
        surfaces=surfaces, node_sets=node_sets,
    )


def one_step(**more):
    spec = {"material": MATERIAL, "step": [{"name": "load", "end_time": 1.0}], "output": {"name": "cube"}}
    spec.update(more)
    return spec


def test_a_node_set_holds_its_nodes_as_the_surface_of_the_same_nodes_does():
    _, _, surfaces = hex_cube()
    top = np.unique(surfaces["top"])
    by_surface = one_step(displacement=[HELD, {"surface": "top", "z": -0.05}])
    by_nodes = one_step(displacement=[HELD, {"nodes": "top_nodes", "z": -0.05}])
    a = signorini.Simulation(cube(by_surface), threads=1).run()
    case = cube(by_nodes, node_sets={"top_nodes": top})
    assert case.node_set_names == ["top_nodes"]
    b = signorini.Simulation(case, threads=1).run()
    # the same constraints on the same unknowns: the same answer
    np.testing.assert_array_equal(b.displacement, a.displacement)
    assert np.all(b.displacement[top, 2] == -0.05)


def test_a_nodal_force_on_a_node_set_is_carried_by_the_support():
    # 2 down on the corner (1, 1, 1): the bottom's reaction is 2 up
    nodes, _, _ = hex_cube()
    corner = int(np.argmin(np.linalg.norm(nodes - [1.0, 1.0, 1.0], axis=1)))
    spec = one_step(displacement=[HELD], nodal_force=[{"nodes": "corner", "value": [0.0, 0.0, -2.0]}])
    result = signorini.Simulation(cube(spec, node_sets={"corner": [corner]}), threads=1).run()
    reaction = result.reaction_forces["bottom"]
    assert reaction[2] == pytest.approx(2.0, rel=1e-9)
    assert abs(reaction[0]) < 1e-9 and abs(reaction[1]) < 1e-9
    assert result.displacement[corner, 2] < 0


def test_bad_node_sets_name_the_set_and_the_node():
    with pytest.raises(signorini.MeshError, match="node set 'tip' refers to node 999, but the mesh has 64 nodes"):
        cube(one_step(displacement=[HELD]), node_sets={"tip": [999]})
    with pytest.raises(signorini.MeshError, match="node set 'tip' is empty"):
        cube(one_step(displacement=[HELD]), node_sets={"tip": []})


RECOVERED = ["recovered_cauchy_stress", "recovered_principal_stress", "recovered_von_mises"]


def von_mises(sigma):
    s = sigma - np.trace(sigma, axis1=-2, axis2=-1)[..., None, None] * np.eye(3) / 3.0
    return np.sqrt(1.5 * np.sum(s * s, axis=(-2, -1)))


@pytest.fixture(scope="module")
def pressed():
    """The cube pressed on top (neo-Hookean, two increments), every field kept."""
    spec = {
        "material": [dict(MATERIAL[0], model="neo_hookean")],
        "displacement": [HELD],
        "pressure": [{"surface": "top", "value": 5.0}],
        "step": [{"name": "load", "end_time": 1.0, "initial_increment": 0.5, "max_increment": 0.5}],
        "output": {"name": "cube"},
    }
    fields = RECOVERED + ["principal_stress", "green_lagrange_strain", "region"]
    return spec, signorini.Simulation(cube(spec), threads=1).run(stresses=True, fields=fields)


def test_any_field_by_name_and_the_principal_stresses_are_the_eigenvalues(pressed):
    _, result = pressed
    assert len(result) == 2
    n, m = 64, 27
    for inc in result.increments:
        sigma = inc.field("cauchy_stress")
        assert sigma.shape == (m, 3, 3)
        np.testing.assert_array_equal(sigma, inc.cauchy_stress)
        scale = np.abs(sigma).max()
        # σ₁ ≥ σ₂ ≥ σ₃: the eigenvalues of the averaged Cauchy stress
        principal = inc.field("principal_stress")
        assert principal.shape == (m, 3)
        eigen = np.linalg.eigvalsh(sigma)[:, ::-1]
        assert np.abs(principal - eigen).max() <= 1e-12 * scale
        np.testing.assert_allclose(inc.field("von_mises"), von_mises(sigma), rtol=1e-12, atol=1e-12 * scale)
        nodal = inc.field("recovered_cauchy_stress")
        assert nodal.shape == (n, 3, 3)
        eigen = np.linalg.eigvalsh(0.5 * (nodal + nodal.transpose(0, 2, 1)))[:, ::-1]
        assert np.abs(inc.field("recovered_principal_stress") - eigen).max() <= 1e-12 * scale
        vm = inc.field("recovered_von_mises")
        assert vm.shape == (n,)
        assert np.abs(vm - von_mises(nodal)).max() <= 1e-12 * scale
        strain = inc.field("green_lagrange_strain")
        np.testing.assert_allclose(strain, strain.transpose(0, 2, 1), atol=1e-14)
        np.testing.assert_array_equal(inc.field("region"), np.zeros(m))
        np.testing.assert_array_equal(inc.field("slip_increment"), inc.slip_increment)
    # pressed down: the top moves down, the strain's zz is negative
    assert result.field("displacement")[:, 2].min() < 0
    assert result.field("green_lagrange_strain")[:, 2, 2].max() < 0
    assert result.history("recovered_von_mises").shape == (2, n)


def test_a_field_not_kept_or_misspelt_is_a_key_error_saying_what_to_do(pressed):
    _, result = pressed
    with pytest.raises(KeyError, match=r"run\(fields=\['logarithmic_strain'\]\)"):
        result.field("logarithmic_strain")
    with pytest.raises(KeyError, match="did you mean"):
        result.field("von_misses")
    with pytest.raises(signorini.CaseError, match="unknown output field 'stress'"):
        signorini.Simulation(result.case).run(fields=["stress"])


def test_a_restart_from_an_interrupted_run_reaches_the_uninterrupted_state(pressed, tmp_path):
    spec, full = pressed
    folder = tmp_path / "run"
    case = cube(spec)
    first = signorini.Simulation(case, threads=1, output=folder).run(callback=lambda inc: False)
    assert first.status == "interrupted" and len(first) == 1
    assert (folder / "cube.checkpoint").is_file()
    resumed = signorini.Simulation(case, threads=1, output=folder, restart=folder).run()
    assert resumed.status == "completed"
    # the second increment only, from the first's checkpoint
    assert [inc.time for inc in resumed.increments] == [1.0]
    # bit for bit, as tests/restart.rs shows for the command line
    np.testing.assert_array_equal(resumed.displacement, full.displacement)
