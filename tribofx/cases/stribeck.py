"""The Stribeck curve of a soft cylinder or ball sliding on a rough rigid plane (issue 32).

``stribeck`` — a neo-Hookean cylinder (``geometry=cylinder``: radius R, plane
strain, both sides of the contact modelled, W in N/mm) or ball (``geometry=ball``:
the quarter model of ``ehl-ball``, W in N on the whole ball) at rest on a rigid
plane that slides at U (mm/s) under it (:mod:`.stribeck_geometry`); the film
between them is the chapter's
:class:`~tribofx.interfaces.Film` with a :class:`~tribofx.roughness.Roughness`:
the average-flow Reynolds equation (Patir–Cheng flow factors) and the
Greenwood–Tripp asperity pressure p_a(h) with boundary friction μ_b p_a, the
roughness σ on the plane.  The film and the asperities share the load:
W = ∫ (p + p_a) — the film alone at high speed (λ = h_c/σ ≳ 3), the asperities
alone at low speed, mixed between.

The load is reached at the highest speed by the approach of the plane (a secant
on log W inside a load march), then the speed is marched down through
``speeds`` (geometric steps, cut on failure), W held by the approach at each.

Asperity data: σ (mm, combined RMS), ``eta_beta_sigma`` (ηβσ), ``sigma_beta`` (σ/β):
K = (16√2/15)π(ηβσ)²√(σ/β), E* = E/(1 − ν²); the defaults (0.1, 0.1) are a rough
counterface (machined metals, Greenwood & Williamson 1966: 0.03–0.05, 1e-4–1e-2).

Results per speed: ``friction_coefficient`` (the tangential force on the
body over W: fluid shear plus μ_b times the asperity load),
``film_load_fraction`` (film load / W), ``lambda_ratio`` (h_c/σ), ``h_central``,
``h_min``, ``p_max`` (film), ``p_total_max`` (film and asperities),
``newton_iterations``; ``stribeck.png``.  Units: mm, N, s, MPa.
"""

import math

import numpy as np
from mpi4py import MPI

from ..continuation import ConstantParameter, Continuation
from ..held_response import HeldResponse
from ..params import InputError, Param, number_list
from ..problem import NewtonDivergence, Problem
from ..roughness import rough_pair
from . import stribeck_geometry as geometry

__all__ = ["StribeckCase"]


