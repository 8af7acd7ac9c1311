"""The Stribeck curve of a soft cylinder sliding on a rough rigid plane (issue 32, mixed EHL).

``stribeck`` — a neo-Hookean cylinder (radius R, plane strain, both sides of
the contact modelled) at rest under the load W (N/mm) on a rigid plane that
slides at U (mm/s) under it; the film between them is the chapter's
:class:`~tribofx.interfaces.Film` with a :class:`~tribofx.roughness.Roughness`:
the average-flow Reynolds equation (Patir–Cheng flow factors) and the
Greenwood–Tripp asperity pressure p_a(h) with boundary friction μ_b p_a, the
roughness σ on the plane.  The film and the asperities share the load:
W = ∫ (p + p_a) — the film alone at high speed (λ = h_c/σ ≳ 3), the asperities
alone at low speed, mixed between.

The load is reached at the highest speed by the approach of the plane (a secant
on 1/W inside a load march), then the speed is marched down through
``speeds`` (geometric steps, cut on failure), W held by the approach at each.

Asperity data: σ (mm, combined RMS), ``eta_beta_sigma`` (ηβσ), ``sigma_beta`` (σ/β):
K = (16√2/15)π(ηβσ)²√(σ/β), E* = E/(1 − ν²); the defaults (0.1, 0.1) are a rough
counterface (machined metals, Greenwood & Williamson 1966: 0.03–0.05, 1e-4–1e-2).

Results per speed: ``friction_coefficient`` (the tangential force on the
cylinder over W: fluid shear plus μ_b times the asperity load),
``film_load_fraction`` (film load / W), ``lambda_ratio`` (h_c/σ), ``h_central``,
``h_min``, ``p_max`` (film), ``p_total_max`` (film and asperities),
``newton_iterations``; ``stribeck.png``.  Units: mm, N, s, MPa.
"""

import math

import numpy as np
from dolfinx import fem
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms.hyperelastic import lame_parameters
from ..forms.mixed import asperity_constant
from ..held_response import HeldResponse
from ..interfaces import Film
from ..meshes.roller import ROLLER_NAMES, roller
from ..obstacles import rigid_plane
from ..params import InputError, Param, number_list
from ..problem import NewtonDivergence, Problem
from ..references import hertz, rigid_clearance
from ..roughness import Roughness, greenwood_tripp

__all__ = ["StribeckCase"]


