"""Squeeze film of a soft cylinder or sphere approaching a plane (transient soft-EHL).

``ehl-squeeze`` — a hyperelastic cylinder (``dim=2``, plane strain, half model
x ≥ 0) or sphere (``dim=3``, quarter model x, y ≥ 0; ``dim=axisymmetric``, its
meridian section x = r ≥ 0 with the axis x = 0) of radius R, its lowest point
h_start above a rigid plane, squeezes the flooded film between them:

* ``control=speed``: the plane rises at V (mm/s) towards the body, whose top
  face is held (u = 0);
* ``control=load``: the body's top face carries the load F (N; N/mm of the
  whole cylinder in 2D) as a dead traction and nothing else holds it: the film
  alone carries F, through its squeeze term (a monolithic Newton in u, p).

The film is the transient one of :mod:`tribofx.forms.squeeze` on the lubricated
cap within L = min(10ℓ, R/2) of the axis: the rate of the content ρθhJ_S at fixed reference
point, the mean velocity relative to the moving lubrication surface, integrated
by backward Euler or BDF2 (``scheme``) in steps ``dt`` to ``T``; p = 0 at the
film's end (its rim at L opens to a flooded reservoir).

Rigid limit (E1 ≫ the film pressures), the independent checks: Reynolds'
squeeze film with the exact gap (:func:`tribofx.references.squeeze_resistance`,
→ W' = 3√2πμV(R/h)^{3/2} and F = 6πμR²V/h for h ≪ R) and its thinning under a
constant load (:func:`tribofx.references.squeeze_film_under_load`); recorded
per step as ``force_rigid`` / ``h_center_rigid``.  A soft body under load
traps fluid at its centre: the elastohydrodynamic dimple, h_center > h_min.

``cavitation=jfo`` (dim=2, 3) makes the film mass-conserving: a receding plane
(V < 0) opens a cavity in which the void fraction is transported, θh constant at
each point while p = 0 (``tests/test_squeeze.py``; between two bodies the
fluid's content moves along the body's surface with the block's tangential motion
relative to it, docs/films.md).  ``E2`` finite: the plane
is the top of an elastic block [0, 2L] × [−H2, 0] (ν2, H2 default 2L;
axisymmetric: a disc of radius 2L; 3D: the quarter block [0, 2L]² × [−H2, 0]),
a layer bonded to a rigid base where H2 is small, held — or
lifted at V — at its bottom, and the film is the two-body one
(:class:`~tribofx.interfaces.TwoBodyFilm`, S = the body's surface): a soft
cylinder or ball landing on a soft block or disc.

Units: mm, N, s, MPa (viscosity MPa·s).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple, cast

import numpy as np
from dolfinx import fem
from mpi4py import MPI

from ..body import Body
from ..forms.hyperelastic import lame_parameters
from ..interfaces import Film, FilmScales, Fluid, TwoBodyFilm
from ..interfaces.film_options import named_cavitation
from ..meshes.block3d import BOTTOM, SIDES, SYMMETRY_X, SYMMETRY_Y, TOP, contact_block
from ..meshes.hertz import FREE, NAMES, hertz_body
from ..obstacles import rigid_plane
from ..params import InputError, param
from ..problem import Problem
from ..references import hertz, squeeze_film_under_load, squeeze_resistance
from ..step_control import FixedStep
from ..stepper import Stepper, nominal_steps
from .curved_bodies import AXISYMMETRIC, body_kind, dimension, geometric_dim, hertz_dim
from .film_setup import FluidParams, density, viscosity
from .slow_time import SlowTimeRecords

if TYPE_CHECKING:
    import os
    from pathlib import Path

    import numpy.typing as npt
    from tqdm import tqdm

    from ..obstacles import AnalyticObstacle
    from ..output import RunRecord

__all__ = ["Model", "Params", "build", "doc", "extent", "fraction", "length", "measures", "name",
           "plot", "progress_total", "resumable", "run", "speed_scale", "steady_problem",
           "validate", "vtx_fields"]


name = "ehl-squeeze"
#: writes a checkpoint every step: `--resume` continues an interrupted run
resumable = True
doc = ("transient squeeze film of a soft cylinder (2D) or sphere (3D, or axisymmetric) "
       "approaching a rigid plane, at a speed or under a load; rigid-limit references")


@dataclass(frozen=True)
class Params(FluidParams):
    """The parameters of ``ehl-squeeze`` (``--set KEY=VALUE``)."""

    dim: int | str = param(
        2, "-",
        "2: cylinder (plane strain, half model), 3: sphere (quarter model), "
        "axisymmetric: sphere (meridian section x >= 0, the axis x = 0)",
        choices=(2, 3, AXISYMMETRIC), parse=dimension)
    control: str = param(
        "speed", "-",
        "speed: the plane approaches at V; load: the "
        "body carries F",
        choices=("speed", "load"))
    V: float = param(
        1.0, "mm/s",
        "approach speed of the plane (control=speed; < 0: "
        "it recedes, the film cavitates: cavitation=jfo)")
    cavitation: str = param(
        "none", "-",
        "none (a full film) or jfo (mass-conserving, "
        "the void fraction transported in time; dim=2 or 3, on the plane or the block)",
        choices=("none", "jfo"))
    lumped: bool = param(
        False, "-",
        "jfo: the content's rate at the nodes (lumped) and "
        "the SUPG rate weighted by the full-film fraction (forms.jfo.jfo_on_surface)")
    F: float = param(0.05, "N", "load (control=load; N/mm of the cylinder in 2D)", lower=0.0)
    R: float = param(10.0, "mm", "radius of the cylinder or sphere", lower=0.0)
    E1: float = param(
        1e5, "MPa",
        "Young's modulus of the cylinder or sphere (neo-Hookean)",
        lower=0.0)
    nu1: float = param(0.3, "-", "Poisson's ratio of the cylinder or sphere", lower=-1.0, upper=0.5)
    E2: float = param(
        math.inf, "MPa",
        "Young's modulus of the plane body (inf: rigid; "
        "finite: an elastic block (dim=2, 3) or disc (dim=axisymmetric), the two-body film)",
        lower=0.0, infinite=True)
    nu2: float = param(0.3, "-", "Poisson's ratio of the plane body", lower=-1.0, upper=0.5)
    H2: float | None = param(
        None, "mm",
        "thickness of the elastic block or disc (E2 finite; default 2L, L the film's end): "
        "a layer bonded to a rigid base at its bottom",
        lower=0.0)
    mu: float = param(1e-7, "MPa·s", "viscosity μ₀ (1e-7 MPa·s = 0.1 Pa·s)", lower=0.0)
    h_start: float = param(0.01, "mm", "initial film at the centre", lower=0.0)
    T: float = param(2e-3, "s", "end time", lower=0.0)
    dt: float = param(2.5e-4, "s", "time step", lower=0.0)
    scheme: str = param(
        "bdf2", "-",
        "time scheme of the squeeze term: euler (backward "
        "Euler) or bdf2 (second order, started by one Euler step)",
        choices=("euler", "bdf2"))
    mesh: int = param(
        0, "-",
        "element size ℓ/(8·2^mesh) near the centre, "
        "ℓ = max(√(2R h_start), Hertz half-width)",
        lower=0, upper=6, closed=True)
    supg: bool = param(True, "-", "SUPG stabilisation of the Reynolds rows")


def validate(v: Params) -> None:
    """Bad input: a one-line error."""
    if not v.h_start < 0.1 * v.R:
        raise InputError(f"h_start = {v.h_start} mm must be below R/10 (a thin film)")
    if v.H2 is not None and math.isinf(v.E2):
        raise InputError("H2 is the thickness of the elastic block: give E2 too")
    if v.dt > v.T:
        raise InputError(f"dt = {v.dt} s exceeds T = {v.T} s")
    if v.control == "speed" and v.V <= 0 and not (v.V < 0 and v.cavitation
                                                         == "jfo"):
        raise InputError(f"V = {v.V} mm/s: a receding plane (V < 0) needs "
                         f"cavitation=jfo; V = 0 has no squeeze")
    if v.lumped and v.cavitation != "jfo":
        raise InputError("lumped=true is for cavitation=jfo")
    if v.cavitation == "jfo" and v.dim == AXISYMMETRIC:
        raise InputError("cavitation=jfo is built for dim=2 and dim=3 (not axisymmetric)")
    if v.control == "speed" and not v.V * v.T < 0.9 * v.h_start:
        raise InputError(f"V·T = {v.V * v.T:.3g} mm would close the rigid gap "
                         f"h_start = {v.h_start} mm; shorten T")
    viscosity(v)
    density(v, v.cavitation)


def fraction(v: Params) -> float:
    """Modelled part of the body: 1/2 (cylinder, half), 1/4 (sphere, quarter), 1 (revolved)."""
    return {2: 0.5, 3: 0.25, AXISYMMETRIC: 1.0}[v.dim]


def length(v: Params) -> float:
    """ℓ = max(√(2R h_start), Hertz half-width at F) (mm): the film's width."""
    ell = math.sqrt(2 * v.R * v.h_start)
    if v.control == "load" and v.F > 0:
        ell = max(ell, hertz(v.F, v.R, v.E1, v.nu1, line=v.dim == 2).a)
    return ell


