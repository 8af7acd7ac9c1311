"""Every demo is also a test: each runs in its fast mode (``--quick``).

A demo ends with its own checks against references (asserts) and prints "all
checks passed"; it fails here when it raises.  The list is every
``demos/demo_*.py``, the main demo (``demo_tour.py``) included; a demo without a
``--quick`` mode fails.

The test is marked ``mpi``: the test command runs every demo serially, and on 2
ranks (the demo executed in-process by every rank, as under ``mpiexec -n 2
python demo.py``) every demo whose physics no other test runs on 2 ranks.  A demo
whose physics other tests run on 2 ranks is named in ``PARALLEL_TESTED`` with
those tests (checked to exist): all but the O-ring cycle's compare 2 ranks with
one; the cycle's checks its oil balance on 2 ranks from the same start and steps
as the demo.  The main demo is four cases run through the runner, each of which
its own test runs on 2 ranks through the same runner (``tribofx run`` under
mpiexec).  Their runs on 2 ranks would repeat those tests at the cost of the
whole demo.  A demo named in ``SLOW`` runs in the slow set only.
"""

import runpy
import sys
from pathlib import Path

import pytest
from mpi4py import MPI

DEMOS = sorted((Path(__file__).parents[1] / "demos").glob("demo_*.py"))

#: demo → the test (file::function), or tests, that run its physics on 2 ranks
PARALLEL_TESTED = {
    "demo_tour": ("test_ehl_ball.py::test_serial_equals_two_processes",
                  "test_ehl_oring.py::test_parallel_matches_serial",
                  "test_wear_groove.py::test_two_ranks_match_serial",
                  "test_parallel.py::test_two_body_serial_equals_two_processes"),
    "demo_oring_cycle":
        "test_oring_cycle.py::test_film_content_changes_by_the_net_flux_of_each_step",
    "demo_mixed_lubrication": "test_wear_lubricated.py::test_running_in_parallel_matches_serial",
    "demo_ehl_oring": "test_ehl_oring.py::test_parallel_matches_serial",
    "demo_ehl_cylinder_layer": "test_ehl.py::test_serial_equals_two_processes",
    "demo_ehl_two_cylinders": "test_ehl_two_cylinders.py::test_parallel_matches_serial",
    "demo_ehl_ball": "test_ehl_ball.py::test_serial_equals_two_processes",
    "demo_ehl_squeeze": "test_squeeze.py::test_parallel_matches_serial",
    "demo_reynolds_cylinder": "test_reynolds.py::test_serial_and_parallel_agree",
    "demo_reynolds_slider": "test_reynolds.py::test_serial_and_parallel_agree",
    "demo_wear_ball_flat": "test_wear_ball.py::test_serial_and_two_processes_agree",
    "demo_wear_pin": "test_wear.py::test_serial_parallel_agree",
    "demo_wear_ball_halfspace": "test_wear_groove.py::test_two_ranks_match_serial",
    "demo_hertz": "test_parallel.py::test_serial_equals_two_processes",
    "demo_two_cylinders": "test_parallel.py::test_two_body_serial_equals_two_processes",
    "demo_wear_reciprocating": "test_parallel.py::test_two_body_serial_equals_two_processes",
    "demo_wear_two_body": "test_parallel.py::test_two_body_serial_equals_two_processes",
}


def test_every_demo_has_a_quick_mode():
    assert "demo_tour" in [p.stem for p in DEMOS]
    missing = [p.name for p in DEMOS if '"--quick"' not in p.read_text()]
    assert not missing, f"demos without --quick: {missing}"


def test_the_parallel_tests_named_for_demos_exist():
    here = Path(__file__).parent
    stems = {p.stem for p in DEMOS}
    for demo, tests in PARALLEL_TESTED.items():
        assert demo in stems, demo
        for test in (tests,) if isinstance(tests, str) else tests:
            path, name = test.split("::")
            assert f"def {name}(" in (here / path).read_text(), test


#: demos whose quick mode takes minutes: in the slow set (serially and on 2 ranks)
SLOW = {"demo_soft_on_soft": "two 3D two-body films, each marched in speed: about 4 min"}


@pytest.mark.mpi
@pytest.mark.parametrize("demo", [pytest.param(p, marks=pytest.mark.slow) if p.stem in SLOW
                                  else p for p in DEMOS], ids=lambda p: p.stem)
def test_demo(demo, tmp_path, monkeypatch, capsys):
    if MPI.COMM_WORLD.size > 1 and demo.stem in PARALLEL_TESTED:
        pytest.skip(f"on 2 ranks by {PARALLEL_TESTED[demo.stem]}")
    out = MPI.COMM_WORLD.bcast(str(tmp_path / "out"), root=0)
    monkeypatch.setattr(sys, "argv", [str(demo), "--quick", "--out", out])
    monkeypatch.chdir(tmp_path)
    runpy.run_path(str(demo), run_name="__main__")
    if MPI.COMM_WORLD.rank == 0:
        assert "all checks passed" in capsys.readouterr().out
