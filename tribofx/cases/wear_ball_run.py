"""The slow-time run of the ball worn by a flat (chapter §5.2): measures, histories, report.

:class:`BallWearRun` is a base class of :class:`tribofx.cases.wear_ball.WearBallCase`:
the run through :class:`tribofx.slow_run.SlowRun` with the force held by the
case's control, the scar measures (contact and scar radius, pressure ratio,
approach) on the symmetry line, the late-time exponent and the plots.
"""

import math
import time

import numpy as np
from mpi4py import MPI

from ..references import hertz, rigid_cap_radius
from ..slow_run import SlowRun, wear_fields
from ..stepper import nominal_steps
from . import slow_time

__all__ = ["MODEL_FRACTION", "BallWearRun"]

MODEL_FRACTION = 0.5  # the quarter ball carries half of the contact (and of the wear)


class BallWearRun:
    """The slow-time run of the ball worn by a flat (chapter §5.2): measures, histories, report."""

    @staticmethod
    def progress_total(v):
        """Return the steps the progress bar counts: nominal steps of dt to T (by time)."""
        return nominal_steps(v["T"], v["dt"])

    @staticmethod
    def measures(stepper, v):
        """Contact radius, flat-scar radius, pressure ratio, max depth, full-ball worn volume."""
        wear = stepper.wear
        comm = wear.body.mesh.comm
        d = wear.nodal_shape_data()
        area = comm.allreduce(float(np.sum(d["weight"][d["active"]])), op=MPI.SUM)
        a_c = math.sqrt(area / (MODEL_FRACTION * math.pi))
        h = comm.allreduce(float(np.max(d["depth"], initial=0.0)), op=MPI.MAX)
        a_s = math.sqrt(max(2 * v["R"] * h - h * h, 0.0))
        r = np.linalg.norm(d["x"][:, :2], axis=1)
        inner = d["active"] & (r < 0.7 * a_c)
        pmax = comm.allreduce(float(np.max(d["p"][inner], initial=0.0)), op=MPI.MAX)
        pmin = comm.allreduce(float(np.min(d["p"][inner], initial=np.inf)), op=MPI.MIN)
        return {"contact_radius": a_c, "scar_radius": a_s, "max_wear_depth": h,
                "pressure_ratio": pmax / pmin if pmin > 0 else math.inf,
                "wear_volume": wear.worn_volume() / MODEL_FRACTION,
                "wear_rate_integral": wear.wear_rate_integral() / MODEL_FRACTION}

    @classmethod
    def symmetry_line(cls, stepper, v):
        """Worn and deformed contact boundary along y = 0 near the contact, on rank 0 (else None).

        Returns a dict of arrays sorted by X̂_x: X_worn, x (deformed), p (pressure).
        """
        d = stepper.wear.gather_shape()
        if d is None:
            return None
        r_fine = cls.mesh_sizes(v)[2]
        sel = (np.abs(d["X_hat"][:, 1]) < 1e-9 * v["R"]) & (d["X_hat"][:, 2] < 0.5 * v["R"]) \
            & (np.abs(d["X_hat"][:, 0]) <= 2 * r_fine)
        return {"X_worn": d["X_worn"][sel], "x": d["x"][sel], "p": d["p"][sel]}

    @staticmethod
    def contact_plane(stepper):
        """(x, y, p) of all contact-surface nodes within the active zone, on rank 0 (else None)."""
        d = stepper.wear.gather_shape()
        if d is None:
            return None
        a = d["active"]
        return np.column_stack([d["x"][a, 0], d["x"][a, 1], d["p"][a]])

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, on_step=None, comm=MPI.COMM_WORLD,
            t_stop=None, checkpoint=None, resume=False):
        """Integrate the wear of the ball from t = 0 to T; record per-step histories.

        ``on_step(stepper, report)``, if given, is called after every accepted step;
        ``t_stop`` < T ends the run early (on the mesh built for T).  ``checkpoint``:
        directory of the per-step checkpoint (state and histories); ``resume``:
        continue from it (:mod:`tribofx.restart`).  Returns the stepper.
        """
        t_wall = time.perf_counter()
        stepper = cls.build(v, comm=comm, checkpoint=checkpoint)
        stepper.verbose = stepper.control.inner.verbose = verbose
        record.result("shape_unknown_fraction", stepper.shape_unknown_fraction(), "-")
        record.stepper = stepper
        comm = stepper.comm
        record.result("h_contact_zone", stepper.h_fine, "mm")
        keys = ("time", "dt", "approach", "wear_volume", "max_wear_depth", "contact_radius",
                "scar_radius", "pressure_ratio", "newton_iterations", "wear_rate_integral",
                "error_estimate", "rejected")
        # the worn shape (warp by w), the deformation (by u) and the contact pressure at
        # every step (ParaView time series)
        sr = SlowRun(stepper, v, record, keys, cls.vtx_fields(stepper), resume)
        h = sr.history
        state = h.setdefault("state", {"profiles": [], "initial_plane": None})
        residuals = h.setdefault("newton_residuals", [])
        residuals_all = h.setdefault("newton_residuals_all", [])
        record.data["newton_residuals"] = residuals
        record.data["newton_residuals_all"] = residuals_all
        offset = stepper.wear.contact.counterpart.offset

        def log(t, its, dt, error=None, rejected=0):
            m = cls.measures(stepper, v)
            sr.log(its, (("time", t), ("dt", dt), ("newton_iterations", its),
                         ("approach", float(offset.value[2])), *m.items(),
                         ("error_estimate", error), ("rejected", rejected)))
            line = cls.symmetry_line(stepper, v)
            if comm.rank == 0:
                state["profiles"].append((t, line["X_worn"][:, [0, 2]].tolist()))

        def step_done(st, rep):
            log(st.t, rep.iterations, rep.dt, rep.error, rep.rejected)
            residuals.append([float(x) for x in rep.reports[-1].residuals])
            residuals_all.append([[float(x) for x in r.residuals] for r in rep.reports])
            if on_step is not None:
                on_step(st, rep)

        if not resume:
            reports = stepper.control.solve(guess=hertz(v["F"], v["R"], v["E"], v["nu"]).delta)
            plane = cls.contact_plane(stepper)
            state["initial_plane"] = None if plane is None else plane.tolist()
            log(0.0, int(sum(r.iterations for r in reports)), 0.0)
        T = v["T"] if t_stop is None else min(t_stop, v["T"])
        sr.run(T, v["dt"], step_done, progress, report=lambda: cls._report(
            stepper, v, record, sr.hist, state, time.perf_counter() - t_wall),
            **slow_time.control(v))
        return stepper

    @staticmethod
    def late_time_exponent(time_s, radius, V, t_min):
        """Least-squares slope of log a against log s = V t over the steps with t ≥ t_min."""
        t = np.asarray(time_s, dtype=float)
        a = np.asarray(radius, dtype=float)
        sel = t >= t_min
        if np.count_nonzero(sel) < 2:
            return math.nan
        return float(np.polyfit(np.log(V * t[sel]), np.log(a[sel]), 1)[0])

    @classmethod
    def _report(cls, stepper, v, record, hist, state, wall):
        units = {"time": "s", "dt": "s", "approach": "mm (flat position)",
                 "wear_volume": "mm^3 (full ball)",
                 "max_wear_depth": "mm", "contact_radius": "mm", "scar_radius": "mm",
                 "pressure_ratio": "-", "newton_iterations": "-",
                 "wear_rate_integral": "mm^3/s (full ball)",
                 "error_estimate": "mm (per step, error control)", "rejected": "-"}
        for key, vals in hist.items():
            record.result(key, vals, units[key])
        record.result("rejected_steps", int(sum(hist["rejected"])), "-")
        record.result("force_fallbacks", getattr(stepper.control, "fallbacks", 0), "-")
        record.result("wall_time", stepper.comm.allreduce(wall, op=MPI.MAX), "s")
        record.result("steps", len(hist["time"]) - 1, "-")
        s = v["V"] * np.asarray(hist["time"])
        record.result("rigid_cap_radius", rigid_cap_radius(v["k"], v["F"], v["R"], s).tolist(),
                      "mm")
        record.result("archard_volume", (v["k"] * v["F"] * s).tolist(), "mm^3 (k F V t)")
        for key in ("contact_radius", "scar_radius"):
            record.result(f"{key}_exponent_late",
                          cls.late_time_exponent(hist["time"], hist[key], v["V"], 0.4 * v["T"]),
                          "-")
        line = cls.symmetry_line(stepper, v)
        plane = cls.contact_plane(stepper)
        if line is not None:
            record.result("final_profile", line["X_worn"][:, [0, 2]].tolist(),
                          "mm ([x, z] of the worn boundary on y = 0)")
            record.result("final_profile_deformed", line["x"][:, [0, 2]].tolist(), "mm")
            record.result("final_pressure_symmetry_line", line["p"].tolist(), "MPa")
            initial = state["initial_plane"]
            record.profile = {**hist, "profiles": state["profiles"],
                              "initial_plane": None if initial is None else np.asarray(initial),
                              "final_plane": plane,
                              "scheme": v["scheme"], "dt": v["dt"], "R": v["R"], "k": v["k"],
                              "F": v["F"], "V": v["V"]}

    @staticmethod
    def vtx_fields(stepper):
        """Fields for ParaView: displacement and shape change (bulk), contact multiplier."""
        return wear_fields(stepper.wear)

    @staticmethod
    def plot(profile, outdir):
        """``pressure.png``, ``profiles.png`` and ``scar.png`` (:func:`tribofx.plots.wear`)."""
        from ..plots.wear import plot_wear_ball

        plot_wear_ball(profile, outdir)
