"""The slow-time run of the wear pin (chapter §4.4): histories, series, report, plots.

:class:`PinRun` is a base class of :class:`tribofx.cases.wear.WearPinCase`: the
run from t = 0 (or a checkpoint) to T through :class:`tribofx.slow_run.SlowRun`
(or the Δt study of :mod:`tribofx.cases.wear_dt_study`), the per-step measures
and the results.
"""

from ..params import InputError, number_list
from ..slow_run import SlowRun, wear_fields
from ..stepper import nominal_steps
from . import slow_time
from .wear_dt_study import run_dt_study

__all__ = ["PinRun"]


class PinRun:
    """The slow-time run of the wear pin (chapter §4.4): histories, series, report, plots."""

    @staticmethod
    def study_lists(v):
        """``(dts, mesh levels)`` of ``study=dt`` parsed from the comma-separated strings."""
        dts = number_list(v["study_dts"], "study_dts", allow_empty=True)
        levels = number_list(v["study_meshes"], "study_meshes", int, True) or [v["mesh"]]
        return dts, levels

    @staticmethod
    def study_schemes(v):
        """Schemes of ``study=dt`` (one-line error if unknown or none)."""
        schemes = [x.strip() for x in v["study_schemes"].split(",") if x.strip()]
        if not schemes or any(x not in ("explicit", "implicit", "bdf2") for x in schemes):
            raise InputError(f"study_schemes = {v['study_schemes']!r}: a comma-separated "
                             "list of explicit, implicit, bdf2")
        return list(dict.fromkeys(schemes))

    @classmethod
    def progress_total(cls, v):
        """Return the steps the progress bar counts: slow steps to T, or a Δt study's runs."""
        if v["study"] == "dt":
            dts, levels = cls.study_lists(v)
            return len(cls.study_schemes(v)) * len(dts) * len(levels)
        return nominal_steps(v["T"], cls.slow_step(v))

    @staticmethod
    def vtx_fields(stepper):
        """Fields for ParaView: displacement and shape change (bulk), contact multiplier."""
        return wear_fields(stepper.wear)

    @staticmethod
    def plot(profile, outdir):
        """Plot ``profiles.png``, ``wear.png`` (``study=dt``: ``error_vs_dt.png``, profiles)."""
        from ..plots.wear import plot_dt_study, plot_wear_pin

        if profile.get("study") == "dt":
            return plot_dt_study(profile, outdir)
        return plot_wear_pin(profile, outdir)

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, n=None, setup=None, checkpoint=None,
            resume=False):
        """Integrate the wear of the pin from t = 0 to T; record per-step histories.

        ``checkpoint``: directory of the per-step checkpoint (state and the
        histories so far); ``resume``: continue from it instead of t = 0.
        """
        if v["study"] == "dt":
            dts, levels = cls.study_lists(v)
            ns = [10 * 2**m for m in levels] if n is None else [n]
            return run_dt_study(cls, v, record, ns, dts, progress=progress, verbose=verbose)
        stepper, load = cls.build(v, n=n, setup=setup, checkpoint=checkpoint)
        stepper.verbose = verbose
        wear, contact = stepper.wear, stepper.wear.contact
        comm = wear.body.mesh.comm
        keys = ("time", "wear_volume", "max_wear_depth", "contact_radius",
                "newton_iterations", "wear_rate_integral", "dt", "error_estimate", "rejected")
        # the worn shape and the deformation at every step (ParaView time series)
        sr = SlowRun(stepper, v, record, keys,
                     {"displacement": [wear.body.u, wear.body.w]}, resume)
        h = sr.history
        profiles, ptimes = h.setdefault("profiles", []), h.setdefault("ptimes", [])
        if stepper.cycle is None:
            record.data["newton_residuals"] = h.setdefault("newton_residuals", [])

        def log(t, its, dt, error=None, rejected=0):
            area, _ = contact.measures()
            sr.log(its, (("time", t), ("dt", dt), ("wear_volume", wear.worn_volume()),
                         ("max_wear_depth", wear.max_depth()), ("contact_radius", area / 2),
                         ("newton_iterations", its),
                         ("wear_rate_integral", wear.wear_rate_integral()),
                         ("error_estimate", error), ("rejected", rejected)))
            s = wear.gather_shape()
            if comm.rank == 0:
                profiles.append(s["X_worn"].tolist())
                ptimes.append(t)

        def on_step(st, rep):
            log(st.t, rep.iterations, rep.dt, rep.error, rep.rejected)
            if st.cycle is None:
                record.data["newton_residuals"].append(
                    [float(x) for x in rep.reports[-1].residuals])

        if not resume:
            log(0.0, cls.load_up(stepper, load, v, verbose) + stepper.start(), 0.0)
        sr.run(v["T"], cls.slow_step(v), on_step, progress,
               report=lambda: cls._report(stepper, v, record, sr.hist, profiles, ptimes),
               **slow_time.control(v))
        return stepper

    @classmethod
    def _report(cls, stepper, v, record, hist, profiles, ptimes):
        units = {"time": "s", "wear_volume": "mm^3/mm", "max_wear_depth": "mm",
                 "contact_radius": "mm (half-width)", "newton_iterations": "-",
                 "wear_rate_integral": "mm^3/(mm*s)", "dt": "s",
                 "error_estimate": "mm (per step, error control)", "rejected": "-"}
        for key, vals in hist.items():
            record.result(key, vals, units[key])
        record.result("accepted_steps", len(hist["time"]) - 1, "-")
        record.result("rejected_steps", int(sum(hist["rejected"])), "-")
        d = stepper.wear.gather_shape()
        if d is not None:
            record.result("final_profile", d["X_worn"].tolist(), "mm (worn configuration)")
            record.result("final_profile_deformed", d["x"].tolist(), "mm (current)")
            record.result("final_pressure", d["p"].tolist(), "MPa")
            record.profile = {**hist, "profiles": profiles, "times": ptimes,
                              "scheme": v["scheme"], "dt": cls.slow_step(v)}
