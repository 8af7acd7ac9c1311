"""A run whose Newton iteration fails for good keeps and writes its last converged state."""

import json

import pytest

import tribofx.runner as runner
from tribofx.problem import NewtonDivergence, Problem
from tribofx.runner import run_case


def test_failed_run_keeps_last_converged_state(tmp_path, monkeypatch):
    original = Problem.solve
    state = {"solves": 0, "limit": None}

    def solve(self, verbose=False):
        state["solves"] += 1
        if state["limit"] is not None and state["solves"] > state["limit"]:
            raise NewtonDivergence("injected failure")
        return original(self, verbose)

    class FirstStepOnly:
        """Progress bar stand-in: once step 1 is done, every later solve fails."""

        def update(self, n):
            if state["limit"] is None:
                state["limit"] = state["solves"]

        def close(self):
            pass

    monkeypatch.setattr(Problem, "solve", solve)
    monkeypatch.setattr(runner, "_progress_bar", lambda total, name: FirstStepOnly())
    out = tmp_path / "run"
    summary = run_case("hertz", {"mesh": "0", "load": "0.05", "steps": "3"}, out)
    assert summary["status"].startswith("failed")
    assert len(summary["newton_iterations"]) == 1  # one converged load step
    # what is reported and written is step 1: a third of the load (secant tolerance 1e-6)
    load = summary["results"]["normal_load_full_body"]["value"]
    assert load == pytest.approx(0.05 / 3, rel=1e-5)
    assert json.loads((out / "summary.json").read_text())["status"] == summary["status"]
    assert (out / "displacement.bp").is_dir() and (out / "pressure.png").is_file()


def test_secant_give_up_restores_obstacle_position(tmp_path, monkeypatch):
    # the second load step is given only 2 secant trials: its Newton solves converge
    # but the load is not reached, so the step fails; the reported state (computed
    # with the obstacle position) must be that of step 1
    from tribofx.continuation import Continuation

    original = Continuation.reach
    calls = {"n": 0}

    def reach(self, target, guess=None):
        calls["n"] += 1
        self.max_trials = 25 if calls["n"] == 1 else 2
        return original(self, target, guess)

    monkeypatch.setattr(Continuation, "reach", reach)
    summary = run_case("hertz", {"mesh": "0", "load": "0.05", "steps": "3"}, tmp_path / "r",
                       progress=False)
    assert summary["status"].startswith("failed")
    assert len(summary["newton_iterations"]) == 1
    # force recomputed from the restored multipliers and obstacle position (secant
    # tolerance 1e-6): a stale obstacle position would change it at first order
    load = summary["results"]["normal_load_full_body"]["value"]
    assert load == pytest.approx(0.05 / 3, rel=1e-5)


def test_solver_error_becomes_newton_divergence():
    # an error raised inside a PETSc callback (as a failed MUMPS factorisation is)
    # must reach the controllers as NewtonDivergence, with the unknowns restored,
    # so that they can cut the step
    import numpy as np
    import ufl
    from dolfinx import mesh
    from mpi4py import MPI

    from tribofx.body import Body

    m = mesh.create_unit_square(MPI.COMM_WORLD, 4, 4)
    f = mesh.locate_entities_boundary(m, 1, lambda x: np.isclose(x[1], 0))
    ft = mesh.meshtags(m, 1, f, np.ones(len(f), dtype=np.int32))
    body = Body(m, ft, {"bottom": 1}, "plane_strain", ("neo-hookean", {"mu": 1.0, "lmbda": 1.0}))
    body.add_dirichlet("bottom", np.zeros(2))
    body.add_body_force(ufl.as_vector([0.0, -0.01]))
    calls = {"n": 0}

    def refresh():
        calls["n"] += 1
        if calls["n"] == 2:  # fail at the first Newton trial, not at set-up
            raise RuntimeError("injected solver failure")

    body.refresh = refresh
    problem = Problem([body], name="injected")
    before = body.u.x.array.copy()
    with pytest.raises(NewtonDivergence, match="PETSc error"):
        problem.solve()
    assert np.array_equal(body.u.x.array, before)
    calls["n"] = 10  # no more failures: the same problem now converges
    assert problem.solve().iterations > 0


def test_wear_of_an_axisymmetric_body_is_refused_where_it_is_built():
    """A configuration that cannot run is refused by the constructor, in one line: a
    shape field (finite wear) on an axisymmetric body, which the worn-body kinematics
    (forms/ale.py) do not support, is refused by ``Body``, not later by the stepper."""
    import numpy as np
    from dolfinx import mesh as dmesh
    from mpi4py import MPI

    from tribofx.body import Body
    from tribofx.params import InputError

    msh = dmesh.create_rectangle(MPI.COMM_WORLD, [[1, 0], [2, 1]], [2, 2])
    facets = dmesh.locate_entities_boundary(msh, 1, lambda x: np.isclose(x[1], 0))
    ft = dmesh.meshtags(msh, 1, facets, np.full(len(facets), 1, np.int32))
    law = ("neo-hookean", {"mu": 1.0, "lmbda": 1.0})
    with pytest.raises(InputError, match="3d' or 'plane_strain'") as err:
        Body(msh, ft, {"bottom": 1}, "axisymmetric", law, shape=True)
    assert "\n" not in str(err.value)
    Body(msh, ft, {"bottom": 1}, "plane_strain", law, shape=True)   # the supported kinds build


def test_radial_sliding_of_an_axisymmetric_body_is_refused_where_it_is_built():
    """A radial velocity of an axisymmetric body's material (or of its countersurface)
    is no rigid motion of a surface of revolution (div(V e_r) = V/r ≠ 0): ``Body`` and
    ``Contact`` refuse it in one line; sliding along the axis builds."""
    import numpy as np
    from dolfinx import mesh as dmesh
    from mpi4py import MPI

    from tribofx.body import Body
    from tribofx.interfaces import Contact
    from tribofx.obstacles import rigid_plane
    from tribofx.params import InputError

    msh = dmesh.create_rectangle(MPI.COMM_WORLD, [[1, 0], [2, 1]], [2, 2])
    facets = dmesh.locate_entities_boundary(msh, 1, lambda x: np.isclose(x[0], 1))
    ft = dmesh.meshtags(msh, 1, facets, np.full(len(facets), 1, np.int32))
    law = ("neo-hookean", {"mu": 1.0, "lmbda": 1.0})
    with pytest.raises(InputError, match="slides only along its axis") as err:
        Body(msh, ft, {"bore": 1}, "axisymmetric", law, velocity=(1.0, 0.0))
    assert "\n" not in str(err.value)
    body = Body(msh, ft, {"bore": 1}, "axisymmetric", law, velocity=(0.0, 1.0))
    plane = rigid_plane(np.array([0.9, 0.0]), np.array([1.0, 0.0]))
    with pytest.raises(InputError, match="slides only along its axis"):
        Contact(body, "bore", plane, 1.0, friction=0.1, slip="eulerian", V_master=(0.5, 0.0))
    Contact(body, "bore", plane, 1.0, friction=0.1, slip="eulerian", V_master=(0.0, 0.5))
