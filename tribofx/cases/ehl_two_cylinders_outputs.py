"""Outputs of ``ehl-two-cylinders``: the film's measures per load, the report, the plot.

:class:`TwoCylinderOutputs` is a base class of
:class:`tribofx.cases.ehl_two_cylinders.EHLTwoCylindersCase`.
"""

import numpy as np

from ..interfaces import TwoBodyFilm
from ..references import rigid_clearance

__all__ = ["TwoCylinderOutputs"]


class TwoCylinderOutputs:
    """Per-load measures, the results at the last load, VTX fields and the plot."""

    @staticmethod
    def measures(run, v):
        """Return the film at the current load: h at x = 0, h_min, p_max, forces, profile."""
        film = run["film"]
        prof = film.profile(everywhere=True)
        X = prof["X"][:, 0]
        m = {"W": float(run["sign"] * film.force()[1]), "h_central": float(
            prof["h"][np.argmin(np.abs(X))]), "h_min": float(prof["h"].min()),
            "p_max": float(prof["p"].max()), "x": prof["x"][:, 0], "h": prof["h"],
            "p": prof["p"]}
        if isinstance(film, TwoBodyFilm):
            on1, on2 = film.forces()
        else:
            on = film.force()
            on1, on2 = (on, -on) if run["sign"] > 0 else (-on, on)
        m["friction_force_upper"], m["friction_force_lower"] = float(on1[0]), float(on2[0])
        m["approach"] = float(run["lift"].value[1]) * (1 if run["sign"] > 0 else -1)
        return m

    @staticmethod
    def report(run, v, record, steps, ref):
        """Results at the last converged load; profiles for the plot."""
        if not steps:
            return
        m = steps[-1]
        units = {"W": "N/mm", "h_central": "mm", "h_min": "mm", "p_max": "MPa",
                 "friction_force_upper": "N/mm", "friction_force_lower": "N/mm",
                 "approach": "mm"}
        for key, unit in units.items():
            record.result("normal_load" if key == "W" else key, m[key], unit)
        u_m = 0.5 * (v["U1"] + v["U2"])
        record.result("hertz_half_width", ref.a, "mm")
        record.result("hertz_p_max", ref.p0, "MPa")
        record.result("rigid_film_martin", rigid_clearance(m["W"], v["mu"], 2 * u_m,
                                                           ref.R_star), "mm")
        if run["film"].sub.comm.rank == 0:
            record.profile = {"steps": [{k: s[k] for k in ("W", "x", "p", "h")}
                                        for s in steps]}

    @staticmethod
    def vtx_fields(run):
        """Displacements of the elastic bodies (one file per mesh)."""
        return {b.name: [b.u] for b in run["bodies"].values()}

    @staticmethod
    def plot(profile, outdir):
        """``profiles.png``: p(x) and h(x) per load step."""
        from ..plots.film import plot_film_profiles

        plot_film_profiles(profile["steps"], outdir / "profiles.png",
                           "two elastic cylinders: film per load step")
