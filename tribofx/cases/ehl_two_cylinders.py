"""Soft-EHL line contact of two elastic cylinders, rolling and sliding (plane strain).

``ehl-two-cylinders`` — two hyperelastic (neo-Hookean) cylinders of radii R1
(above, centre (0, R1 + h₀)) and R2 (below, centre (0, −R2)), their surfaces
moving at U1 and U2 (mm/s, along +x at the contact: the upper one rolls
counter-clockwise, the lower clockwise), press a flooded film between them at
the load W (N/mm).  ``R2=inf`` makes the lower body a block (its surface
sliding at U2); ``E1=inf`` or ``E2=inf`` makes that body rigid (then the film
lives on the other one, against the rigid roller or plane: the chapter's
:class:`~tribofx.interfaces.Film`).

Both bodies are modelled on both sides of the contact (the film has an inlet
and an outlet): the half discs towards the contact (:func:`tribofx.meshes.roller.roller`),
their flat faces held (the upper) and lifted by δ (the lower).  The film,
:class:`~tribofx.interfaces.TwoBodyFilm`, lives on the upper body's boundary
|x| ≤ x_l (S = γ_l), projected onto the lower body's current boundary
(|x| ≤ x_l + 2ℓ); p = 0 at its ends, penalty cavitation.  The load is reached
by δ (a secant on 1/W, nearly linear for a rigid film, inside a load march
with step cutting: :class:`~tribofx.hold.Hold`).

References: Hertz (line contact, R* and E* of the pair, the dry limit of the
pressure) and Martin's rigid film h = 4.9 μ u_m R*/W (u_m = (U1 + U2)/2),
the isoviscous-rigid limit; the soft (isoviscous-elastic) regime lies between.

Results: ``h_central`` (at x = 0 of the upper body), ``h_min``, ``p_max``, the
film's force on each body (``friction_force_upper``/``_lower``, x, N/mm;
``normal_load``), ``approach`` δ; ``profiles.png`` (p and h against x); VTX of
both displacements.  Units: mm, N, s, MPa (viscosity MPa·s).
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
from ..interfaces import Film, FilmScales, Fluid, Penalty, TwoBodyFilm
from ..meshes.roller import ROLLER_NAMES, roller
from ..motions import Rolling, Sliding
from ..obstacles import rigid_cylinder, rigid_plane
from ..params import CaseParams, InputError, param
from ..problem import NewtonDivergence, Problem
from ..references import hertz, rigid_clearance

if TYPE_CHECKING:
    from pathlib import Path

    from tqdm import tqdm

    from ..obstacles import AnalyticObstacle
    from ..output import RunRecord
    from ..references import HertzContact

__all__ = ["Model", "Params", "build", "doc", "measures", "name", "plot", "progress_total",
           "reference", "report", "resumable", "run", "scales", "validate", "vtx_fields"]


name = "ehl-two-cylinders"
resumable = False   # no per-step checkpoint
doc = ("soft-EHL line contact of two elastic cylinders (or a cylinder on a block), "
       "rolling and sliding; either body may be rigid")


@dataclass(frozen=True)
class Params(CaseParams):
    """The parameters of ``ehl-two-cylinders`` (``--set KEY=VALUE``)."""

    R1: float = param(10.0, "mm", "radius of the upper cylinder", lower=0.0)
    R2: float = param(
        10.0, "mm",
        "radius of the lower cylinder (inf: a block)",
        lower=0.0, infinite=True)
    E1: float = param(
        10.0, "MPa",
        "Young's modulus of the upper body (inf: rigid)",
        lower=0.0, infinite=True)
    E2: float = param(
        10.0, "MPa",
        "Young's modulus of the lower body (inf: rigid)",
        lower=0.0, infinite=True)
    nu1: float = param(0.45, "-", "Poisson's ratio of the upper body", lower=-1.0, upper=0.5)
    nu2: float = param(0.45, "-", "Poisson's ratio of the lower body", lower=-1.0, upper=0.5)
    U1: float = param(
        1000.0, "mm/s",
        "surface speed of the upper body (along +x at "
        "the contact)")
    U2: float = param(1000.0, "mm/s", "surface speed of the lower body")
    W: float = param(0.5, "N/mm", "load per unit length", lower=0.0)
    mu: float = param(1e-7, "MPa·s", "viscosity (1e-7 MPa·s = 0.1 Pa·s)", lower=0.0)
    extent: float = param(
        4.0, "-",
        "half length of the film x_l in units of the "
        "Hertz half-width a",
        lower=1.0)
    steps: int = param(4, "-", "load steps", lower=1, upper=100, closed=True)
    mesh: int = param(
        0, "-",
        "element size a/(8·2^mesh) along the film",
        lower=0, upper=5, closed=True)
    penalty: float = param(
        1e-4, "-",
        "cavitation penalty ε in units of 12μℓ²/h³ "
        "(0: none)",
        lower=0.0, closed=True)
    shear: bool = param(True, "-", "Couette and Poiseuille shear tractions")
    supg: bool = param(True, "-", "SUPG stabilisation of the Reynolds rows")


def reference(v: Params) -> HertzContact:
    """Hertz line contact of the pair (the dry limit)."""
    return hertz(v.W, v.R1, v.E1, v.nu1, v.R2, v.E2, v.nu2, line=True)


def scales(v: Params, W: float | None = None) -> tuple[float, float, float, float]:
    """Rigid film h_r (mm), pressure scale p_c (MPa), penalty ε (MPa·s/mm), x_l (mm)."""
    ref = reference(v)
    u_m = 0.5 * (v.U1 + v.U2)
    h_r = rigid_clearance(v.W if W is None else W, v.mu, 2 * u_m, ref.R_star)
    ell = math.sqrt(2 * ref.R_star * h_r)
    return (h_r, max(ref.p0, 6 * v.mu * u_m * ell / h_r**2),
            v.penalty * 12 * v.mu * ell**2 / h_r**3, v.extent * ref.a)


def validate(v: Params) -> None:
    """Bad input: a one-line error."""
    if math.isinf(v.E1) and math.isinf(v.E2):
        raise InputError("E1 = E2 = inf: two rigid bodies (use the case reynolds-cylinder)")
    if math.isinf(v.R1):
        raise InputError("R1 must be finite (the upper body is a cylinder)")
    if not v.U1 + v.U2 > 0:
        raise InputError(f"U1 + U2 = {v.U1 + v.U2} mm/s: no entrainment into the "
                         f"film (needs > 0)")
    try:
        h_r, _, _, x_l = scales(v)
        R_star = reference(v).R_star
    except (ArithmeticError, ValueError):
        raise InputError("W, U1, U2, mu or the radii out of range (the film's scales "
                         "overflow)") from None
    if not 0 < h_r < 0.05 * R_star:
        raise InputError(f"the rigid film at W, {h_r:.3g} mm, is not thin against R* = "
                         f"{R_star:.3g} mm: W, U1 + U2 or mu out of range")
    if x_l > 0.5 * min(v.R1, v.R2):
        raise InputError(f"film half length x_l = {x_l:.3g} mm exceeds R/2: lower "
                         f"extent or W")


@dataclass
class Model:
    """What :func:`build` assembles: the bodies (0 upper, 1 lower), the film, the problem.

    ``lift``: what moves the lower body (a Dirichlet value, or the countersurface's
    offset of a one-body film); ``sign`` (+1: the film's force on the upper body is
    the load along +y).
    """

    bodies: dict[int, Body]
    film: Film | TwoBodyFilm
    problem: Problem
    lift: fem.Constant
    sign: float


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD) -> Model:
    """Bodies, film and problem with the upper body h_r(W/steps) above the lower one.

    Returns the :class:`Model`: ``bodies``, ``film``, ``problem``, ``lift`` (the
    Constant that moves the lower body, or a rigid lower countersurface, up by δ),
    ``sign`` (+1: the film's force on the upper body is the load along +y).
    """
    ref = reference(v)
    h_r, p_c, eps, x_l = scales(v, v.W / v.steps)
    h_fine = ref.a / (8 * 2 ** v.mesh)
    R1, R2, U = v.R1, v.R2, (v.U1, v.U2)
    shapes = (Rolling((0, R1 + h_r), R1),
              Sliding((1, 0)) if math.isinf(R2) else Rolling((0, -R2), -R2))
    bodies: dict[int, Body] = {}
    for k, (E, nu) in enumerate(((v.E1, v.nu1), (v.E2, v.nu2))):
        if math.isinf(E):
            continue
        R = (R1, R2)[k]
        block = 2 * R1 if math.isinf(R) else None
        xl = x_l if k == 0 or math.isinf(v.E1) else x_l + 2 * ref.a
        msh, ft = roller(R, xl, h_fine, (R if block is None else block) / 4, xl, comm,
                         below=k == 1, block=block)
        if k == 0:
            msh.geometry.x[:, 1] += h_r
        mu_s, lm = lame_parameters(E, nu)
        bodies[k] = Body(msh, ft, ROLLER_NAMES, "plane_strain",
                         ("neo-hookean", {"mu": mu_s, "lmbda": lm}),
                         name=("upper", "lower")[k])
    kw: dict[str, Any]   # the film's keyword arguments
    kw = dict(shear=v.shear, supg=v.supg, cavitation=Penalty(eps) if v.penalty > 0 else None,
              scales=FilmScales(pressure=p_c, film=h_r, speed=max(abs(U[0]), abs(U[1]))))
    if 0 in bodies and 1 in bodies:
        upper, lower = bodies[0], bodies[1]
        upper.add_dirichlet("loaded", np.zeros(2))
        lift = lower.add_dirichlet("loaded", np.zeros(2))
        film: Film | TwoBodyFilm = TwoBodyFilm(
            upper, "lubricated", lower, "lubricated", Fluid(v.mu),
            motion1=shapes[0], U1=U[0], motion2=shapes[1], U2=U[1], **kw)
        sign = 1.0
    else:   # one rigid body: the film on the other, against a rigid roller or plane
        k = 0 if 0 in bodies else 1
        body = bodies[k]
        body.add_dirichlet("loaded", np.zeros(2))
        if k == 0:
            counter = (rigid_plane([0, 0], [0, 1]) if math.isinf(R2)
                       else rigid_cylinder([0, -R2], R2))
        else:
            counter = rigid_cylinder([0, R1 + h_r], R1)
        mine = (shapes[k], fem.Constant(body.mesh, float(U[k])))
        other = (shapes[1 - k], fem.Constant(body.mesh, float(U[1 - k])))
        film = Film(body, "lubricated", counter, Fluid(v.mu), motion=mine, V_counter=other,
                    **kw)
        # (a rigid roller or plane: its offset moves it)
        lift, sign = (cast("AnalyticObstacle", film.counterpart).offset,
                      (1.0 if k == 0 else -1.0))
    film.add_pressure_bc()
    problem = Problem([*bodies.values(), film], name="ehl_two_cylinders", max_it=25)
    return Model(bodies, film, problem, lift, sign)


def progress_total(v: Params) -> int:
    """Return the steps the progress bar counts: the load steps."""
    return v.steps


def run(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
        comm: MPI.Comm = MPI.COMM_WORLD) -> Model:
    """March the load to W (the approach found per load by a secant on 1/W)."""
    run = build(v, comm)
    film, problem, sign = run.film, run.problem, run.sign
    record.data["num_dofs"] = problem.num_dofs
    ref = reference(v)
    u_m = 0.5 * (v.U1 + v.U2)
    # a rigid upper roller moves down (its film lives on the lower body): δ along −y
    inner = Continuation(problem, ConstantParameter(run.lift, 1, scale=sign),
                         response=lambda: 1.0 / (sign * film.force()[1]), rtol=1e-6,
                         max_trials=30, verbose=verbose)
    slope = -1.0 / (4.9 * v.mu * u_m * ref.R_star)    # Martin: d(1/W)/dδ, h = h₀ − δ
    held = Hold(inner, 0.0, transform=lambda W: 1.0 / W, slope=slope)
    steps: list[dict[str, Any]] = []

    def on_load() -> None:
        steps.append(measures(run, v))
        if progress is not None:
            progress.update(1)

    try:
        held.march(v.W, v.steps, on_step=on_load,
                   record=record.data["newton_iterations"])
    except NewtonDivergence as err:
        err.model = run
        raise
    finally:
        report(run, v, record, steps, ref)
    return run


def measures(run: Model, v: Params) -> dict[str, Any]:
    """Return the film at the current load: h at x = 0, h_min, p_max, forces, profile."""
    film = run.film
    prof = film.profile(everywhere=True)
    X = prof["X"][:, 0]
    m = {"W": float(run.sign * film.force()[1]), "h_central": float(
        prof["h"][np.argmin(np.abs(X))]), "h_min": float(prof["h"].min()),
        "p_max": float(prof["p"].max()), "x": prof["x"][:, 0], "h": prof["h"],
        "p": prof["p"]}
    if isinstance(film, TwoBodyFilm):
        on1, on2 = film.forces()
    else:
        on = film.force()
        on1, on2 = (on, -on) if run.sign > 0 else (-on, on)
    m["friction_force_upper"], m["friction_force_lower"] = float(on1[0]), float(on2[0])
    m["approach"] = float(run.lift.value[1]) * (1 if run.sign > 0 else -1)
    return m


def report(run: Model, v: Params, record: RunRecord, steps: list[dict[str, Any]],
           ref: HertzContact) -> None:
    """Results at the last converged load; profiles for the plot."""
    if not steps:
        return
    m = steps[-1]
    units = {"W": "N/mm", "h_central": "mm", "h_min": "mm", "p_max": "MPa",
             "friction_force_upper": "N/mm", "friction_force_lower": "N/mm",
             "approach": "mm"}
    for key, unit in units.items():
        record.result("normal_load" if key == "W" else key, m[key], unit)
    u_m = 0.5 * (v.U1 + v.U2)
    record.result("hertz_half_width", ref.a, "mm")
    record.result("hertz_p_max", ref.p0, "MPa")
    record.result("rigid_film_martin", rigid_clearance(m["W"], v.mu, 2 * u_m,
                                                       ref.R_star), "mm")
    if run.film.sub.comm.rank == 0:
        record.profile = {"steps": [{k: s[k] for k in ("W", "x", "p", "h")}
                                    for s in steps]}


def vtx_fields(run: Model) -> dict[str, list[fem.Function]]:
    """Displacements of the elastic bodies (one file per mesh)."""
    return {b.name: [b.u] for b in run.bodies.values()}


def plot(profile: dict[str, Any], outdir: Path) -> None:
    """``profiles.png``: p(x) and h(x) per load step."""
    from ..plots.film import plot_film_profiles

    plot_film_profiles(profile["steps"], outdir / "profiles.png",
                       "two elastic cylinders: film per load step")
