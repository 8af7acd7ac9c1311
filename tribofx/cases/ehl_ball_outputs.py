"""Outputs of the soft-EHL ball (chapter §8.3): measures of a converged film, results, plots.

:class:`BallOutputs` is a base class of :class:`tribofx.cases.ehl_ball.EHLBallCase`
(see its module docstring for the measures: film thickness on the centre line,
h_min and where, p_max, the friction coefficients on the ball and on the plane,
the film's node-to-node oscillation).

``film_oscillation``: the node-to-node zig-zag of h along the centre line where
p > p_max/2 (:func:`tribofx.positions.oscillation_indicator`, δ for a zig-zag
±δ h̄).  Above ``FILM_OSCILLATION_TOL`` the run warns: the mesh does not resolve
the film, whose numbers are then not the continuum's to better than about that
fraction.  Measured at W = 3 N, U = 10 m/s: 0.048, 0.016, 0.009 on ``mesh=0, 1,
2`` (3k, 12k, 47k unknowns); at the chapter's 40 N and 0.078 N/m on ``mesh=2
edge_refine=1`` (64k) 0.062 (full), 0.063 (no shear), 0.057 (linear) — the
zig-zag visible in Fig. 26 (``docs/figures/ehl_ball_fig26_W40.png``), so the
variants' differences there are known to about ±6 %; coarser still, the spurious
dip described above.

Friction on the ball and on the plane.  The film is in equilibrium, so in the
finite model the x-force of the film on the plane is minus that on the ball
up to the thin-film approximation where the film is not thin against its
slope: the shear on the cap's steep flanks, ∫ (shear)(j − ds_S/dS) dS, exactly
the difference of the two forces on the discrete solution (tested).  The
geometrically linear model's traction −pN on the undeformed sphere (a/R = 0.5
at 40 N) leaves out the pressure on the displacement's slope, ∫ p ∂ₓ(ν·u) ds_S,
and applies its shear on the reference area: at 40 N, μU = 39 N/m, the two
parts are 1.40 and 1.46 N of the ball's 15.0 N, the finite model's flank 0.96 N
of 12.5.  The plane's friction coefficient is what a rig measures on the
counterpart and what the classical EHL friction computes (the shear stress of
the film at a flat wall), so models are compared by it: at 40 N finite and
linear differ by 1.4–5.3 % on the plane, 19–26 % on the ball (Fig. 27,
``benchmarks/chapter_ehl_ball.py``).
"""

import math

import numpy as np

from ..positions import oscillation_indicator, paraboloid_vertex
from .ehl_ball_paths import Z

__all__ = ["BallOutputs"]


