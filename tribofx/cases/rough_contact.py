"""A soft cylinder or ball on a rough rigid plane that slides under it (mixed lubrication).

The model of ``stribeck`` and ``wear-lubricated``: the body (a plane-strain roller
or the quarter ball of ``ehl-ball``), the film with a
:class:`~tribofx.roughness.Roughness` (Patir–Cheng flow factors, Greenwood–Tripp
asperities with boundary friction μ_b), its parameters (:class:`RoughContactParams`), the load
held at W by the plane's approach while the speed is marched down
(:func:`load_and_slow`), and the measures of a state (:func:`measures`).  Units:
mm, N, s, MPa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from dolfinx import fem
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms.hyperelastic import lame_parameters
from ..hold import Hold
from ..interfaces import Film, FilmScales, Fluid, Penalty, Quadrature
from ..meshes.ball import BALL_NAMES, cap_height, quarter_ball
from ..meshes.roller import ROLLER_NAMES, roller
from ..obstacles import rigid_plane
from ..params import CaseParams, InputError, param
from ..problem import NewtonDivergence, Problem
from ..references import composite_modulus, hamrock_dowson, hertz, rigid_clearance
from ..references_mixed import flat_punch_separation
from ..roughness import rough_pair

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from ..continuation import Iterations
    from ..obstacles import AnalyticObstacle
    from ..references import HertzContact
    from ..roughness import Roughness

__all__ = ["CAP_RADII", "Model", "RoughContactParams", "build", "check", "first_film",
           "hertz_contact", "load", "load_and_slow", "measures", "rough_ball", "rough_cylinder",
           "roughness", "set_speed"]


#: the ball's cap radius R sin θ_l in Hertz radii (inlet and outlet on the cap)
CAP_RADII = 3.0


def hertz_contact(v: RoughContactParams, geometry: str, W: float | None = None
                  ) -> HertzContact:
    """Hertz contact at W (default ``v.W``): line (N/mm, cylinder) or point (N, whole ball)."""
    return hertz(v.W if W is None else W, v.R, v.E, v.nu, line=geometry == "cylinder")


def first_film(v: RoughContactParams, geometry: str, U: float, W: float | None = None
               ) -> float:
    """Return the film (mm) at load W (default W/steps) and sliding speed U, before σ's floor.

    Cylinder: Martin's rigid film; ball: Hamrock–Dowson's central film at the
    entrainment speed U/2.
    """
    W = v.W / v.steps if W is None else W
    if geometry == "cylinder":
        return rigid_clearance(W, v.mu, U, v.R)
    return hamrock_dowson(W, v.mu, U / 2, v.R, composite_modulus(v.E, v.nu))[0]


def _scales(v: RoughContactParams, geometry: str, U0: float
            ) -> tuple[float, float, HertzContact]:
    """Film scale h_r (≥ σ), flux floor U_floor = σ³p₀/(12μ a h_r), Hertz contact at W."""
    ref = hertz_contact(v, geometry)
    h_r = max(first_film(v, geometry, U0), v.sigma)
    return h_r, v.sigma ** 3 * ref.p0 / (12 * v.mu * ref.a * h_r), ref


@dataclass
class Model:
    """The body on the rough sliding plane (:func:`build`).

    ``speed``: the plane's sliding velocity (a Constant, mm/s); ``ref``: the Hertz
    contact at W; ``U_floor``: the floor of the film's flux scale (mm/s); ``axis``:
    the normal's component; ``copies``: the symmetry copies of the modelled body
    (the whole cylinder 1, the quarter ball 2: the load is ``copies`` times the
    film's force); ``problem``: the monolithic problem (None while a slow-time
    stepper is to build it).
    """

    body: Body
    film: Film
    speed: fem.Constant
    ref: Any
    U_floor: float
    axis: int
    copies: float
    problem: Problem | None


def rough_cylinder(v: RoughContactParams, U0: float, roughness: Roughness | None,
                   comm: MPI.Comm, shape: bool = False) -> Model:
    """Build the plane-strain cylinder (``shape``: a shape field; its film face alone wears)."""
    R = v.R
    h_r, U_floor, ref = _scales(v, "cylinder", U0)
    x_l, h_fine = 4 * ref.a, ref.a / (8 * 2 ** v.mesh)
    msh, ft = roller(R, x_l, h_fine, R / 4, x_l, comm)
    mu_s, lm = lame_parameters(v.E, v.nu)
    body = Body(msh, ft, ROLLER_NAMES, "plane_strain",
                ("neo-hookean", {"mu": mu_s, "lmbda": lm}), name="cylinder",
                shape=shape, aux=(v.E, 0.3))
    body.add_dirichlet("loaded", np.zeros(2))
    for i in range(2 if shape else 0):   # only the film face wears: the rest keeps its shape
        body.add_shape_dirichlet("loaded", i)
        body.add_shape_dirichlet("free", i, except_on="lubricated")
    speed = fem.Constant(msh, np.array([U0, 0.0]))
    film = Film(body, "lubricated", rigid_plane([0, 0], [0, 1]), Fluid(v.mu),
                scales=FilmScales(pressure=ref.p0, film=h_r, speed=max(U0, U_floor)),
                cavitation=Penalty(1e-4 * 24 * v.mu * R / h_r**2), roughness=roughness,
                V_counter=speed, rtol=1e-8)
    film.add_pressure_bc()
    cast("AnalyticObstacle", film.counterpart).offset.value[1] = -h_r   # the rigid plane's
    return Model(body, film, speed, ref, U_floor, axis=1, copies=1.0, problem=None)


def rough_ball(v: RoughContactParams, U0: float, roughness: Roughness | None,
               comm: MPI.Comm) -> Model:
    """Build the quarter ball, started under the Hertz pressure of W/steps."""
    R = v.R
    h_r, U_floor, ref = _scales(v, "ball", U0)
    a = ref.a
    theta = math.asin(CAP_RADII * a / R)
    h_fine = a / (8 * 2 ** v.mesh)
    msh, _, ft = quarter_ball(R, theta, h_fine, max(R / 3, h_fine), 1.6 * a, comm)
    mu_s, lm = lame_parameters(v.E, v.nu)
    body = Body(msh, ft, BALL_NAMES, "3d", ("neo-hookean", {"mu": mu_s, "lmbda": lm}),
                name="ball")
    body.add_dirichlet("midplane", np.zeros(3))
    body.add_dirichlet("symmetry", 0.0, component=1)
    speed = fem.Constant(msh, np.array([U0, 0.0, 0.0]))
    film = Film(body, "lubricated", rigid_plane(np.zeros(3), np.eye(3)[2]), Fluid(v.mu),
                scales=FilmScales(pressure=ref.p0, film=h_r, speed=max(U0, U_floor)),
                cavitation=Penalty(1e-4 * 12 * v.mu * a**2 / h_r**3), roughness=roughness,
                quadrature=Quadrature(degree=2), V_counter=speed, rtol=1e-8)
    z_cap = cap_height(R, theta)
    film.add_pressure_bc(lambda X: np.abs(X[2] - z_cap) < 1e-6 * R)
    # the start where the film is the thicker (h_r above the asperities' separation h_a
    # at the Hertz p₀ of W/steps: flat punch, F_{5/2} fit): the ball under the Hertz
    # pressure, the plane at h_r; else (creeping speeds) undeformed, the plane at h_r
    start = hertz_contact(v, "ball", v.W / v.steps)
    h_a = -math.inf
    if roughness is not None and roughness.asperity is not None:
        h_a = flat_punch_separation(start.p0, v.sigma, roughness.asperity.parameters["KE"])
    if h_r >= h_a:
        film.start_from_pressure(lambda x: start.pressure(np.hypot(x[0], x[1])), h_r,
                                 np.zeros(3))
    else:
        cast("AnalyticObstacle", film.counterpart).offset.value[2] = -h_r   # the plane's
    return Model(body, film, speed, ref, U_floor, axis=2, copies=2.0, problem=None)


@dataclass(frozen=True)
class RoughContactParams(CaseParams):
    """Body, load, lubricant, the plane's roughness (``stribeck``, ``wear-lubricated``)."""

    W: float = param(0.5, "N/mm | N", "load per unit length (cylinder), on the ball (ball)",
                     lower=0.0)
    R: float = param(10.0, "mm", "radius", lower=0.0)
    E: float = param(10.0, "MPa", "Young's modulus of the body", lower=0.0)
    nu: float = param(0.45, "-", "Poisson's ratio", lower=-1.0, upper=0.5)
    mu: float = param(1e-7, "MPa·s", "viscosity (1e-7 MPa·s = 0.1 Pa·s)", lower=0.0)
    sigma: float = param(1e-3, "mm", "combined RMS roughness σ (on the plane)", lower=0.0)
    mu_b: float = param(0.1, "-", "boundary friction coefficient of the asperities", lower=0.0,
                        closed=True)
    eta_beta_sigma: float = param(0.1, "-", "ηβσ (asperity density × radius × σ)", lower=0.0)
    sigma_beta: float = param(0.1, "-", "σ/β (roughness over asperity radius)", lower=0.0)
    mesh: int = param(0, "-", "element size a/(8·2^mesh) along the film", lower=0, upper=4,
                      closed=True)
    steps: int = param(3, "-", "load steps at the first speed", lower=1, upper=50, closed=True)


