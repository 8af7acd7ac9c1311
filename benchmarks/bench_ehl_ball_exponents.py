"""Speed and load exponents of the ball's film against Hamrock–Dowson's, as rates.

The isoviscous-elastic fit of Hamrock & Dowson (1978) has h_c ∝ U^0.64 W^−0.22 and
h_min ∝ U^0.65 W^−0.21 (:func:`tribofx.references.hamrock_dowson`).  This script runs
``ehl-ball`` (its defaults: the mixed solid, the vertex rule) at (W, U), (2W, U) and
(W, 2U) on each mesh level and reports the exponents d ln h / d ln W and
d ln h / d ln U from those pairs, level by level: how they move with the mesh is the
rate at which the film's dependence converges, and where it converges to says whether
the fit's exponent holds for a soft ball at finite strain (a/R ≈ 0.18 at 2 N).
Nothing is asserted: the exponents are measured (the issue "Soft on soft" asks for them
as rates, not as tests).

    .venv/bin/python benchmarks/bench_ehl_ball_exponents.py [--W 2] [--U 1e4]
        [--meshes 1 2] [--out results/bench_ehl_ball_exponents]
"""

import argparse
import json
import math
import os
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import dolfinx_solver  # noqa: E402,F401  (before dolfinx / petsc4py)
from mpi4py import MPI  # noqa: E402

from tribofx.cases import ehl_ball as Case  # noqa: E402
from tribofx.params import resolve  # noqa: E402
from tribofx.references import hamrock_dowson  # noqa: E402


def film(W: float, U: float, mesh: int) -> dict:
    """h_c, h_min (mm) of the ball at (W, U) on ``mesh``, one load step; wall time."""
    v = resolve(Case.Params, {"W": str(W), "U": str(U), "mesh": str(mesh), "steps": "1"})
    Case.validate(v)
    run = Case.build(v)
    t0 = time.perf_counter()
    Case.load_sweep(run, v)
    m = Case.measures(run, v)
    return {"h_central": m["h_central"], "h_min": m["h_min"], "unknowns": run.problem.num_dofs,
            "rule": Case.film_rule(v), "wall_s": time.perf_counter() - t0}


def exponents(base: dict, other: dict, ratio: float) -> dict:
    """d ln h / d ln x from two runs whose x differs by ``ratio``."""
    return {k: math.log(other[k] / base[k]) / math.log(ratio) for k in ("h_central", "h_min")}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--W", type=float, default=2.0)
    parser.add_argument("--U", type=float, default=1e4)
    parser.add_argument("--meshes", type=int, nargs="*", default=[1, 2])
    parser.add_argument("--out", default="results/bench_ehl_ball_exponents")
    a = parser.parse_args()
    v = resolve(Case.Params, {"W": str(a.W), "U": str(a.U)})
    ref = {}
    for name, (W, U) in (("load", (2 * a.W, a.U)), ("speed", (a.W, 2 * a.U))):
        h0 = hamrock_dowson(a.W, v.mu, a.U, v.R, Case.e_star(v))
        h1 = hamrock_dowson(W, v.mu, U, v.R, Case.e_star(v))
        ref[name] = {k: math.log(h1[i] / h0[i]) / math.log(2.0)
                     for i, k in enumerate(("h_central", "h_min"))}
    rows = {}
    for mesh in a.meshes:
        base = film(a.W, a.U, mesh)
        load = film(2 * a.W, a.U, mesh)
        speed = film(a.W, 2 * a.U, mesh)
        rows[mesh] = {"runs": {"base": base, "load": load, "speed": speed},
                      "load": exponents(base, load, 2.0), "speed": exponents(base, speed, 2.0)}
    if MPI.COMM_WORLD.rank == 0:
        print(f"W = {a.W:g} → {2 * a.W:g} N, U = {a.U:g} → {2 * a.U:g} mm/s "
              "(exponents d ln h / d ln x)")
        print(f"{'mesh':>5} {'unknowns':>9} {'rule':>7} {'h_c~W':>7} {'h_c~U':>7} "
              f"{'h_min~W':>8} {'h_min~U':>8} {'wall s':>7}")
        for mesh, r in rows.items():
            b = r["runs"]["base"]
            wall = sum(x["wall_s"] for x in r["runs"].values())
            print(f"{mesh:>5} {b['unknowns']:>9} {b['rule']:>7} "
                  f"{r['load']['h_central']:7.3f} {r['speed']['h_central']:7.3f} "
                  f"{r['load']['h_min']:8.3f} {r['speed']['h_min']:8.3f} {wall:7.0f}")
        print(f"{'HD':>5} {'':>9} {'':>7} {ref['load']['h_central']:7.3f} "
              f"{ref['speed']['h_central']:7.3f} {ref['load']['h_min']:8.3f} "
              f"{ref['speed']['h_min']:8.3f}")
        out = Path(a.out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "bench_ehl_ball_exponents.json").write_text(
            json.dumps({"rows": rows, "hamrock_dowson": ref}, indent=1))


if __name__ == "__main__":
    main()
