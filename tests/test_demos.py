"""Every demo is also a test: each runs in its fast mode (``--quick``).

The test is marked ``mpi``, so the test command runs it serially and again on
2 ranks (the demo is executed in-process by every rank, as under
``mpiexec -n 2 python demo.py``).  A demo ends with its own checks against
references (asserts) and prints "all checks passed"; it fails here when it
raises.  The list is every ``demos/demo_*.py``, the main demo (``demo_tour.py``)
included; a demo without a ``--quick`` mode fails.
"""

import runpy
import sys
from pathlib import Path

import pytest
from mpi4py import MPI

DEMOS = sorted((Path(__file__).parents[1] / "demos").glob("demo_*.py"))


def test_every_demo_has_a_quick_mode():
    assert "demo_tour" in [p.stem for p in DEMOS]
    missing = [p.name for p in DEMOS if '"--quick"' not in p.read_text()]
    assert not missing, f"demos without --quick: {missing}"


@pytest.mark.mpi
@pytest.mark.parametrize("demo", DEMOS, ids=lambda p: p.stem)
def test_demo(demo, tmp_path, monkeypatch, capsys):
    out = MPI.COMM_WORLD.bcast(str(tmp_path / "out"), root=0)
    monkeypatch.setattr(sys, "argv", [str(demo), "--quick", "--out", out])
    monkeypatch.chdir(tmp_path)
    runpy.run_path(str(demo), run_name="__main__")
    if MPI.COMM_WORLD.rank == 0:
        assert "all checks passed" in capsys.readouterr().out