class BallOutputs:
    """Outputs of the soft-EHL ball (chapter §8.3): measures of a converged film, results, plots."""

    @staticmethod
    def film_oscillation(h_axis, p_axis):
        """Zig-zag of h on the centre line where p > p_max/2 (see the module docstring)."""
        p_axis = np.asarray(p_axis)
        return oscillation_indicator(np.asarray(h_axis), p_axis, 0.5 * p_axis.max(initial=0))

    @classmethod
    def measures(cls, run, v):
        """h_central, h_min (x, y), p_max, W, friction coefficients, clearance (all ranks)."""
        film = run[1]
        prof, f, fc = film.profile(everywhere=True), film.force(), film.couette_force()
        f_plane = film.counter_force()
        xy = (prof["x"] if v["model"] == "finite" else prof["X"])[:, :2]
        on = np.abs(prof["X"][:, 1]) < 1e-9 * v["R"]          # the symmetry line y = 0
        order = np.argsort(xy[on, 0])
        xx, hh, pp = xy[on, 0][order], prof["h"][on][order], prof["p"][on][order]
        i = int(np.argmin(prof["h"]))
        # where h is least, between nodes (tribofx.positions); y ≥ 0 in the quarter model
        x_min, y_min = paraboloid_vertex(xy, prof["h"], "min")
        per_load = 1 / float(f[Z]) if f[Z] > 0 else math.nan
        return {"h_central": float(np.interp(0.0, xx, hh)), "h_min": float(prof["h"][i]),
                "film_oscillation": cls.film_oscillation(hh, pp),
                "x_h_min": x_min, "y_h_min": max(y_min, 0.0),
                "p_max": float(prof["p"].max()),
                "profile": {"xy": xy, "h": prof["h"], "p": prof["p"], "x_axis": xx,
                            "h_axis": hh, "p_axis": pp},
                "W": 2.0 * float(f[Z]), "friction_force": 2.0 * float(f[0]),
                "friction_coefficient": abs(float(f[0])) * per_load,
                "couette_friction_coefficient": abs(float(fc[0])) * per_load,
                "plane_friction_coefficient": abs(float(f_plane[0])) * per_load,
                "clearance": -float(film.counterpart.offset.value[Z])}

    @classmethod
    def _report(cls, steps, speed, v, record, prefix):
        keys = ("h_central", "h_min", "x_h_min", "y_h_min", "p_max", "friction_coefficient",
                "couette_friction_coefficient", "plane_friction_coefficient", "clearance",
                "film_oscillation")
        for m in steps:  # a journal written before film_oscillation was measured
            if "film_oscillation" not in m:
                m["film_oscillation"] = (cls.film_oscillation(m["profile"]["h_axis"],
                                                              m["profile"]["p_axis"])
                                         if "profile" in m else math.nan)
        for m in steps + speed:   # ... or before the force on the plane was
            m.setdefault("plane_friction_coefficient", math.nan)
        if steps:
            for k in keys:
                record.result(prefix + k, steps[-1][k], cls.UNITS[k])
            if steps[-1]["film_oscillation"] > cls.FILM_OSCILLATION_TOL:
                who = f"{prefix.rstrip('_')}: " if prefix else ""
                record.warn(f"{who}film zig-zags node to node by ±"
                            f"{100 * steps[-1]['film_oscillation']:.0f} % on the centre line "
                            f"(W = {steps[-1]['W']:.3g} N): the mesh does not resolve it; "
                            "refine (mesh, edge_refine)")
            record.result(prefix + "W_reached", steps[-1]["W"], "N")
        for k in ("W",) + keys:
            record.result(f"{prefix}steps_{k}", [m[k] for m in steps], cls.UNITS[k])
        for m in speed:
            m["mu_U"] = v["mu"] * m["U"]
        if len(speed) > 1:
            for k in ("U", "mu_U", "friction_coefficient", "couette_friction_coefficient",
                      "plane_friction_coefficient", "h_central", "h_min", "p_max"):
                record.result(f"{prefix}speed_{k}", [m[k] for m in speed], cls.UNITS[k])

    @staticmethod
    def vtx_fields(run):
        """Displacement (bulk) and film pressure (cap submesh)."""
        ball, film, _ = run
        return {"displacement": [ball.u], "pressure": [film.p]}

    @staticmethod
    def plot(profile, outdir):
        """film_map.png, centerline.png and (with speeds) friction_vs_speed.png."""
        from ..plots import plot_ball_film, plot_friction_vs_speed

        variants = {k: var for k, var in profile["variants"].items() if "xy" in var}
        if not variants:
            return
        plot_ball_film(variants, profile["W"], outdir)
        # without shear tractions the film force has no drag: plot the Couette drag
        curves = {var["label"] + ("" if var["shear"] else " (Couette drag)"): (
            var["speed"]["mu_U"], var["speed"]["friction_coefficient" if var["shear"]
                                               else "couette_friction_coefficient"])
            for var in profile["variants"].values() if len(var["speed"]["mu_U"]) > 1}
        curves.update({var["label"] + " (on the plane)": (
            var["speed"]["mu_U"], var["speed"]["plane_friction_coefficient"])
            for var in profile["variants"].values() if len(var["speed"]["mu_U"]) > 1
            and np.isfinite(var["speed"]["plane_friction_coefficient"]).all()})
        if curves:
            plot_friction_vs_speed(curves, outdir / "friction_vs_speed.png")
