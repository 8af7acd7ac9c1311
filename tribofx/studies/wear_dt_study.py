"""The error-versus-Δt study of the wear pin (Figs. 3–4, ``wear-pin --set study=dt``).

:func:`run_dt_study` runs the explicit and the implicit scheme (and BDF2, if
``study_schemes`` asks) over a list of steps on one or more meshes against a fine
(or Richardson) reference, flags the
unstable runs (:mod:`tribofx.studies.wear_stability`) and records errors, costs
and profiles.  Units: s, mm.
"""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from mpi4py import MPI

from ..cases import wear_pin
from ..output import SubRecord
from ..problem import NewtonDivergence
from .wear_stability import (
    OSCILLATION_TOL,
    checkerboard_amplitude,
    oscillation_ratio,
    pin_critical_step,
)

if TYPE_CHECKING:
    from collections.abc import Iterable, Sequence
    from types import ModuleType

    from tqdm import tqdm

    from ..output import RunRecord
    from ..stepper import Stepper

__all__ = ["progress_total", "run", "run_dt_study"]


def _study_run(case: ModuleType, v: wear_pin.Params, n: int, scheme: str, dt: float,
               verbose: bool = False) -> tuple[Stepper | None, dict[str, Any]]:
    """One run of a study; returns (stepper, dict with status, profiles, costs)."""
    over = v.replace(study="none", scheme=scheme, dt=dt)
    if scheme == "explicit":
        over = over.replace(max_cuts=0)  # at its nominal Δt: a failure is the instability
    sub = SubRecord()
    t0 = time.perf_counter()
    status = "ok"
    try:
        prob = case.run(over, sub, n=n, verbose=verbose)
    except NewtonDivergence as err:
        status = f"failed: {type(err).__name__}: {err}"[:200]
        prob = err.model
    wall = time.perf_counter() - t0
    comm = MPI.COMM_WORLD if prob is None else prob.comm
    res = {k: r["value"] for k, r in sub.data["results"].items()}
    out = {"status": status, "wall_time_s": comm.allreduce(wall, op=MPI.MAX),
           "steps": len(res.get("time", [0.0])) - 1,
           "newton_iterations": int(sum(res.get("newton_iterations", [0])[1:])),
           "final_time": res["time"][-1] if res.get("time") else 0.0,
           "max_wear_depth": res["max_wear_depth"][-1] if res.get("max_wear_depth") else 0.0,
           "checkerboard": checkerboard_amplitude(prob.wear) if prob is not None else math.nan}
    prof = sub.profile if comm.rank == 0 else None
    out["final_profile"] = comm.bcast(
        np.asarray(res["final_profile"]) if comm.rank == 0 and "final_profile" in res else None,
        root=0)
    out["profiles"] = comm.bcast(
        None if prof is None else {"times": prof["times"], "profiles": prof["profiles"]}, root=0)
    return prob, out


