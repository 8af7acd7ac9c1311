"""Numerical studies of the wear cases: explicit critical step (eq. 31) and error versus Δt.

* :func:`pin_critical_step` — largest stable explicit Δt of the flat pin, from the
  growth of a node-to-node alternating wear-depth perturbation;
* :func:`ball_critical_step` — largest stable explicit Δt of the ball on a flat
  from a developed scar, from the growth of the pressure nonuniformity;
* :func:`run_dt_study` — the error-versus-Δt study of Figs. 3–4 (``wear-pin
  --set study=dt``).

Both critical steps bisect with :func:`tribofx.stepper.bisect_critical_step`;
the chapter gives only the scaling Δt_cr ∼ h/E.  Units: s, mm.
"""

import math
import time

import numpy as np
from mpi4py import MPI

from .cases.wear import WearPinCase
from .cases.wear_ball import MODEL_FRACTION, WearBallCase
from .problem import NewtonDivergence
from .stepper import bisect_critical_step, growth_probe

__all__ = ["OSCILLATION_TOL", "ball_critical_step", "checkerboard_amplitude",
           "oscillation_ratio", "pin_critical_step", "pressure_nonuniformity", "run_dt_study",
           "seed_checkerboard"]

OSCILLATION_TOL = 0.7  # unstable: node-to-node oscillating part of the error > 70 %


def oscillation_ratio(err):
    """Share of the node-to-node alternating mode in a nodal error e_i (nodes sorted by X̂).

    ‖(e_{i−1} − 2 e_i + e_{i+1})/4‖ / ‖e_i‖ over the interior nodes: ≈ 1 for an
    alternating (checkerboard) error, O((h/L)²) for a smooth one.
    """
    err = np.asarray(err, dtype=float)
    hp = (err[:-2] - 2 * err[1:-1] + err[2:]) / 4
    den = np.linalg.norm(err[1:-1])
    return float(np.linalg.norm(hp) / den) if den > 0 else 0.0


def seed_checkerboard(wear, W, n, eps):
    """Add a wear-depth perturbation ε(−1)^i to the contact nodes x_i = −W/2 + i h of a flat pin."""
    w = wear.body.w
    X = w.function_space.tabulate_dof_coordinates()
    on = np.isclose(X[:, 1], 0.0, atol=1e-9 * W)
    i = np.rint((X[on, 0] + W / 2) / (W / n)).astype(int)
    w.x.array.reshape(-1, 2)[on, 1] += eps * (-1.0) ** i
    w.x.scatter_forward()


def checkerboard_amplitude(wear):
    """Amplitude of the node-to-node alternating mode of the wear depth on Γ̂_c (mm).

    Projection of d_i − mean(d) onto (−1)^i − mean((−1)^i), nodes sorted by X̂;
    the same value on every rank.
    """
    d = wear.gather_shape(root_only=False)
    depth = d["depth"] - np.mean(d["depth"])
    s = (-1.0) ** np.arange(len(depth))
    s -= s.mean()
    return float(depth @ s / (s @ s))


def pin_critical_step(v, n, lo, hi, steps=3, iters=12, eps=1e-6):
    """Largest stable Δt (s) of the explicit scheme on an n × n flat-ended pin (eq. 31).

    The stability probe: the flat pin in the homogeneous state (parameters ``v``
    of ``wear-pin``, R_tip forced to 0) gets a node-to-node alternating wear-depth
    perturbation of amplitude ε (the highest mode the mesh carries, i.e. the
    first to go unstable), the contact problem is re-solved, and ``steps``
    explicit steps are taken.  Forward Euler multiplies that mode by g = 1 − Δt kV S
    per step (S: pressure per unit depth of the mode, ∝ E/h), so Δt is stable iff
    the amplitude does not grow, |a_steps| ≤ |a_0|; a Newton failure or inverted
    mesh also counts as unstable.  Bisection on log Δt in [lo, hi] (lo stable, hi
    unstable, both checked).  Returns ``(dt_cr, probe)`` with ``probe`` the list of
    (Δt, a_steps/a_0) evaluated.
    """
    v = {**v, "scheme": "explicit", "R_tip": 0.0}
    stepper, load = WearPinCase.build(v, n=n)
    WearPinCase.load_up(stepper, load, v)
    seed_checkerboard(stepper.wear, v["W"], n, eps)
    stepper.problem.solve()
    stepper.problem.commit()
    start = stepper.state()
    a0 = checkerboard_amplitude(stepper.wear)
    probe = []
    growth = growth_probe(stepper, start, steps,
                          lambda: checkerboard_amplitude(stepper.wear) / a0, probe)
    dt_cr = bisect_critical_step(growth, lo, hi, iters, probe=probe)
    stepper.restore(start)
    return dt_cr, probe