def check(v: RoughContactParams, geometry: str, speeds: Sequence[float]) -> None:
    """Bad input (the body ``geometry`` at the decreasing ``speeds``, mm/s): a one-line error."""
    a = hertz_contact(v, geometry).a
    if not 0 < first_film(v, geometry, speeds[0], v.W) < 0.05 * v.R:
        raise InputError("the film at the first speed is not thin: W, mu or speeds "
                         "out of range")
    if 4 * a > 0.5 * v.R:
        raise InputError(f"load too large: the film (4a = {4 * a:.3g} mm) exceeds R/2")


def roughness(v: RoughContactParams) -> Roughness:
    """Return the plane's roughness: Patir–Cheng flow, Greenwood–Tripp asperities, μ_b."""
    return rough_pair(v.sigma, v.E / (1 - v.nu ** 2), v.mu_b,
                      v.eta_beta_sigma, v.sigma_beta)


def build(v: RoughContactParams, geometry: str, U0: float, comm: MPI.Comm = MPI.COMM_WORLD,
          rough: bool = True, shape: bool = False) -> Model:
    """Body (``geometry`` cylinder or ball), rough film and problem at the speed U0 (mm/s).

    ``rough=False``: the same film on smooth surfaces (the chapter's).
    ``shape=True`` (cylinder): the body carries a shape field (wear) and no Problem
    is built (the slow-time stepper builds it: ``run.problem`` is None).
    """
    law = roughness(v) if rough else None
    if geometry == "ball":
        if shape:
            raise ValueError("a worn ball (shape=True) is not built: geometry=cylinder")
        run = rough_ball(v, U0, law, comm)
    else:
        run = rough_cylinder(v, U0, law, comm, shape)
    if not shape:
        run.problem = Problem([run.body, run.film], name="stribeck", max_it=30)
    return run


