"""The Python snippets of README.md and docs/python.md run as they are
(from the repository's root, as the README says), and the README's prints
the Hertz example's numbers (examples/hertz/README.md)."""

import re

import pytest


def python_blocks(path):
    return re.findall(r"```python\n(.*?)```", path.read_text(encoding="utf-8"), re.S)


def test_the_readme_snippet_prints_the_hertz_force_and_peak_pressure(repo, monkeypatch, capsys):
    blocks = python_blocks(repo / "README.md")
    assert len(blocks) == 1
    monkeypatch.chdir(repo)
    exec(compile(blocks[0], "README.md", "exec"), {})
    force, peak = map(float, capsys.readouterr().out.split())
    # examples/hertz/README.md: total force 1.9696, peak contact_pressure
    # (dual mortar's multiplier, per current area) 81.85
    assert force == pytest.approx(1.9696, rel=1e-4)
    assert peak == pytest.approx(81.85, rel=1e-3)


def test_the_python_guide_snippet_runs(repo, monkeypatch, capsys):
    pytest.importorskip("meshio")
    blocks = python_blocks(repo / "docs" / "python.md")
    assert len(blocks) == 1
    monkeypatch.chdir(repo)
    scope = {}
    exec(compile(blocks[0], "docs/python.md", "exec"), scope)
    assert scope["result"].status == "completed"
    assert scope["F"] == pytest.approx(1.9696, rel=1e-4)
    # one line per increment from the callback, then the figures
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == len(scope["result"].increments) + 1
    assert len(scope["mesh"].points) == len(scope["case"].nodes)