def extent(v: Params) -> float:
    """End L of the film (mm): min(10ℓ, R/2); the body is lubricated within L of its axis.

    Beyond it the gap exceeds ~50 h_start: the film carries ≲ (ℓ/L)³ (2D) or
    ≲ (ℓ/L)² (3D) of the load there, and Reynolds' thin-film equation with its
    growing conductance h³ (ill-conditioned rows) has no business there.  The
    references are taken with the same extent.
    """
    return min(10 * length(v), 0.5 * v.R)


def speed_scale(v: Params) -> float:
    """Approach speed (mm/s): V, or under load the rigid squeeze's F/K(h_start)."""
    if v.control == "speed":
        return abs(v.V)
    return v.F / squeeze_resistance(hertz_dim(v.dim), v.R, v.mu, v.h_start, extent(v))


class Model(NamedTuple):
    """What :func:`build` assembles: the stepper (bodies, transient film).

    ``plane``: the plane's (or the block's) rigid position, a Constant (mm).
    """

    stepper: Stepper
    plane: fem.Constant


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD,
          checkpoint: str | os.PathLike[str] | None = None) -> Model:
    """Body, transient film and stepper at t = 0 (the plane at h_start below the body)."""
    bodies, film, lift = _parts(v, comm)
    film.transient(v.scheme, lumped=v.lumped)
    dim = geometric_dim(v.dim)
    up = np.eye(dim)[dim - 1]
    y0 = float(lift.value[dim - 1])
    schedule = []
    if v.control == "speed":
        schedule = [(lift, lambda t: y0 * up + v.V * t * up)]
    return Model(Stepper([*bodies, film], film, checkpoint=checkpoint, schedule=schedule,
                         name="ehl_squeeze"), lift)