class StribeckCase:
    """Case ``stribeck``; see the module docstring."""

    name = "stribeck"
    doc = "Stribeck curve of a soft cylinder sliding on a rough rigid plane (mixed EHL)"
    params = (
        Param("W", float, 0.5, "N/mm", "load per unit length", lower=0.0),
        Param("R", float, 10.0, "mm", "cylinder radius", lower=0.0),
        Param("E", float, 10.0, "MPa", "Young's modulus of the cylinder", lower=0.0),
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
        ref = hertz(v["W"], v["R"], v["E"], v["nu"], line=True)
        if not 0 < rigid_clearance(v["W"], v["mu"], U[0], v["R"]) < 0.05 * v["R"]:
            raise InputError("the rigid film at the first speed is not thin: W, mu or speeds "
                             "out of range")
        if 4 * ref.a > 0.5 * v["R"]:
            raise InputError(f"load too large: the film (4a = {4 * ref.a:.3g} mm) exceeds R/2")

    @staticmethod
    def roughness(v):
        """Return the plane's roughness: Patir–Cheng flow, Greenwood–Tripp asperities, μ_b."""
        sig, E_star = v["sigma"], v["E"] / (1 - v["nu"] ** 2)
        beta = sig / v["sigma_beta"]
        KE = asperity_constant(v["eta_beta_sigma"] / (beta * sig), beta, sig) * E_star
        return Roughness(sig, asperity=greenwood_tripp(KE, sig), share=-1.0, mu_b=v["mu_b"])

    @classmethod
    def build(cls, v, comm=MPI.COMM_WORLD, rough=True, shape=False):
        """Cylinder, rough film and problem; the plane at Martin's film of W/steps.

        ``rough=False``: the same film on smooth surfaces (the chapter's).
        ``shape=True``: the cylinder carries a shape field (wear) and no Problem is
        built (the slow-time stepper builds it: ``run["problem"]`` is None).
        """
        R, U0 = v["R"], cls.speeds(v)[0]
        ref = hertz(v["W"], R, v["E"], v["nu"], line=True)
        # the rigid film at W/steps, at least σ (the asperities' scale at creeping speeds)
        h_r = max(rigid_clearance(v["W"] / v["steps"], v["mu"], U0, R), v["sigma"])
        # the film's flux scale: Couette U h_r, at least the Poiseuille flux σ³p₀/(12μa)
        # of a σ-thick gap under the contact pressure (the tolerances at creeping speeds)
        U_floor = v["sigma"] ** 3 * ref.p0 / (12 * v["mu"] * ref.a * h_r)
        x_l, h_fine = 4 * ref.a, ref.a / (8 * 2 ** v["mesh"])
        msh, ft = roller(R, x_l, h_fine, R / 4, x_l, comm)
        mu_s, lm = lame_parameters(v["E"], v["nu"])
        body = Body(msh, ft, ROLLER_NAMES, "plane_strain",
                    ("neo-hookean", {"mu": mu_s, "lmbda": lm}), name="cylinder",
                    shape=shape, aux=(v["E"], 0.3))
        body.add_dirichlet("loaded", np.zeros(2))
        for i in range(2 if shape else 0):   # only the film face wears: the rest keeps its shape
            body.add_shape_dirichlet("loaded", i)
            body.add_shape_dirichlet("free", i, except_on="lubricated")
        speed = fem.Constant(msh, np.array([U0, 0.0]))
        film = Film(body, "lubricated", rigid_plane([0, 0], [0, 1]), v["mu"], V_counter=speed,
                    roughness=cls.roughness(v) if rough else None,
                    eps=1e-4 * 24 * v["mu"] * R / h_r**2, p_c=ref.p0, film_scale=h_r,
                    speed_scale=max(U0, U_floor), rtol=1e-8)
        film.add_pressure_bc()
        film.counterpart.offset.value[1] = -h_r
        problem = None if shape else Problem([body, film], name="stribeck", max_it=30)
        return {"body": body, "film": film, "problem": problem, "speed": speed, "ref": ref,
                "U_floor": U_floor}

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
            cls.report(rows, record)
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
        h_r = -float(film.counterpart.offset.value[1])
        inner = Continuation(problem, ConstantParameter(film.counterpart.offset, 1),
                             response=lambda: math.log(max(film.force()[1], 1e-300)),
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
    def measures(run, v):
        """Return friction coefficient, film and asperity loads, λ = h_c/σ, h, p maxima."""
        film = run["film"]
        F, Fa = film.force(), film.asperity_force()
        prof = film.profile(everywhere=True)
        h_c = float(prof["h"][np.argmin(np.abs(prof["X"][:, 0]))])
        return {"friction_coefficient": abs(float(F[0])) / float(F[1]),
                "film_load_fraction": float(F[1] - Fa[1]) / float(F[1]),
                "asperity_load": float(Fa[1]),
                "lambda_ratio": h_c / v["sigma"], "h_central": h_c,
                "h_min": float(prof["h"].min()), "W": float(F[1]),
                "p_max": float(prof["p"].max()),
                "p_total_max": float((prof["p"] + prof.get("p_a", 0.0)).max())}

    @staticmethod
    def report(rows, record):
        """Per-speed lists and the curve for the plot."""
        units = {"U": "mm/s", "friction_coefficient": "-", "film_load_fraction": "-",
                 "lambda_ratio": "-", "h_central": "mm", "h_min": "mm", "W": "N/mm",
                 "p_max": "MPa", "p_total_max": "MPa",
                 "newton_iterations": "-"}
        for key, unit in units.items():
            record.result(key if key != "U" else "speeds", [r[key] for r in rows], unit)
        if MPI.COMM_WORLD.rank == 0 and rows:
            record.profile = {"rows": rows}

    @staticmethod
    def vtx_fields(run):
        """Displacement of the cylinder."""
        return {"displacement": [run["body"].u]}

    @staticmethod
    def plot(profile, outdir):
        """``stribeck.png``: friction coefficient and film load fraction against speed."""
        from ..plots.film import plot_stribeck

        plot_stribeck(profile["rows"], outdir / "stribeck.png")
