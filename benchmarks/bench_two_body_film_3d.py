"""The 3D two-body film's Newton iteration against the one-body film's (issue 52's goal: ≤ 1.5×).

The problem is ``ehl-ball`` at W = 2 N (mesh 1, the ball's ~12k unknowns) twice, in
one run: on the rigid plane (``E2=inf``, the one-body :class:`tribofx.interfaces.Film`)
and on a disc as soft as the ball (``E2=1.19``, :class:`tribofx.interfaces.TwoBodyFilm`
in 3D, the disc's bulk added).  After the load is reached, one more Newton solve from
a perturbed position of the countersurface is timed, per iteration:

* the whole iteration, t₁ (one body) and t₂ (two bodies);
* the disc's own bulk: a Newton iteration of the disc alone under the film's pressure
  as a prescribed follower load (:class:`~tribofx.interfaces.prescribed_pressure.
  BoundaryPressure`), t_d — what any model with a deformable disc pays;
* the two-body film's kernel work (gather, box-tree refit and projection on the
  master's triangles, the C++ nodal kernel and the insertion of its blocks:
  ``add_residual``, ``add_jacobian``) and its search alone (``_kernel``).

Reported: (t₂ − t_d)/t₁ (goal ≤ 1.5), the kernel's share of t₂ (goal ≤ 10 %) and
the UFL assembly's (the rest is the linear solve of the coupled system and the line
search).
Ratios within one run on one machine.  Writes ``--out`` (JSON).

    .venv/bin/python benchmarks/bench_two_body_film_3d.py [--out results/two_body_film_3d.json]
"""

import argparse
import json
import os
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401,E402
import numpy as np  # noqa: E402
from timing import Timer  # noqa: E402  (benchmarks/timing.py)

from tribofx.cases import ehl_ball as Case  # noqa: E402
from tribofx.interfaces.prescribed_pressure import BoundaryPressure  # noqa: E402
from tribofx.params import resolve  # noqa: E402
from tribofx.problem import Problem  # noqa: E402

__all__ = ["disc_alone", "main", "one_solve"]


def one_solve(E2):
    """Reach W = 2 N on the plane (E2 = inf) or the disc; time one more solve (dict)."""
    v = resolve(Case.Params, {"W": "2", "steps": "1", "mesh": "1", "E2": str(E2)})
    run = Case.build(v)
    Case.load_sweep(run, v, lambda W, its: None)
    run.position.value[Case.Z] += 0.02 * Case.hertz_contact(v).delta   # a new approach
    timer = Timer()
    if run.disc is not None:      # (the one-body problem assembles its Jacobian in DOLFINx)
        timer.time_split(run.film, ("add_residual", "add_jacobian", "_kernel"), run.problem)
    t0 = time.perf_counter()
    rep = run.problem.solve()
    total = time.perf_counter() - t0
    its = max(rep.iterations, 1)
    t = timer.total
    return run, {"E2": E2, "unknowns": run.problem.num_dofs, "newton_iterations": rep.iterations,
                 "iteration_s": total / its,
                 "kernel_s": (t.get("add_residual", 0.0) + t.get("add_jacobian", 0.0)) / its,
                 "search_s": t.get("_kernel", 0.0) / its,
                 "ufl_assembly_s": (t.get("_assemble_residual", 0.0)
                                    + t.get("_assemble_jacobian", 0.0)) / its}


def disc_alone(run):
    """Time a Newton iteration of the disc alone under the film's pressure (s per iteration)."""
    disc = run.disc
    load = BoundaryPressure(disc, "lubricated")
    problem = Problem([disc, load], name="disc_alone")
    p_max = float(np.max(run.film.p.x.array))
    load.p.interpolate(lambda x: p_max * np.maximum(0.0, 1 - (x[0] ** 2 + x[1] ** 2) / 4.0))
    disc.u.x.array[:] *= 0.98            # off its equilibrium: a few iterations
    t0 = time.perf_counter()
    rep = problem.solve()
    return (time.perf_counter() - t0) / max(rep.iterations, 1), rep.iterations


def main():
    """Run both films and print the ratios."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="results/two_body_film_3d.json")
    a = ap.parse_args()
    _, one = one_solve(float("inf"))
    run, two = one_solve(1.19)
    t_d, its_d = disc_alone(run)
    ratio = (two["iteration_s"] - t_d) / one["iteration_s"]
    share = two["kernel_s"] / two["iteration_s"]
    out = {"one_body": one, "two_body": two, "disc_alone_iteration_s": t_d,
           "disc_alone_newton_iterations": its_d, "ratio_minus_disc": ratio,
           "kernel_share": share, "search_share": two["search_s"] / two["iteration_s"]}
    print(f"one-body film: {one['unknowns']} unknowns, {one['iteration_s']:.3f} s/it "
          f"({one['newton_iterations']} its); two-body film: {two['unknowns']} unknowns, "
          f"{two['iteration_s']:.3f} s/it ({two['newton_iterations']} its); the disc alone "
          f"{t_d:.3f} s/it; (t2 - t_disc)/t1 = {ratio:.2f} (goal <= 1.5); kernel "
          f"{100 * share:.1f} % of t2 (search {100 * out['search_share']:.1f} %; goal <= 10 %); "
          f"UFL assembly {100 * two['ufl_assembly_s'] / two['iteration_s']:.1f} % of t2, the "
          f"linear solve and the rest "
          f"{100 * (1 - (two['kernel_s'] + two['ufl_assembly_s']) / two['iteration_s']):.1f} %")
    path = Path(__file__).parent / a.out
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(out, indent=1))
    return out


if __name__ == "__main__":
    main()