def steady_problem(v: Params, comm: MPI.Comm = MPI.COMM_WORLD) -> Problem:
    """Return the same bodies and film with the chapter's steady rows, as one Problem.

    The benchmarks' comparison of a transient step with a steady solve
    (``benchmarks/bench_squeeze.py``).
    """
    bodies, film, _ = _parts(v, comm)
    return Problem([*bodies, film], name="ehl_squeeze_steady")


def _parts(v: Params, comm: MPI.Comm) -> tuple[list[Body], Film | TwoBodyFilm, fem.Constant]:
    """Return the body (and block), the steady film and the Constant that positions the plane."""
    dim, sphere, R, h0 = geometric_dim(v.dim), hertz_dim(v.dim), v.R, v.h_start
    ell, L = length(v), extent(v)
    h_fine, h_coarse = ell / (8 * 2 ** v.mesh), R / (8 * 2 ** v.mesh)
    msh, ft = hertz_body(dim, R, h_fine, h_coarse, 2 * ell, comm, cap=L)
    names = {("lubricated" if k == "contact" else k): t for k, t in NAMES.items()}
    names["free"] = FREE
    if dim == 2:
        names.pop("symmetry_y")
    mu_s, lm = lame_parameters(v.E1, v.nu1)
    kind = body_kind(v.dim)
    Vs = speed_scale(v)
    K0 = squeeze_resistance(sphere, R, v.mu, h0, L)
    # momentum rows relative to the film's force, far below the body's stiffness
    # G·L^(d−1); not below the round-off of a node's internal force, ~ε G h^(d−1) on
    # the coarse elements h (×100), so a stiff body (the rigid limit) converges
    f_s = fraction(v) * K0 * Vs
    node = h_coarse ** (dim - 1) * (2 * math.pi * R if v.dim == AXISYMMETRIC else 1.0)
    rtol = max(1e-10, 100 * np.finfo(float).eps * mu_s * node / f_s)
    body = Body(msh, ft, names, kind, ("neo-hookean", {"mu": mu_s, "lmbda": lm}),
                name="body", force_scale=f_s, rtol=rtol)
    body.add_dirichlet("symmetry_x", 0.0, component=0)
    if dim == 3:
        body.add_dirichlet("symmetry_y", 0.0, component=1)
    up = np.eye(dim)[dim - 1]
    if v.control == "speed":
        body.add_dirichlet("loaded", np.zeros(dim))
    else:   # the model's part of F, uniform over the top face (its discrete area)
        one = fem.form(fem.Constant(msh, 1.0) * body.weight * body.ds(body.tag("loaded")))
        area = msh.comm.allreduce(fem.assemble_scalar(one), op=MPI.SUM)
        body.add_traction("loaded", fem.Constant(msh, -fraction(v) * v.F / area * up))
    p_c = K0 * Vs / (ell if sphere == 2 else ell * ell)
    # Reynolds rows: flux scale U·h_ref = V ℓ (the squeeze flux), not below the
    # round-off ε p_c h_L³/(12μ h) of a row at the rim, where the gap h_L is largest
    h_L = h0 + R - math.sqrt(R * R - L * L)
    floor = 100 * np.finfo(float).eps * p_c * h_L**3 / (12 * v.mu * h_coarse)
    fluid = Fluid(viscosity(v), density(v, v.cavitation))
    kw = dict(supg=v.supg, scales=FilmScales(pressure=p_c, film=h0, speed=Vs * ell / h0),
              rtol=max(1e-10, floor / (Vs * ell)), cavitation=named_cavitation(v.cavitation))
    bodies = [body]
    if math.isinf(v.E2):
        film = Film(body, "lubricated", rigid_plane(np.zeros(dim), up), fluid, **kw)
    else:      # a block [0, 2L] × [−H2, 0] under the body (axisymmetric: a disc; 3D: the
        # quarter [0, 2L]² × [−H2, 0]), held (and lifted) at its bottom
        H2 = 2 * L if v.H2 is None else v.H2
        if dim == 3:
            mb, fb = contact_block(2 * L, H2, h_fine, h_coarse, 2 * ell, comm)
            block_names = {"lubricated": TOP, "loaded": BOTTOM, "symmetry_x": SYMMETRY_X,
                           "symmetry_y": SYMMETRY_Y, "free": SIDES}
        else:
            mb, fb = hertz_body(2, 2 * L, h_fine, h_coarse, 2 * ell, comm, block=2 * L,
                                depth=None if v.H2 is None else H2)
            block_names = names
        mu_b, lm_b = lame_parameters(v.E2, v.nu2)
        block = Body(mb, fb, block_names, kind, ("neo-hookean", {"mu": mu_b, "lmbda": lm_b}),
                     name="block", force_scale=f_s, rtol=rtol)
        block.add_dirichlet("symmetry_x", 0.0, component=0)
        if dim == 3:
            block.add_dirichlet("symmetry_y", 0.0, component=1)
        lift = block.add_dirichlet("loaded", np.zeros(dim))
        msh.geometry.x[:, dim - 1] += h0     # the body's lowest point h0 above the block
        film = TwoBodyFilm(body, "lubricated", block, "lubricated", fluid, **kw)
        bodies.append(block)

    def rim(X: npt.NDArray[np.float64]) -> npt.NDArray[np.bool_]:
        return np.sum(X[:dim - 1] ** 2, axis=0) > (L * (1 - 1e-6)) ** 2

    if v.cavitation == "jfo":     # the rim opens to a flooded reservoir: p = 0, λ = 0
        film.add_reservoir(rim, 0.0)
        # no flux through the planes of symmetry (the axis x = 0 of the section)
        film.add_symmetry(lambda X: np.any(np.abs(X[:dim - 1]) < 1e-9 * L, axis=0))
    else:
        film.add_pressure_bc(rim)
    if math.isinf(v.E2):
        film.place_countersurface(h0, np.zeros(3))
        lift = cast("AnalyticObstacle", film.counterpart).offset   # the rigid plane's
    return bodies, film, lift


