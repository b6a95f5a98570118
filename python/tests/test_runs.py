"""Runs of the examples: the results equal the command line's VTU files,
a callback stops a run consistently, Hertz's contact radius."""

import math
import os
import signal

import numpy as np
import pytest

import signorini
from conftest import read_vtu_point_field, run_cli


@pytest.fixture(scope="module")
def press_pull(repo):
    case = signorini.Case.from_file(repo / "examples" / "press-pull" / "case.toml")
    return case, signorini.Simulation(case, threads=2).run(stresses=True)


def test_results_equal_the_cli_vtu(repo, cli, tmp_path, press_pull):
    """Every increment, every nodal field and the von Mises stress of
    examples/press-pull (frictional contact) against the CLI's VTU."""
    _, result = press_pull
    run_cli(cli, repo / "examples" / "press-pull" / "case.toml", tmp_path)
    assert result.status == "completed"
    assert len(result.increments) == 6
    for k, inc in enumerate(result.increments):
        vtu = tmp_path / f"press-pull_{k + 1:04d}.vtu"
        for name in signorini.NODAL_FIELDS:
            ours = np.asarray(getattr(inc, name)).ravel()
            theirs = read_vtu_point_field(vtu, name)
            assert theirs is not None, name
            finite = np.isfinite(theirs)
            assert np.array_equal(finite, np.isfinite(ours)), name
            scale = max(np.abs(theirs[finite]).max(), 1e-300)
            assert np.abs(ours[finite] - theirs[finite]).max() <= 1e-12 * scale, (k, name)
        vm = read_vtu_point_field(vtu, "von_mises")  # cell data is read the same way
        assert np.abs(inc.von_mises - vm).max() <= 1e-12 * vm.max()
    # the press of 20 is carried by contact, the pull by friction (0.8 μN)
    assert result.contact["base"]["force"][2] == pytest.approx(20.0, rel=1e-9)
    assert result.contact["base"]["tangential_force"][0] == pytest.approx(-4.8, rel=1e-9)


def test_slip_increments_add_up_to_the_accumulated_slip(press_pull):
    """examples/press-pull: the pull slides the leading end; each
    increment's slip_increment is the accumulated slip now minus before, so
    they sum to the final slip (and accumulated_slip is slip)."""
    _, result = press_pull
    total = sum(inc.slip_increment for inc in result.increments)
    scale = np.abs(result.slip).max()
    assert scale > 0
    assert np.abs(total - result.slip).max() <= 1e-12 * scale
    for before, inc in zip(result.increments, result.increments[1:]):
        np.testing.assert_array_equal(inc.field("accumulated_slip"), inc.slip)
        assert np.abs(inc.slip_increment - (inc.slip - before.slip)).max() <= 1e-12 * scale
    np.testing.assert_array_equal(result.increments[0].slip_increment, result.increments[0].slip)


def test_a_callback_stops_the_run_after_two_increments(press_pull):
    case, full = press_pull
    seen = []

    def stop_after_two(inc):
        seen.append((inc.index, inc.step_name, inc.time, inc.iterations))
        return inc.index < 1

    result = signorini.Simulation(case, threads=2).run(callback=stop_after_two)
    assert result.status == "interrupted"
    assert result.summary["status"] == "interrupted"
    assert len(result.increments) == 2 and len(result.summary["increments"]) == 2
    # the full run's first two increments, as its summary lists them
    expected = [
        (k, i["step_name"], i["time"], i["iterations"])
        for k, i in enumerate(full.summary["increments"][:2])
    ]
    assert [(k, step, t) for k, step, t, _ in expected] == [(0, "press", 0.5), (1, "press", 1.0)]
    assert seen == expected
    # what it kept is the full run's first two increments
    for a, b in zip(result.increments, full.increments[:2]):
        assert a.time == b.time
        assert np.abs(a.displacement - b.displacement).max() <= 1e-12 * np.abs(b.displacement).max()
        assert np.abs(a.contact_pressure - b.contact_pressure).max() <= 1e-12 * b.contact_pressure.max()
    assert result.history("displacement").shape == (2, case.nodes.shape[0], 3)


def test_an_exception_in_the_callback_stops_the_run_and_is_raised(press_pull):
    case, _ = press_pull

    def fail(inc):
        raise ValueError("enough")

    with pytest.raises(ValueError, match="enough") as info:
        signorini.Simulation(case, threads=1).run(callback=fail)
    assert info.value.result.status == "interrupted"
    assert len(info.value.result.increments) == 1


def test_ctrl_c_stops_the_run_after_the_increment_in_progress(press_pull):
    """SIGINT (Ctrl-C) during the run (here in the first increment's
    callback, where Python raises it at once): the run ends after that
    increment, KeyboardInterrupt is raised with the consistent partial
    result. (A SIGINT while the solver works is seen by the waiting main
    thread within 50 ms and ends the run after the increment in progress.)"""
    case, full = press_pull
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    calls = []

    def press_ctrl_c(inc):
        calls.append(inc.index)
        os.kill(os.getpid(), signal.SIGINT)

    try:
        with pytest.raises(KeyboardInterrupt) as info:
            signorini.Simulation(case, threads=1).run(callback=press_ctrl_c)
    finally:
        signal.signal(signal.SIGINT, previous)
    result = info.value.result
    assert calls == [0]
    assert result.status == "interrupted" and result.summary["status"] == "interrupted"
    assert len(result.increments) == 1 and len(result.summary["increments"]) == 1
    assert np.abs(result.displacement - full.increments[0].displacement).max() <= 1e-12


def test_hertz_contact_radius_within_one_percent(repo):
    """examples/hertz (README): a = (3FR/4E*)^(1/3) with the computed force,
    against the least-squares fit of p² = p0²(1 − r²/a²) over the nodes
    with p > 0.2 p0 (the README's method, contact::hertz), p the nominal
    pressure (force over reference area: contact_traction's z component on
    the plane z = 0; contact_pressure, dual mortar's multiplier, is per
    current area and its fit reads 1.5 % short, as contact_radius gives)."""
    E, nu, R = 1000.0, 0.3, 1.0
    case = signorini.Case.from_file(repo / "examples" / "hertz" / "case.toml")
    result = signorini.Simulation(case, threads=2).run()
    force = 4.0 * result.contact["pole"]["force"][2]  # quarter model
    e_star = E / (1.0 - nu**2)
    a = (3.0 * force * R / (4.0 * e_star)) ** (1.0 / 3.0)
    p0 = 3.0 * force / (2.0 * math.pi * a * a)
    last = result.last
    nominal = np.abs(last.contact_traction[:, 2])
    a_fit = signorini.contact_radius(case, last, 0.2 * p0, pressure=nominal)
    assert force == pytest.approx(1.9696, rel=1e-4)  # the README's run
    assert abs(a_fit / a - 1.0) < 0.01, (a_fit, a)
    a_cauchy = signorini.contact_radius(case, last, 0.2 * p0)
    assert abs(a_cauchy / a - 1.0) < 0.02, (a_cauchy, a)
