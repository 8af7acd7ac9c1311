"""Cost of the transient film: one implicit time step against one steady Newton solve.

Issue 31's goal: one implicit step of the transient film costs at most 1.3× a
steady Newton solve at the same unknowns.  The problem is ``ehl-squeeze``
(cylinder ``dim=2`` and sphere ``dim=3``, mesh 0, the stiff body under a load).
Measured in one run, per dimension:

* the time per Newton iteration (residual + Jacobian assembly + linear solve) of
  the transient Problem (BDF2 rows) and of the same body and film built steady
  (``transient`` not called: the chapter's rows), both at the same state;
* ``begin_step`` (the histories: content interpolated at the quadrature points);
* Newton iterations per transient step.

The ratio reported is (begin_step + n·t_iter,transient)/(n·t_iter,steady) with
the transient step's n iterations: a steady solve at a new load or speed takes
at least as many (2–3 here; 3–6 per continuation step in the EHL cases), so
the ratio bounds the step's cost against a steady solve.  Writes ``--out`` (JSON).

    .venv/bin/python benchmarks/bench_squeeze.py [--out results/bench_squeeze.json]
        [--ranks 2]

``--ranks 2`` runs the same measurements again under ``mpiexec -n 2`` (a
subprocess of this run) and reports the times per iteration serial against
2 ranks.
"""

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401,E402

from tribofx.cases import ehl_squeeze as Case  # noqa: E402
from tribofx.params import resolve  # noqa: E402


def per_iteration(problem, repeat=3):
    """Seconds of one Newton iteration's work: assemble R and J, factor and solve once."""
    ksp_solve = problem.snes.getKSP()
    t = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        b, A = problem.assemble()
        ksp_solve.setOperators(A)
        x = b.duplicate()
        ksp_solve.solve(b, x)
        t.append(time.perf_counter() - t0)
        x.destroy()
    return min(t)


def run(dim):
    """Measure one dimension; returns the row."""
    over = {"dim": dim, "control": "load", "E1": 1e7, "F": 0.05 if dim == 2 else 0.02,
            "T": 1e-3, "dt": 2.5e-4}
    v = resolve(Case.Params, {k: str(x) for k, x in over.items()})
    st = Case.build(v).stepper
    st.run(2 * v.dt, v.dt)                  # two steps: the BDF2 history is full
    film = st.wear
    t0 = time.perf_counter()
    film.begin_step(v.dt)
    t_begin = time.perf_counter() - t0
    its = st.problem.solve().iterations
    t_tr = per_iteration(st.problem)
    # the same mesh, body and film with the chapter's steady rows (the body held at its
    # top, since a steady film cannot carry a load alone), the same unknowns
    steady = Case.steady_problem(v.replace(control="speed"))
    t_st = per_iteration(steady)
    return {"dim": dim, "unknowns": st.problem.num_dofs, "unknowns_steady": steady.num_dofs,
            "begin_step_s": t_begin, "iteration_transient_s": t_tr,
            "iteration_steady_s": t_st, "iterations_transient_step": its,
            "ratio_iteration": t_tr / t_st,
            "ratio_step_to_solve": (t_begin + its * t_tr) / (its * t_st)}


def main():
    """Run both dimensions and print the table."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="results/bench_squeeze.json")
    ap.add_argument("--ranks", type=int, default=1)
    a = ap.parse_args()
    rows = [run(2), run(3)]
    from mpi4py import MPI

    if MPI.COMM_WORLD.rank != 0:
        return
    if a.ranks > 1:
        par = Path(a.out).with_name(Path(a.out).stem + f"_{a.ranks}ranks.json")
        mpiexec = Path(sys.executable).parent / "mpiexec"
        subprocess.run([str(mpiexec), "-n", str(a.ranks), sys.executable, __file__,
                        "--out", str(par)], check=True, cwd=Path(__file__).parent)
        other = json.loads((Path(__file__).parent / par).read_text())
        for r, o in zip(rows, other):
            r[f"speedup_{a.ranks}_ranks"] = r["iteration_transient_s"] / o["iteration_transient_s"]
    for r in rows:
        print(f"dim {r['dim']}: {r['unknowns']} unknowns, begin_step {r['begin_step_s']:.4f} s, "
              f"iteration {r['iteration_transient_s']:.4f} s transient / "
              f"{r['iteration_steady_s']:.4f} s steady, {r['iterations_transient_step']} "
              f"iterations per step, per iteration {r['ratio_iteration']:.2f}, step/solve "
              f"{r['ratio_step_to_solve']:.2f}"
              + (f", {a.ranks} ranks: {r[f'speedup_{a.ranks}_ranks']:.2f}x" if a.ranks > 1
                 else ""))
    out = Path(__file__).parent / a.out
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(rows, indent=2))


if __name__ == "__main__":
    main()