def progress_total(v: Params) -> int:
    """Time steps to T."""
    return nominal_steps(v.T, v.dt)


def vtx_fields(model: Model) -> dict[str, list[fem.Function]]:
    """Displacement of the body; film pressure (on Γ_l)."""
    film = model.stepper.wear
    return {"displacement": [film.body.u], "pressure": [film.p]}


def plot(profile: dict[str, Any], outdir: Path) -> None:
    """``squeeze.png``: film and force against time; ``squeeze_profiles.png``."""
    from ..plots.film import plot_squeeze

    plot_squeeze(profile, outdir)


def measures(model: Model, v: Params, y0: float) -> dict[str, float]:
    """One step's measures: film at the centre and its minimum, force, plane position."""
    dim, film = geometric_dim(v.dim), model.stepper.wear
    prof = film.profile(everywhere=True)
    r = np.linalg.norm(prof["X"][:, :dim - 1], axis=1)
    h_c = float(prof["h"][np.argmin(r)])
    force = float(film.force()[dim - 1]) / fraction(v)
    return {"h_center": h_c, "h_min": film.min_film(), "force": force,
            "approach": float(model.plane.value[dim - 1]) - y0,
            "p_center": float(prof["p"][np.argmin(r)]),
            "content": film.content() / fraction(v)}


