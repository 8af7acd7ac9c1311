"""Outputs of the coated layer under a rigid cylinder (chapter §8.2): measures, results, plots.

:class:`CylinderOutputs` is a base class of
:class:`tribofx.cases.ehl.EHLCylinderLayerCase`: h_min, h_central, p_max (and where),
the load, the friction coefficient and the clearance of a converged film; the
per-load and per-speed results; the film profiles and the friction against μU.
"""

import math

import numpy as np
from mpi4py import MPI

from ..positions import parabolic_vertex

__all__ = ["CylinderOutputs"]


class CylinderOutputs:
    """Outputs of the coated layer under a rigid cylinder (chapter §8.2)."""

    @classmethod
    def measures(cls, run, v):
        """Film measures on all ranks: h_min, h_central, p_max, W, friction, clearance."""
        film, prof, f = run[1], run[1].profile(everywhere=True), run[1].force()
        xx = prof["y"][:, 0] if v["model"] == "finite" else prof["X"][:, 0]
        return {"h_min": float(prof["h"].min()), "h_central": float(np.interp(0, xx, prof["h"])),
                "p_max": float(prof["p"].max()), "x_p_max": parabolic_vertex(xx, prof["p"]),
                "profile": {"x": xx, "p": prof["p"], "h": prof["h"]}, "W": -float(f[1]),
                "tangential_force": float(f[0]),
                "friction_coefficient": abs(f[0] / f[1]) if f[1] < 0 else math.nan,
                "clearance": float(film.counterpart.offset.value[1])}

    @classmethod
    def _report(cls, steps, speed, profiles, v, record, prefix):
        keys = ("W", "h_min", "h_central", "p_max", "friction_coefficient", "clearance")
        if steps:
            for k in keys[1:5]:
                record.result(prefix + k, steps[-1][k], cls.UNITS[k])
            record.result(prefix + "W_reached", steps[-1]["W"], "N/mm")
        for k in keys:
            record.result(f"{prefix}steps_{k}", [m[k] for m in steps], cls.UNITS[k])
        for m in speed:
            m["mu_U"] = v["mu"] * m["U"]
        if len(speed) > 1:
            for k in ("U", "mu_U", "friction_coefficient", "h_min", "p_max", "clearance"):
                record.result(f"{prefix}speed_{k}", [m[k] for m in speed], cls.UNITS[k])
        if MPI.COMM_WORLD.rank == 0:
            prof = record.profile or {"variants": {}}
            prof["variants"][prefix[:-1] or v["model"]] = {
                "label": prefix[:-1] or v["model"], "steps": profiles,
                "speed": ([m["mu_U"] for m in speed], [m["friction_coefficient"] for m in speed])}
            record.profile = prof

    @classmethod
    def progress_total(cls, v):
        """Points the progress bar counts: the loads of every variant."""
        return v["steps"] * (1 if v["compare"] == "none" else len(cls.COMPARE[v["compare"]]))

    @staticmethod
    def vtx_fields(run):
        """Displacement (bulk) and film pressure (Γ_l submesh)."""
        layer, film, _ = run
        return {"displacement": [layer.u], "pressure": [film.p]}

    @classmethod
    def plot(cls, profile, outdir):
        """``profiles.png`` (or the ``compare`` plot) and ``friction_vs_speed.png``."""
        from ..plots import plot_film_profiles, plot_friction_vs_speed

        variants = profile["variants"]
        if "compare" in profile:
            title = ("coated layer: finite deformation vs geometrically linear"
                     if profile["compare"] == "linear" else "coated layer: lubrication surface S_α")
            plot_film_profiles(None, outdir / cls.COMPARE_PLOT[profile["compare"]], title,
                               variants)
            return
        (name, var), = variants.items()
        plot_film_profiles(var["steps"], outdir / "profiles.png",
                           f"coated layer, model = {name}")
        if len(var["speed"][0]) > 1:
            plot_friction_vs_speed({None: var["speed"]}, outdir / "friction_vs_speed.png")
