"""The time steps of ``ehl-squeeze``: per-step measures, the run, its report and plots.

:class:`SqueezeRun` is a base class of :class:`tribofx.cases.ehl_squeeze.EHLSqueezeCase`
(which gives ``build``, ``fraction`` and ``extent``).
"""

import numpy as np

from ..references import squeeze_film_under_load, squeeze_resistance
from ..slow_run import SlowRun
from ..stepper import nominal_steps

__all__ = ["SqueezeRun"]


class SqueezeRun:
    """Per-step measures, the run from t = 0 (or a checkpoint) to T, the report."""

    @staticmethod
    def progress_total(v):
        """Time steps to T."""
        return nominal_steps(v["T"], v["dt"])

    @staticmethod
    def vtx_fields(stepper):
        """Displacement of the body; film pressure (on Γ_l)."""
        film = stepper.wear
        return {"displacement": [film.body.u], "pressure": [film.p]}

    @staticmethod
    def plot(profile, outdir):
        """``squeeze.png``: film and force against time; ``squeeze_profiles.png``."""
        from ..plots.film import plot_squeeze

        plot_squeeze(profile, outdir)

    @classmethod
    def measures(cls, film, v, y0):
        """One step's measures: film at the centre and its minimum, force, plane position."""
        dim = v["dim"]
        prof = film.profile(everywhere=True)
        r = np.linalg.norm(prof["X"][:, :dim - 1], axis=1)
        h_c = float(prof["h"][np.argmin(r)])
        force = float(film.force()[dim - 1]) / cls.fraction(v)
        return {"h_center": h_c, "h_min": film.min_film(), "force": force,
                "approach": float(film.plane.value[dim - 1]) - y0,
                "p_center": float(prof["p"][np.argmin(r)]),
                "content": film.content() / cls.fraction(v)}

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, checkpoint=None, resume=False):
        """Step the squeeze from t = 0 (or the checkpoint) to T; per-step records."""
        stepper = cls.build(v, checkpoint=checkpoint)
        stepper.verbose = verbose
        film, dim = stepper.wear, v["dim"]
        keys = ("time", "h_center", "h_min", "force", "approach", "p_center", "content",
                "newton_iterations", "force_rigid", "h_center_rigid")
        sr = SlowRun(stepper, v, record, keys, {"displacement": [film.body.u]}, resume)
        y0 = sr.history.setdefault("y0", float(film.plane.value[dim - 1]))
        R, mu, L = v["R"], v["mu"], cls.extent(v)

        def log(t, its):
            m = cls.measures(film, v, y0)
            h_rigid = v["h_start"] - m["approach"]     # the rigid body's gap at the plane
            m["force_rigid"] = (squeeze_resistance(dim, R, mu, h_rigid, L) * v["V"]
                                if v["control"] == "speed" else v["F"])
            m["h_center_rigid"] = (h_rigid if v["control"] == "speed" else float(
                squeeze_film_under_load(dim, R, mu, v["F"], v["h_start"], [t], L)[0]))
            sr.log(its, dict(time=t, newton_iterations=its, **m))

        if not resume:
            log(0.0, 0)
        sr.run(v["T"], v["dt"], lambda st, rep: log(st.t, rep.iterations), progress,
               report=lambda: cls._report(film, record, sr.hist))
        return stepper

    @staticmethod
    def _report(film, record, hist):
        units = {"time": "s", "h_center": "mm", "h_min": "mm", "force": "N (N/mm in 2D)",
                 "approach": "mm", "p_center": "MPa", "newton_iterations": "-",
                 "content": "mm² per unit length (2D), mm³ (3D): the fluid in the film",
                 "force_rigid": "N (N/mm in 2D)", "h_center_rigid": "mm"}
        for key, vals in hist.items():
            record.result(key, vals, units[key])
        prof = film.profile()
        if prof is not None:
            r = np.linalg.norm(prof["X"][:, :-1], axis=1)    # distance from the axis
            record.result("final_film", np.column_stack([r, prof["h"], prof["p"]]).tolist(),
                          "mm (radius), mm (h), MPa (p) per node of the film")
            record.profile = {**hist, "X": prof["X"].tolist(), "h": prof["h"].tolist(),
                              "p": prof["p"].tolist()}
