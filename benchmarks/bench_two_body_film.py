"""The two-body film's share of a Newton iteration (issue 31's goal: at most 10 %).

The problem is ``ehl-two-cylinders`` (two soft cylinders rolling on a film) at
its default load, mesh levels 0–2.  After the load is reached, one more Newton
solve (from a perturbed approach δ) is timed; per Newton iteration:

* the film's kernel work: gather of the master's current nodes on every rank,
  box-tree refit and projection, the C++ nodal kernel (``TwoBodyFilm._kernel``),
  and the C++ insertion of its blocks into the PETSc vector and matrix
  (``add_residual``, ``add_jacobian``, which include ``_kernel``'s first call);
* the UFL assembly of all blocks (bodies and the film's Reynolds, trace,
  gradient, nodal and collocation rows);
* the rest (the linear solve, the line search, the stopping test).

``--ranks 2`` runs the same under ``mpiexec -n 2`` (a subprocess) and reports the
time per iteration serial against 2 ranks.  Writes ``--out`` (JSON).

    .venv/bin/python benchmarks/bench_two_body_film.py [--out results/two_body_film.json]
        [--ranks 2] [--levels 0,1,2]
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
from timing import Timer  # noqa: E402  (benchmarks/timing.py)

from tribofx.cases import ehl_two_cylinders as Case  # noqa: E402
from tribofx.output import RunRecord  # noqa: E402
from tribofx.params import resolve  # noqa: E402

__all__ = ["main", "split"]


def split(level):
    """Load the case at mesh ``level``; time one Newton solve; return the split (dict)."""
    from mpi4py import MPI

    v = resolve(Case.Params, {"mesh": str(level)})
    rec = RunRecord(Case.name, {}, {}, Path("."), MPI.COMM_WORLD)
    run = Case.run(v, rec)
    film, problem, lift = run.film, run.problem, run.lift
    lift.value[1] *= 0.98                      # a new approach: a few Newton iterations
    timer = Timer()
    timer.time_split(film, ("add_residual", "add_jacobian", "_kernel"), problem)
    t0 = time.perf_counter()
    rep = problem.solve()
    total = time.perf_counter() - t0
    t = timer.total
    film_t = t.get("add_residual", 0.0) + t.get("add_jacobian", 0.0)
    ufl_t = t.get("_assemble_residual", 0.0) + t.get("_assemble_jacobian", 0.0)
    its = max(rep.iterations, 1)
    return {"mesh": level, "unknowns": problem.num_dofs, "film_nodes": int(
        MPI.COMM_WORLD.allreduce(len(film._q))), "newton_iterations": rep.iterations,
        "iteration_s": total / its, "film_fraction": film_t / total,
        "film_kernel_search_fraction": t.get("_kernel", 0.0) / total,
        "ufl_assembly_fraction": ufl_t / total,
        "solve_and_rest_fraction": 1 - (film_t + ufl_t) / total}


def main():
    """Run the levels and print the table."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="results/two_body_film.json")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--levels", default="0,1,2")
    a = ap.parse_args()
    rows = [split(int(k)) for k in a.levels.split(",")]
    from mpi4py import MPI

    if MPI.COMM_WORLD.size > 1 or MPI.COMM_WORLD.rank > 0:
        if MPI.COMM_WORLD.rank == 0:
            out = Path(__file__).parent / a.out
            out.parent.mkdir(parents=True, exist_ok=True)
            out.write_text(json.dumps(rows, indent=1))
        return rows
    if a.ranks > 1:
        par = Path(a.out).with_name(Path(a.out).stem + f"_{a.ranks}ranks.json")
        mpiexec = Path(sys.executable).parent / "mpiexec"
        subprocess.run([str(mpiexec), "-n", str(a.ranks), sys.executable, __file__,
                        "--out", str(par), "--levels", a.levels], check=True,
                       cwd=Path(__file__).parent)
        other = json.loads((Path(__file__).parent / par).read_text())
        for r, o in zip(rows, other):
            r[f"speedup_{a.ranks}_ranks"] = r["iteration_s"] / o["iteration_s"]
            r[f"film_fraction_{a.ranks}_ranks"] = o["film_fraction"]
    for r in rows:
        print(f"mesh {r['mesh']}: {r['unknowns']} unknowns, {r['film_nodes']} film nodes, "
              f"{r['newton_iterations']} its, {r['iteration_s']:.4f} s/it; film "
              f"{100 * r['film_fraction']:.1f} % (of which gather+search+kernel "
              f"{100 * r['film_kernel_search_fraction']:.1f} %), UFL assembly "
              f"{100 * r['ufl_assembly_fraction']:.1f} %, solve and rest "
              f"{100 * r['solve_and_rest_fraction']:.1f} %"
              + (f"; {a.ranks} ranks: {r[f'speedup_{a.ranks}_ranks']:.2f}x, film "
                 f"{100 * r[f'film_fraction_{a.ranks}_ranks']:.1f} %" if a.ranks > 1 else ""))
    out = Path(__file__).parent / a.out
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(rows, indent=1))
    return rows


if __name__ == "__main__":
    main()