def pressure_nonuniformity(contact):
    """Relative standard deviation of the nodal contact pressure over the inner scar.

    Area-weighted over the active nodes within 0.7 of the contact radius of the
    half disc (the edge nodes carry partial lumped areas); 0 for a uniform pressure.
    """
    comm = contact.body.mesh.comm
    d = contact.nodal_data()
    area = comm.allreduce(float(np.sum(d["weight"][d["active"]])), op=MPI.SUM)
    a_c = math.sqrt(area / (MODEL_FRACTION * math.pi))
    r = np.linalg.norm(d["x"][:, :2], axis=1)
    sel = d["active"] & (r < 0.7 * a_c)
    w, p = d["weight"][sel], d["p"][sel]
    sw, swp, swp2 = (comm.allreduce(float(np.sum(x)), op=MPI.SUM) for x in (w, w * p, w * p * p))
    if sw <= 0:
        return math.inf
    mean = swp / sw
    return math.sqrt(max(swp2 / sw - mean * mean, 0.0)) / mean if mean > 0 else math.inf


class _SubRecord:
    """Minimal stand-in for :class:`tribofx.output.RunRecord` for the runs of a study."""

    def __init__(self):
        self.data = {"newton_iterations": [], "results": {}}
        self.profile = None

    def result(self, key, value, unit="-"):
        self.data["results"][key] = {"value": value, "unit": unit}


def ball_critical_step(v, t0, lo, hi, steps=5, iters=4, growth_tol=2.0, comm=MPI.COMM_WORLD):
    """Largest stable explicit Δt (s) of ``wear-ball-flat`` from a developed scar (bisection).

    The implicit scheme (``v["dt"]``) runs to ``t0`` on the mesh of ``v``; its
    state is copied into an explicit stepper on the same mesh, which takes one
    step of Δt and then ``steps`` more.  Wear evens out the pressure (the
    continuous problem is dissipative): an unstable Δt amplifies the highest
    mode geometrically, a stable one leaves the pressure nonuniformity
    (:func:`pressure_nonuniformity`) near its value after the first step.  The
    first step is the reference, not the state at t0: the implicit state is not
    on the explicit scheme's path, and its first step jumps to that path's
    nonuniformity whatever Δt (on a scar the implicit scheme has made very even,
    e.g. 7.5e-4 with the chapter's §5.2 element size, the jump alone is a factor
    of about 25).  Δt counts as stable iff the nonuniformity after the ``steps`` steps is
    at most ``growth_tol`` times the one after the first and no step fails
    (Newton divergence, force not reached, inverted mesh).  Bisection on log Δt
    in [lo, hi] (lo stable, hi unstable, both checked).  Returns ``(dt_cr,
    probe)``, ``probe`` the list of (Δt, nonuniformity ratio).
    """
    rec = _SubRecord()
    implicit = WearBallCase.run({**v, "scheme": "implicit"}, rec, comm=comm, t_stop=t0)
    start = implicit.state()
    stepper = WearBallCase.build({**v, "scheme": "explicit"}, comm=comm)
    if not np.array_equal(stepper.wear.body.mesh.geometry.x, implicit.wear.body.mesh.geometry.x):
        raise RuntimeError("rebuilt mesh differs from the implicit run's: cannot restore its state")
    probe = []
    growth = growth_probe(stepper, start, steps,
                          lambda: pressure_nonuniformity(stepper.wear.contact), probe, settle=1)
    return bisect_critical_step(growth, lo, hi, iters, tol=growth_tol, probe=probe), probe


def _study_run(v, n, scheme, dt, verbose=False):
    """One run of a study; returns (stepper, dict with status, profiles, costs)."""
    over = {**v, "study": "none", "scheme": scheme, "dt": dt}
    if scheme == "explicit":
        over["max_cuts"] = 0  # at its nominal Δt: a failure is the instability
    sub = _SubRecord()
    t0 = time.perf_counter()
    status = "ok"
    try:
        prob = WearPinCase.run(over, sub, n=n, verbose=verbose)
    except NewtonDivergence as err:
        status = f"failed: {type(err).__name__}: {err}"[:200]
        prob = getattr(err, "problem", None)
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


