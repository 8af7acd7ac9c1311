"""wear-pin: cost of the monolithic implicit scheme against the explicit scheme (§4.4, eq. 31).

In one run, for the ``wear-pin`` defaults (E = 640 MPa, 20 × 20 mesh, T = 1000 s,
small-deformation regime):

1. the critical step Δt_cr of the explicit scheme on this mesh and modulus, by
   bisection with the flat-pin stability probe
   (:func:`tribofx.studies.wear_stability.pin_critical_step`);
2. a reference worn profile: Richardson extrapolation 2 p(Δt/2) − p(Δt) of two
   implicit runs with Δt = 10 s and 5 s (second order);
3. implicit, Δt = 200 s (5 steps), and explicit at its largest stable step
   (the largest T/N below Δt_cr), plus explicit with Δt = 200 s to show the
   instability, plus implicit with the step that matches the explicit run's
   error (implicit error ∝ Δt); wall time, steps, Newton iterations and the error of the final
   worn contact profile (Euclidean norm of the nodal position differences, mm,
   as in Fig. 4) for each;
4. the fraction of the monolithic unknowns that belong to Ψ (w and the
   multiplier ζ of the shape constraint; w alone also reported).

Prints a table and writes benchmarks/results/wear.json.

    .venv/bin/python benchmarks/bench_wear.py [--E 640] [--mesh 1] [--out FILE]
"""

import argparse
import json
import math
import os
import tempfile
import time
from pathlib import Path

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401
import numpy as np
from mpi4py import MPI

from tribofx.cases import wear_pin
from tribofx.output import RunRecord
from tribofx.params import resolve
from tribofx.problem import NewtonDivergence
from tribofx.studies.wear_stability import pin_critical_step

parser = argparse.ArgumentParser()
parser.add_argument("--E", type=float, default=640.0)
parser.add_argument("--mesh", type=int, default=1)
parser.add_argument("--out", default="benchmarks/results/wear.json")
args = parser.parse_args()
comm = MPI.COMM_WORLD
units = None


def run(tmp, **over):
    """One wear-pin run; returns (stepper or None, results, wall time, status)."""
    over = {"E": args.E, "mesh": args.mesh, **over}
    values = resolve(wear_pin.Params, {k: str(v) for k, v in over.items()})
    wear_pin.validate(values)
    rec = RunRecord("wear-pin", values, units, Path(tmp) / f"r{len(os.listdir(tmp))}", comm)
    rec.profile = None
    t0 = time.perf_counter()
    status, prob = "ok", None
    try:
        prob = wear_pin.run(values, rec)
    except NewtonDivergence as err:
        status = f"failed: {err}"
    wall = time.perf_counter() - t0
    res = {k: v["value"] for k, v in rec.data["results"].items()}
    return prob, res, wall, status, values


def profile(res):
    p = comm.bcast(res.get("final_profile"), root=0)
    return np.asarray(p)