def run(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
        checkpoint: str | os.PathLike[str] | None = None, resume: bool = False) -> Model:
    """Step the squeeze from t = 0 (or the checkpoint) to T; per-step records."""
    model = build(v, checkpoint=checkpoint)
    stepper = model.stepper
    stepper.verbose = verbose
    film, dim, sphere = stepper.wear, geometric_dim(v.dim), hertz_dim(v.dim)
    keys = ("time", "h_center", "h_min", "force", "approach", "p_center", "content",
            "newton_iterations", "force_rigid", "h_center_rigid")
    sr = SlowTimeRecords(stepper, v, record, keys, {"displacement": [film.body.u]},
                         resume)
    y0 = sr.history.setdefault("y0", float(model.plane.value[dim - 1]))
    R, mu, L = v.R, v.mu, extent(v)

    def log(t: float, its: int) -> None:
        m = measures(model, v, y0)
        h_rigid = v.h_start - m["approach"]     # the rigid body's gap at the plane
        m["force_rigid"] = (squeeze_resistance(sphere, R, mu, h_rigid, L) * v.V
                            if v.control == "speed" else v.F)
        m["h_center_rigid"] = (h_rigid if v.control == "speed" else float(
            squeeze_film_under_load(sphere, R, mu, v.F, v.h_start, [t], L)[0]))
        sr.log(its, dict(time=t, newton_iterations=its, **m))

    if not resume:
        log(0.0, 0)
    with sr.closing(report=lambda: _report(film, record, sr.hist), model=model):
        stepper.run(v.T, FixedStep(v.dt), progress=progress,
                    on_step=sr.written(lambda st, rep: log(st.t, rep.iterations)))
    return model


def _report(film: Film | TwoBodyFilm, record: RunRecord, hist: dict[str, list[Any]]
            ) -> None:
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