def run_dt_study(v, record, ns, dts, progress=None, verbose=False):
    """``study=dt`` of ``wear-pin`` on the n × n meshes ``ns`` for the time steps ``dts``.

    Records ``study_dt``, ``study_error_explicit`` and ``study_error_implicit``
    ({"n×n": [error per Δt, None if the run failed]}, mm, Euclidean norm of the
    final worn contact-node positions minus the reference), the max-norm
    counterparts ``study_maxerror_*``, ``study_unstable_*`` and ``study_status_*``
    flags, checkerboard amplitudes, costs and ``study_dt_cr`` (explicit critical
    step per mesh, None if not computed or not bracketed).  Returns the reference
    run's stepper of the last mesh; ``record.profile`` holds what
    :func:`tribofx.plots.wear.plot_dt_study` needs.
    """
    T = v["T"]
    ref_dt = v["study_ref_dt"]
    res = {key: {} for key in ("error_explicit", "error_implicit", "maxerror_explicit",
                               "maxerror_implicit", "unstable_explicit", "unstable_implicit",
                               "status_explicit", "status_implicit", "oscillation_explicit",
                               "oscillation_implicit", "checkerboard_explicit",
                               "checkerboard_implicit", "wall_time_explicit",
                               "wall_time_implicit", "newton_explicit", "newton_implicit",
                               "dt_cr", "reference_wall_time", "reference_correction",
                               "checkerboard_reference")}
    plots = {"study": "dt", "dts": list(dts), "E": v["E"], "T": T, "meshes": {}}
    prob_ref = None
    for n in ns:
        key = f"{n}x{n}"
        t0 = time.perf_counter()
        prob_ref, ref = _study_run(v, n, "implicit", ref_dt, verbose)
        if not ref["status"] == "ok":
            raise NewtonDivergence(f"study reference run ({key}, Δt = {ref_dt} s) "
                                   f"{ref['status']}")
        p_ref = ref["final_profile"]
        correction = 0.0
        if v["study_ref"] == "richardson":
            _, coarse = _study_run(v, n, "implicit", 2 * ref_dt, verbose)
            if not coarse["status"] == "ok":
                raise NewtonDivergence(f"study reference run ({key}, Δt = {2 * ref_dt} s) "
                                       f"{coarse['status']}")
            correction = float(np.linalg.norm(p_ref - coarse["final_profile"]))
            p_ref = 2 * p_ref - coarse["final_profile"]
        res["reference_wall_time"][key] = time.perf_counter() - t0
        res["reference_correction"][key] = correction
        res["checkerboard_reference"][key] = ref["checkerboard"]
        dt_cr = None
        if v["study_critical"]:
            try:
                dt_cr = pin_critical_step(v, n, lo=0.01, hi=1e4)[0]
            except (ValueError, NewtonDivergence):
                dt_cr = None
        res["dt_cr"][key] = dt_cr
        runs = {"reference": {"dt": ref_dt, "profiles": ref["profiles"],
                              "final_profile": p_ref}}
        for scheme in ("explicit", "implicit"):
            for name in ("error", "maxerror", "unstable", "oscillation", "status", "checkerboard",
                         "wall_time", "newton"):
                res[f"{name}_{scheme}"][key] = []
            for dt in dts:
                _, r = _study_run(v, n, scheme, dt, verbose)
                ok = r["status"] == "ok"
                if ok:
                    diff = r["final_profile"] - p_ref
                    err = float(np.linalg.norm(diff))
                    maxerr = float(np.max(np.linalg.norm(diff, axis=1)))
                    osc = oscillation_ratio(diff[:, 1])
                else:
                    err = maxerr = osc = None
                res[f"error_{scheme}"][key].append(err)
                res[f"maxerror_{scheme}"][key].append(maxerr)
                res[f"unstable_{scheme}"][key].append(
                    bool(not ok or osc > OSCILLATION_TOL
                         or (scheme == "explicit" and dt_cr is not None and dt > dt_cr)))
                res[f"oscillation_{scheme}"][key].append(osc)
                res[f"status_{scheme}"][key].append(r["status"])
                res[f"checkerboard_{scheme}"][key].append(r["checkerboard"])
                res[f"wall_time_{scheme}"][key].append(r["wall_time_s"])
                res[f"newton_{scheme}"][key].append(r["newton_iterations"])
                runs[(scheme, dt)] = {"profiles": r["profiles"], "ok": ok}
                if progress is not None:
                    progress.update(1)
        plots["meshes"][key] = {"runs": runs, "dt_cr": dt_cr,
                                "error_explicit": res["error_explicit"][key],
                                "error_implicit": res["error_implicit"][key],
                                "unstable_explicit": res["unstable_explicit"][key],
                                "unstable_implicit": res["unstable_implicit"][key]}
    record.result("study_dt", list(dts), "s")
    units = {"error": "mm (Euclidean norm over the contact nodes)",
             "maxerror": "mm (max nodal distance)", "unstable": "-", "status": "-",
             "oscillation": "-",
             "checkerboard": "mm", "wall_time": "s", "newton": "-", "dt_cr": "s",
             "reference": "s", "checkerboard_reference": "mm"}
    for name, val in res.items():
        record.result(f"study_{name}", val, units.get(name.split("_")[0], units.get(name, "-")))
    ref_txt = (f"implicit, Δt = {ref_dt:g} s" if v["study_ref"] == "fine" else
               f"Richardson 2 p({ref_dt:g} s) − p({2 * ref_dt:g} s), implicit")
    record.result("study_reference", ref_txt, "-")
    record.result("study_unstable_criterion",
                  "failed at nominal Δt, or oscillation ratio of the error > "
                  f"{OSCILLATION_TOL:g}, or explicit with Δt > study_dt_cr", "-")
    plots["reference"] = ref_txt
    if prob_ref is not None and prob_ref.comm.rank == 0:
        record.profile = plots
    return prob_ref