class StribeckCase:
    """Case ``stribeck``; see the module docstring."""

    name = "stribeck"
    doc = "Stribeck curve of a soft cylinder or ball sliding on a rough rigid plane (mixed EHL)"
    params = (
        Param("geometry", str, "cylinder", "-", "cylinder (plane strain) or ball (3D quarter)",
              choices=("cylinder", "ball")),
        Param("W", float, 0.5, "N/mm | N", "load per unit length (cylinder), on the ball (ball)",
              lower=0.0),
        Param("R", float, 10.0, "mm", "radius", lower=0.0),
        Param("E", float, 10.0, "MPa", "Young's modulus of the body", lower=0.0),
        Param("nu", float, 0.45, "-", "Poisson's ratio", lower=-1.0, upper=0.5),
        Param("mu", float, 1e-7, "MPa·s", "viscosity (1e-7 MPa·s = 0.1 Pa·s)", lower=0.0),
        Param("sigma", float, 1e-3, "mm", "combined RMS roughness σ (on the plane)",
              lower=0.0),
        Param("mu_b", float, 0.1, "-", "boundary friction coefficient of the asperities",
              lower=0.0, closed=True),
        Param("eta_beta_sigma", float, 0.1, "-", "ηβσ (asperity density × radius × σ)",
              lower=0.0),
        Param("sigma_beta", float, 0.1, "-", "σ/β (roughness over asperity radius)",
              lower=0.0),
        Param("speeds", str, "1000,300,100,30,10,3,1,0.3,0.1,0.03,0.01", "mm/s",
              "sliding speeds, decreasing (comma-separated)"),
        Param("mesh", int, 0, "-", "element size a/(8·2^mesh) along the film", lower=0,
              upper=4, closed=True),
        Param("steps", int, 3, "-", "load steps at the first speed", lower=1, upper=50,
              closed=True),
    )

    @staticmethod
    def speeds(v):
        """Return the speeds (mm/s), decreasing (one-line error otherwise)."""
        U = number_list(v["speeds"], "speeds")
        if any(u <= 0 for u in U) or any(b >= a for a, b in zip(U, U[1:])):
            raise InputError("speeds must be positive and decreasing")
        return U

    @classmethod
    def validate(cls, v):
        """Bad input: a one-line error."""
        U = cls.speeds(v)
        a = geometry.hertz_contact(v).a
        if not 0 < geometry.first_film(v, U[0], v["W"]) < 0.05 * v["R"]:
            raise InputError("the film at the first speed is not thin: W, mu or speeds "
                             "out of range")
        if 4 * a > 0.5 * v["R"]:
            raise InputError(f"load too large: the film (4a = {4 * a:.3g} mm) exceeds R/2")

    @staticmethod
    def roughness(v):
        """Return the plane's roughness: Patir–Cheng flow, Greenwood–Tripp asperities, μ_b."""
        return rough_pair(v["sigma"], v["E"] / (1 - v["nu"] ** 2), v["mu_b"],
                          v["eta_beta_sigma"], v["sigma_beta"])

    @classmethod
    def build(cls, v, comm=MPI.COMM_WORLD, rough=True, shape=False):
        """Body, rough film and problem at the first speed (:mod:`.stribeck_geometry`).

        ``rough=False``: the same film on smooth surfaces (the chapter's).
        ``shape=True`` (cylinder): the body carries a shape field (wear) and no Problem
        is built (the slow-time stepper builds it: ``run["problem"]`` is None).
        """
        U0, law = cls.speeds(v)[0], cls.roughness(v) if rough else None
        if v["geometry"] == "ball":
            if shape:
                raise ValueError("a worn ball (shape=True) is not built: geometry=cylinder")
            run = geometry.ball(v, U0, law, comm)
        else:
            run = geometry.cylinder(v, U0, law, comm, shape)
        run["problem"] = None if shape else Problem([run["body"], run["film"]],
                                                    name="stribeck", max_it=30)
        return run

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, comm=MPI.COMM_WORLD, rough=True):
        """Reach W at the first speed, then march the speed down; record per speed.

        ``rough=False``: the smooth film (the chapter's) at the same speeds.
        """
        run = cls.build(v, comm, rough)
        record.data["num_dofs"] = run["problem"].num_dofs
        rows = []

        def on_speed(U, iterations):
            rows.append(dict(cls.measures(run, v), U=U, newton_iterations=iterations))
            if progress is not None:
                progress.update(1)

        try:
            cls.load_and_slow(run, v, cls.speeds(v), verbose, on_speed)
        except NewtonDivergence as err:
            err.problem = run
            raise
        finally:
            cls.report(rows, record, v["geometry"])
        return run

    @staticmethod
    def load_and_slow(run, v, speeds, verbose=False, on_speed=None):
        """Reach W at ``speeds[0]`` by the plane's approach, then march down through ``speeds``.

        ``on_speed(U, newton_iterations)`` once each speed is reached.  The approach
        is a secant on log W: d log W/dδ = 1/h for the rigid film (W ∝ 1/h), and
        n/(σ(H_c − H)) where the asperities carry (W ∝ (H_c − H)^n): both mild in log.
        Between speeds, 8 geometric steps per decade, a failed step retried at its
        square root.
        """
        film, problem = run["film"], run["problem"]
        h_r = -float(film.counterpart.offset.value[run["axis"]])
        inner = Continuation(problem, ConstantParameter(film.counterpart.offset, run["axis"]),
                             response=lambda: math.log(max(StribeckCase.load(run), 1e-300)),
                             rtol=1e-7, max_trials=30, verbose=verbose)
        # first-update slope d log W/dδ ≈ 1/h at the current thinnest film (the rigid
        # film's 1/h; steeper once the asperities carry: at least 1/σ)
        held = HeldResponse(inner, 0.0, transform=math.log, slope=lambda W: 1.0 / max(
            film.min_film(), v["sigma"]) if inner.history else 1.0 / max(h_r, v["sigma"]))
        its = []
        Continuation(held, held, response=lambda: held.target, record=its).march(
            v["W"], v["steps"])
        U_done = speeds[0]
        for U in speeds:
            while U_done > U * (1 + 1e-12):
                ratio = max(U / U_done, 10 ** -0.125)
                for _ in range(6):
                    try:
                        # the secant history belongs to the last speed: start afresh
                        del inner.history[:-1]
                        StribeckCase.set_speed(run, U_done * ratio)
                        its.append(held.solve().iterations)
                        U_done *= ratio
                        break
                    except NewtonDivergence:
                        StribeckCase.set_speed(run, U_done)
                        ratio = math.sqrt(ratio)
                else:
                    raise NewtonDivergence(f"speed {U_done * ratio:.4g} mm/s not reached")
            if on_speed is not None:
                on_speed(U, sum(sum(t) if isinstance(t, list) else t for t in its))
            its.clear()

    @staticmethod
    def set_speed(run, U):
        """Sliding speed U (mm/s); the flux scale U h_r of the tolerances follows it."""
        run["speed"].value[0] = U
        run["film"].set_scales(speed_scale=max(U, run["U_floor"]))

    @staticmethod
    def load(run):
        """Load carried by the whole body (N/mm or N): film and asperities."""
        return run["copies"] * float(run["film"].force()[run["axis"]])

    @staticmethod
    def measures(run, v):
        """Return friction coefficient, film and asperity loads, λ = h_c/σ, h, p maxima."""
        film = run["film"]
        n, F, Fa = run["axis"], film.force(), film.asperity_force()
        W = run["copies"] * float(F[n])
        prof = film.profile(everywhere=True)
        h_c = float(prof["h"][np.argmin(np.linalg.norm(prof["X"][:, :n], axis=1))])
        return {"friction_coefficient": abs(float(F[0])) / float(F[n]),
                "film_load_fraction": float(F[n] - Fa[n]) / float(F[n]),
                "asperity_load": float(Fa[n]) * W / float(F[n]),
                "lambda_ratio": h_c / v["sigma"], "h_central": h_c,
                "h_min": float(prof["h"].min()), "W": W,
                "p_max": float(prof["p"].max()),
                "p_total_max": float((prof["p"] + prof.get("p_a", 0.0)).max())}

    @staticmethod
    def report(rows, record, geometry="cylinder"):
        """Per-speed lists and the curve for the plot."""
        units = {"U": "mm/s", "friction_coefficient": "-", "film_load_fraction": "-",
                 "lambda_ratio": "-", "h_central": "mm", "h_min": "mm", "W": "N/mm | N",
                 "p_max": "MPa", "p_total_max": "MPa",
                 "newton_iterations": "-"}
        for key, unit in units.items():
            record.result(key if key != "U" else "speeds", [r[key] for r in rows], unit)
        if MPI.COMM_WORLD.rank == 0 and rows:
            record.profile = {"rows": rows, "geometry": geometry}

    @staticmethod
    def vtx_fields(run):
        """Displacement of the cylinder."""
        return {"displacement": [run["body"].u]}

    @staticmethod
    def plot(profile, outdir):
        """``stribeck.png``: friction coefficient and film load fraction against speed."""
        from ..plots.film import plot_stribeck

        plot_stribeck(profile["rows"], outdir / "stribeck.png", profile.get("geometry", "cylinder"))