def run_dt_study(case: ModuleType, v: wear_pin.Params, record: RunRecord | SubRecord,
                 ns: Iterable[int], dts: Sequence[float], progress: tqdm | None = None,
                 verbose: bool = False) -> Stepper | None:
    """``study=dt`` of ``wear-pin`` on the n × n meshes ``ns`` for the time steps ``dts``.

    ``case``: the pin case (the module :mod:`tribofx.cases.wear_pin`, its
    ``run`` makes each run).

    Records ``study_dt``, ``study_error_<scheme>`` for each of ``study_schemes``
    ({"n×n": [error per Δt, None if the run failed]}, mm, Euclidean norm of the
    final worn contact-node positions minus the reference), the max-norm
    counterparts ``study_maxerror_*``, ``study_unstable_*`` and ``study_status_*``
    flags, checkerboard amplitudes, costs and ``study_dt_cr`` (explicit critical
    step per mesh, None if not computed or not bracketed).  Returns the reference
    run's stepper of the last mesh; ``record.profile`` holds what
    :func:`tribofx.plots.wear.plot_dt_study` needs.
    """
    T = v.T
    ref_dt = v.study_ref_dt
    schemes = case.study_schemes(v)
    ref_scheme = "bdf2" if "bdf2" in schemes else "implicit"
    names = ("error", "maxerror", "unstable", "oscillation", "status", "checkerboard",
             "wall_time", "newton")
    res: dict[str, dict[str, Any]] = {f"{name}_{s}": {} for s in schemes for name in names}
    res.update({key: {} for key in ("dt_cr", "reference_wall_time", "reference_correction",
                                    "checkerboard_reference")})
    plots = {"study": "dt", "dts": list(dts), "E": v.E, "T": T, "meshes": {},
             "schemes": schemes}
    prob_ref = None
    for n in ns:
        key = f"{n}x{n}"
        t0 = time.perf_counter()
        prob_ref, ref = _study_run(case, v, n, ref_scheme, ref_dt, verbose)
        if not ref["status"] == "ok":
            raise NewtonDivergence(f"study reference run ({key}, Δt = {ref_dt} s) "
                                   f"{ref['status']}")
        p_ref = ref["final_profile"]
        correction = 0.0
        if v.study_ref == "richardson":
            _, coarse = _study_run(case, v, n, "implicit", 2 * ref_dt, verbose)
            if not coarse["status"] == "ok":
                raise NewtonDivergence(f"study reference run ({key}, Δt = {2 * ref_dt} s) "
                                       f"{coarse['status']}")
            correction = float(np.linalg.norm(p_ref - coarse["final_profile"]))
            p_ref = 2 * p_ref - coarse["final_profile"]
        res["reference_wall_time"][key] = time.perf_counter() - t0
        res["reference_correction"][key] = correction
        res["checkerboard_reference"][key] = ref["checkerboard"]
        dt_cr = None
        if v.study_critical and "explicit" in schemes:
            try:
                dt_cr = pin_critical_step(case, v, n, lo=0.01, hi=1e4)[0]
            except (ValueError, NewtonDivergence):
                dt_cr = None
        res["dt_cr"][key] = dt_cr
        runs: dict[str | tuple[str, float], dict[str, Any]] = {
            "reference": {"dt": ref_dt, "profiles": ref["profiles"], "final_profile": p_ref}}
        for scheme in schemes:
            for name in names:
                res[f"{name}_{scheme}"][key] = []
            for dt in dts:
                _, r = _study_run(case, v, n, scheme, dt, verbose)
                ok = r["status"] == "ok"
                if ok:
                    diff = r["final_profile"] - p_ref
                    err: float | None = float(np.linalg.norm(diff))
                    maxerr: float | None = float(np.max(np.linalg.norm(diff, axis=1)))
                    osc: float | None = oscillation_ratio(diff[:, 1])
                else:
                    err = maxerr = osc = None
                res[f"error_{scheme}"][key].append(err)
                res[f"maxerror_{scheme}"][key].append(maxerr)
                res[f"unstable_{scheme}"][key].append(
                    bool(not ok or cast(float, osc) > OSCILLATION_TOL   # ok: osc is a float
                         or (scheme == "explicit" and dt_cr is not None and dt > dt_cr)))
                res[f"oscillation_{scheme}"][key].append(osc)
                res[f"status_{scheme}"][key].append(r["status"])
                res[f"checkerboard_{scheme}"][key].append(r["checkerboard"])
                res[f"wall_time_{scheme}"][key].append(r["wall_time_s"])
                res[f"newton_{scheme}"][key].append(r["newton_iterations"])
                runs[(scheme, dt)] = {"profiles": r["profiles"], "ok": ok}
                if progress is not None:
                    progress.update(1)
        plots["meshes"][key] = {"runs": runs, "dt_cr": dt_cr, **{
            f"{name}_{s}": res[f"{name}_{s}"][key] for s in schemes
            for name in ("error", "unstable")}}
    record.result("study_dt", list(dts), "s")
    units = {"error": "mm (Euclidean norm over the contact nodes)",
             "maxerror": "mm (max nodal distance)", "unstable": "-", "status": "-",
             "oscillation": "-",
             "checkerboard": "mm", "wall_time": "s", "newton": "-", "dt_cr": "s",
             "reference": "s", "checkerboard_reference": "mm"}
    for name, val in res.items():
        record.result(f"study_{name}", val, units.get(name.split("_")[0], units.get(name, "-")))
    ref_txt = (f"{ref_scheme}, Δt = {ref_dt:g} s" if v.study_ref == "fine" else
               f"Richardson 2 p({ref_dt:g} s) − p({2 * ref_dt:g} s), implicit")
    record.result("study_reference", ref_txt, "-")
    record.result("study_unstable_criterion",
                  "failed at nominal Δt, or oscillation ratio of the error > "
                  f"{OSCILLATION_TOL:g}, or explicit with Δt > study_dt_cr", "-")
    plots["reference"] = ref_txt
    if prob_ref is not None and prob_ref.comm.rank == 0:
        record.profile = plots
    return prob_ref


def progress_total(v: wear_pin.Params) -> int:
    """Return the steps the progress bar counts: one per run of the study (scheme × Δt × mesh)."""
    dts, levels = wear_pin.study_lists(v)
    return len(wear_pin.study_schemes(v)) * len(dts) * len(levels)


def run(v: wear_pin.Params, record: RunRecord | SubRecord, progress: tqdm | None = None,
        verbose: bool = False) -> Stepper | None:
    """``tribofx run wear-pin --set study=dt``: the study on the meshes and steps ``v`` lists.

    The meshes are n × n with n = 10·2^level for each level of ``study_meshes``
    (default: ``mesh``); see :func:`run_dt_study`.
    """
    dts, levels = wear_pin.study_lists(v)
    return run_dt_study(wear_pin, v, record, [10 * 2**m for m in levels], dts,
                        progress=progress, verbose=verbose)
