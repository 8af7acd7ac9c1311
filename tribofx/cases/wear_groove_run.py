"""The slow-time run of the groove worn by a ball (chapter §5.3): histories and report.

:class:`GrooveRun` is a base class of
:class:`tribofx.cases.wear_groove.WearBallHalfspaceCase`: the run through
:class:`tribofx.slow_run.SlowRun`, the groove's measures per step and the results.
"""

import time

import numpy as np
from mpi4py import MPI

from ..slow_run import SlowRun
from ..stepper import nominal_steps
from . import slow_time

__all__ = ["GrooveRun", "surface_data"]


def surface_data(contact, root=None):
    """Top-surface nodes: initial (x, y), nominal pressure p = −λ, active (λ < 0).

    Owned nodes (``root=None``) or all nodes gathered on rank ``root`` (None elsewhere).
    """
    n = contact.Q.dofmap.index_map.size_local
    lam = contact.lam_n.x.array[:n]
    d = {"X": contact.X_sub[:n, :2], "p": np.maximum(-lam, 0.0), "active": lam < 0}
    if root is None:
        return d
    parts = contact.body.mesh.comm.gather(d, root=root)
    return None if parts is None else {k: np.concatenate([p[k] for p in parts]) for k in d}


class GrooveRun:
    """The slow-time run of the groove worn by a ball (chapter §5.3): histories and report."""

    @staticmethod
    def progress_total(v):
        """Return the steps the progress bar counts: nominal steps of dt to T (by time)."""
        return nominal_steps(v["T"], v["dt"])

    @staticmethod
    def vtx_fields(stepper):
        """Displacement and 3D shape change (block), contact multiplier."""
        body = stepper.wear.body
        return {"displacement": [body.u, body.w], "contact": [stepper.wear.contact.lam_n]}

    @staticmethod
    def plot(profile, outdir):
        """Groove profiles, pressure maps at t = 0 and final, pressure across the groove."""
        from ..plots.groove import plot_groove

        plot_groove(profile, outdir)

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, checkpoint=None, resume=False):
        """Integrate the groove from t = 0 to T; record per-step histories.

        ``checkpoint``: directory of the per-step checkpoint (state and histories);
        ``resume``: continue from it (:mod:`tribofx.restart`).
        """
        v = cls.resolved(v)
        for key in cls.REGIMES[v["regime"]]:  # record the regime defaults actually used
            record.data["parameters"][key]["value"] = v[key]
        t_start = time.perf_counter()
        stepper, info = cls.build(v, checkpoint=checkpoint)
        stepper.verbose = verbose
        wear, contact = stepper.wear, stepper.wear.contact
        comm = wear.body.mesh.comm
        n = {"u": wear.body.u, "lambda": contact.lam_n, "psi": wear.w2, "zeta": wear.zeta}
        n = {key: f.function_space.dofmap.index_map.size_global
             * f.function_space.dofmap.index_map_bs for key, f in n.items()}
        record.result("dofs", n, "-")
        record.result("psi_fraction", stepper.shape_unknown_fraction(), "- (share of Ψ and ζ)")
        record.result("hertz", info, "mm, MPa")
        # the groove (warp by w), the deformation (by u) and the contact pressure at every
        # step (ParaView time series)
        sr = SlowRun(stepper, v, record, (
            "time", "wear_volume", "max_wear_depth", "contact_radius", "contact_half_length",
            "newton_iterations", "averaged_rate", "max_pressure", "dt", "error_estimate",
            "rejected"),
            cls.vtx_fields(stepper), resume)
        record.data["num_dofs"] = sum(n.values())
        h, hist = sr.history, sr.hist
        prof = h.setdefault("prof", {"times": [], "profiles": [], "maps": []})
        residuals = record.data["newton_residuals"] = h.setdefault("newton_residuals", [])

        def log(t, its, dt, error=None, rejected=0):
            d = surface_data(contact)
            X = d["X"][d["active"]]
            ext = [comm.allreduce(float(np.max(c, initial=0.0)), op=MPI.MAX)
                   for c in (np.abs(X[:, 0]), X[:, 1], d["p"])]
            lp = wear.line_profile()
            sr.log(its, zip(hist, (t, 2 * wear.groove_area(), float(lp["depth"].max()),
                                   ext[1], ext[0], its, 2 * wear.averaged_rate_integral(),
                                   ext[2], dt, error, rejected)))
            g = surface_data(contact, root=0)
            if g is not None:
                prof["times"].append(t)
                prof["profiles"].append(lp["worn"].tolist())
                prof["maps"].append(np.column_stack([g["X"], g["p"]]).tolist())

        def on_step(st, rep):
            log(st.t, rep.iterations, rep.dt, rep.error, rep.rejected)
            residuals.append([float(x) for x in rep.reports[0].residuals])

        if not resume:
            log(0.0, cls.initial_contact(stepper, info, verbose).iterations, 0.0)
        sr.run(v["T"], v["dt"], on_step, progress, report=lambda: cls._report(
            stepper, v, record, hist, prof, time.perf_counter() - t_start),
            **slow_time.control(v))
        return stepper

    @staticmethod
    def _report(stepper, v, record, hist, prof, wall):
        units = {"time": "s", "wear_volume": "mm^3/mm (full groove cross-section area)",
                 "max_wear_depth": "mm", "contact_radius": "mm (half-width across the groove)",
                 "contact_half_length": "mm (along the sliding direction)",
                 "newton_iterations": "-", "averaged_rate": "mm^3/(mm*s) ((2/L) ∫ k p v dA)",
                 "max_pressure": "MPa (nominal)", "dt": "s",
                 "error_estimate": "mm (per step, error control)", "rejected": "-"}
        for key, vals in hist.items():
            record.result(key, vals, units[key])
        record.result("accepted_steps", len(hist["time"]) - 1, "-")
        record.result("rejected_steps", int(sum(hist["rejected"])), "-")
        wear = stepper.wear
        w = wear.line_profile()["worn"]
        record.result("final_profile", np.vstack([w[::-1] * [-1, 1], w[1:]]).tolist(),
                      "mm (worn cross-section (y, z), both halves)")
        y, pint = wear.averaged_pressure()
        record.result("final_pressure_integral", np.column_stack([y, pint]).tolist(),
                      "mm, N/mm (y, ∫ p dx)")
        record.result("wall_time_solve", wall, "s")
        d = surface_data(wear.contact, root=0)
        if d is None:
            return
        on = np.abs(d["X"][:, 0]) < 1e-9
        o = np.argsort(d["X"][on, 1])
        px0 = np.column_stack([d["X"][on, 1][o], d["p"][on][o]]).tolist()
        record.result("final_pressure_x0", px0, "mm, MPa (y, p at x = 0)")
        record.profile = {**hist, **prof, "scheme": v["scheme"], "graded": v["graded"],
                          "R": v["R"], "pressure_x0": px0,
                          "pressure_integral": np.column_stack([y, pint]).tolist()}