def load_and_slow(run: Model, v: RoughContactParams, speeds: Sequence[float],
                  verbose: bool = False,
                  on_speed: Callable[[float, int], object] | None = None) -> None:
    """Reach W at ``speeds[0]`` by the plane's approach, then march down through ``speeds``.

    ``on_speed(U, newton_iterations)`` once each speed is reached.  The approach
    is a secant on log W: d log W/dδ = 1/h for the rigid film (W ∝ 1/h), and
    n/(σ(H_c − H)) where the asperities carry (W ∝ (H_c − H)^n): both mild in log.
    Between speeds, 8 geometric steps per decade, a failed step retried at its
    square root.
    """
    film, problem = run.film, run.problem
    assert problem is not None   # built with the model, or the stepper's (set by the caller)
    plane = cast("AnalyticObstacle", film.counterpart)   # the rigid plane
    h_r = -float(plane.offset.value[run.axis])
    inner = Continuation(problem, ConstantParameter(plane.offset, run.axis),
                         response=lambda: math.log(max(load(run), 1e-300)),
                         rtol=1e-7, max_trials=30, verbose=verbose)
    # first-update slope d log W/dδ ≈ 1/h at the current thinnest film (the rigid
    # film's 1/h; steeper once the asperities carry: at least 1/σ)
    held = Hold(inner, 0.0, transform=math.log, slope=lambda W: 1.0 / max(
        film.min_film(), v.sigma) if inner.history else 1.0 / max(h_r, v.sigma))
    its: list[Iterations] = []
    held.march(v.W, v.steps, record=its)
    U_done = speeds[0]
    for U in speeds:
        while U_done > U * (1 + 1e-12):
            ratio = max(U / U_done, 10 ** -0.125)
            for _ in range(6):
                try:
                    # the secant history belongs to the last speed: start afresh
                    del inner.history[:-1]
                    set_speed(run, U_done * ratio)
                    its.append(held.solve().iterations)
                    U_done *= ratio
                    break
                except NewtonDivergence:
                    set_speed(run, U_done)
                    ratio = math.sqrt(ratio)
            else:
                raise NewtonDivergence(f"speed {U_done * ratio:.4g} mm/s not reached")
        if on_speed is not None:
            on_speed(U, sum(sum(cast("list[int]", t)) if isinstance(t, list) else t
                            for t in its))
        its.clear()


def set_speed(run: Model, U: float) -> None:
    """Sliding speed U (mm/s); the flux scale U h_r of the tolerances follows it."""
    run.speed.value[0] = U
    run.film.set_scales(speed_scale=max(U, run.U_floor))


def load(run: Model) -> float:
    """Load carried by the whole body (N/mm or N): film and asperities."""
    return run.copies * float(run.film.force()[run.axis])


def measures(run: Model, v: RoughContactParams) -> dict[str, float]:
    """Return friction coefficient, film and asperity loads, λ = h_c/σ, h, p maxima."""
    film = run.film
    n, F, Fa = run.axis, film.force(), film.asperity_force()
    W = run.copies * float(F[n])
    prof = film.profile(everywhere=True)
    h_c = float(prof["h"][np.argmin(np.linalg.norm(prof["X"][:, :n], axis=1))])
    return {"friction_coefficient": abs(float(F[0])) / float(F[n]),
            "film_load_fraction": float(F[n] - Fa[n]) / float(F[n]),
            "asperity_load": float(Fa[n]) * W / float(F[n]),
            "lambda_ratio": h_c / v.sigma, "h_central": h_c,
            "h_min": float(prof["h"].min()), "W": W,
            "p_max": float(prof["p"].max()),
            "p_total_max": float((prof["p"] + prof.get("p_a", 0.0)).max())}