rows = []
with tempfile.TemporaryDirectory() as tmp:
    values = resolve(wear_pin.Params, {"E": str(args.E), "mesh": str(args.mesh)})
    n = wear_pin.n_elements(values)
    t0 = time.perf_counter()
    dt_cr, _ = pin_critical_step(wear_pin, values, n, lo=0.05, hi=200.0)
    t_probe = time.perf_counter() - t0
    T = values.T
    dt_exp = T / math.ceil(T / dt_cr)

    _, r10, _, _, _ = run(tmp, scheme="implicit", dt=10)
    _, r5, _, _, _ = run(tmp, scheme="implicit", dt=5)
    ref = 2 * profile(r5) - profile(r10)
    ref_err = float(np.linalg.norm(profile(r5) - ref))

    plan = [("implicit dt=200", {"scheme": "implicit", "dt": 200}),
            ("explicit dt_cr", {"scheme": "explicit", "dt": dt_exp}),
            ("explicit dt=200", {"scheme": "explicit", "dt": 200, "max_cuts": 0}),
            ("implicit same err", None)]
    for label, over in plan:
        if over is None:
            if "error_mm" not in rows[1] or "error_mm" not in rows[0]:
                continue  # a reference run failed: no matched-accuracy comparison
            # implicit error ∝ Δt: the step that matches the explicit run's error
            dt_m = 200 * rows[1]["error_mm"] / rows[0]["error_mm"]
            over = {"scheme": "implicit", "dt": T / math.ceil(T / dt_m)}
        prob, res, wall, status, v = run(tmp, **over)
        its = int(sum(res["newton_iterations"][1:])) if res.get("newton_iterations") else 0
        row = {"run": label, "scheme": over["scheme"], "dt_s": over["dt"], "status": status,
               "steps": len(res.get("time", [0])) - 1, "newton_iterations": its,
               "wall_time_s": wall}
        if status == "ok":
            row["error_mm"] = float(np.linalg.norm(profile(res) - ref))
            row["worn_area_mm2"] = res["wear_volume"][-1]
            row["max_wear_depth_mm"] = res["max_wear_depth"][-1]
            if over["scheme"] == "implicit":
                gdim = 2
                n_w = prob.wear.body.Vw.dofmap.index_map.size_global * gdim
                row["num_dofs"] = prob.problem.num_dofs
                row["psi_fraction"] = prob.shape_unknown_fraction()
                row["w_fraction"] = n_w / prob.problem.num_dofs
        rows.append(row)

imp, exp, imp_m = rows[0], rows[1], rows[3]
summary = {
    "case": "wear-pin", "E_MPa": args.E, "mesh": f"{n}x{n}", "T_s": T,
    "dt_cr_s": dt_cr, "dt_cr_probe_time_s": t_probe, "explicit_dt_s": dt_exp,
    "reference": "Richardson 2 p(5 s) - p(10 s) of implicit runs",
    "reference_error_estimate_mm": ref_err,
    "cost_ratio_explicit_over_implicit": exp["wall_time_s"] / imp["wall_time_s"],
    "newton_ratio_explicit_over_implicit": exp["newton_iterations"] / imp["newton_iterations"],
    "cost_ratio_same_accuracy": exp["wall_time_s"] / imp_m["wall_time_s"],
    "newton_ratio_same_accuracy": exp["newton_iterations"] / imp_m["newton_iterations"],
    "psi_fraction": imp.get("psi_fraction"), "w_fraction": imp.get("w_fraction"),
    "mpi_size": comm.size, "runs": rows,
}
if comm.rank == 0:
    print(f"wear-pin E = {args.E:g} MPa, {n}x{n}: explicit dt_cr = {dt_cr:.3f} s "
          f"(probe {t_probe:.1f} s); explicit run at dt = {dt_exp:.3f} s")
    print(f"{'run':>16} {'steps':>6} {'Newton':>7} {'wall[s]':>8} {'error[mm]':>10} status")
    for r in rows:
        err = f"{r['error_mm']:10.2e}" if "error_mm" in r else f"{'-':>10}"
        print(f"{r['run']:>16} {r['steps']:6d} {r['newton_iterations']:7d} "
              f"{r['wall_time_s']:8.2f} {err} {r['status'][:60]}")
    print(f"cost ratio explicit/implicit: wall {summary['cost_ratio_explicit_over_implicit']:.1f}, "
          f"Newton its {summary['newton_ratio_explicit_over_implicit']:.1f}; at the explicit "
          f"run's accuracy: wall {summary['cost_ratio_same_accuracy']:.1f}, Newton its "
          f"{summary['newton_ratio_same_accuracy']:.1f}")
    print(f"Ψ unknowns (w, ζ) {100 * summary['psi_fraction']:.1f} % "
          f"(w alone {100 * summary['w_fraction']:.1f} %) of {imp['num_dofs']}")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(summary, indent=2))
