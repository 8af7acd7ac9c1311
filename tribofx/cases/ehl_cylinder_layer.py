"""Soft-EHL: rigid cylinder sliding against a coated elastic layer (chapter §8.2, plane strain).

A rigid cylinder of radius R slides at speed U over an elastic layer of
thickness H bonded to a rigid substrate; the top t_c of the layer is a stiffer
coating.  The lubricant film between them carries the load W per unit length.
Configuration on the core: a :class:`~tribofx.body.Body` (the layer, moving
through its mesh with v = F V, V = (U, 0), eq. 26: the frame of the cylinder), a
:class:`~tribofx.interfaces.Film` on Γ_l against a rigid cylinder (closed form,
or an interval3 arc projected by the C++ kernel, ``countersurface=mesh``), one
:class:`~tribofx.problem.Problem` and :class:`~tribofx.continuation.Continuation`
controllers: the cylinder's vertical position is found by a secant for each load
(:class:`~tribofx.hold.Hold`), the loads W/steps, …, W are
marched with step cutting, ``speeds`` continues the final load in U (geometric
steps, cut on failure) and records friction coefficient, h_min, p_max against μU.

Film options: ``cavitation`` penalty (Swift–Stieber limit) or jfo (void fraction λ,
(57), flooded inlet at X = −x_l); ``alpha``: S_α = (1 − α) P(γ_l) + α γ_l (Fig. 23);
``shear``; ``model=linear`` the classical EHL model; ``compare=linear``
(Fig. 22) or ``alpha`` (Fig. 23) runs the load sweep per variant (results prefixed
``finite_``/``linear_``, ``alpha0_``/…); mesh levels: :mod:`tribofx.studies.ehl_convergence`.

Defaults (mm, N, s, MPa): R = 10; H = 5, E = 10; t_c = 0.1, E_c = 100; ν = 0.45,
neo-Hookean; μ = 1e-7, U = 1000, μU = 1e-4 N/mm (Fig. 22); W = 1 N/mm in 10 steps;
|X| ≤ x_l = 3 lubricated on a layer of half width 3H.  Your own layer (``mesh_file``):
:mod:`tribofx.cases.ehl_cylinder_layer`.

Results: h_min, h_central (below the axis), p_max, friction coefficient (tangential
film force / W), clearance per load step; ``profiles.png``; VTX of u and p at the end
and per converged load and speed (``[variant_]displacement_series.bp``, its (W, U)
in ``series_points``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple, cast

import numpy as np
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms.hyperelastic import lame_parameters
from ..hold import Hold
from ..interfaces import Film, FilmScales, Fluid
from ..interfaces.film_options import named_cavitation
from ..meshes.layer import BOTTOM, COATING, LAYER, LUBRICATED, coated_layer
from ..meshes.user import read_user_mesh
from ..obstacles import rigid_cylinder, rigid_surface_mesh
from ..params import InputError, param
from ..positions import parabolic_vertex
from ..problem import Problem, options_name
from ..references import rigid_clearance
from ..restart import SweepJournal
from ..sweep import SweepVariant, journalled_march
from .film_setup import (
    FluidParams,
    density,
    film_boundary,
    formulation_param,
    speed_list,
    viscosity,
)

if TYPE_CHECKING:
    import os
    from collections.abc import Callable, Mapping, Sequence
    from pathlib import Path

    import numpy.typing as npt
    from dolfinx import fem
    from tqdm import tqdm

    from ..body import Material
    from ..continuation import Iterations
    from ..obstacles import AnalyticObstacle, MeshedObstacle
    from ..output import RunRecord

__all__ = ["COMPARE", "COMPARE_PLOT", "UNITS", "USER_CELLS", "USER_GROUPS", "Model", "Params",
           "arc_half_angle", "build", "check_film_length", "check_user_ends", "cylinder_arc", "doc",
           "load_control", "measures", "name", "place_user_layer", "plot", "progress_total",
           "read_user_layer", "resumable", "run", "scales", "set_speed", "slope", "speed_sweep",
           "sweep", "validate", "vtx_fields"]


#: boundary names a user's layer must carry
USER_GROUPS = ("lubricated", "bottom")


#: cell groups of a user's coated layer: E and E_c (optional)
USER_CELLS = ("layer", "coating")


def read_user_layer(v: Params, comm: MPI.Comm, material: Callable[[float], Material]
                    ) -> tuple[dmesh.Mesh, dmesh.MeshTags | None, dmesh.MeshTags, dict[str, int],
                               Material | dict[int, Material], float]:
    """Read and place the layer of ``v.mesh_file``; its materials from ``material(E)``.

    Returns ``(msh, ct, ft, names, materials, x_l)``: ``ct`` the cell tags (None
    without cell groups), ``names`` {group: tag}, ``materials`` {cell tag: law}
    (one law without cell groups), ``x_l`` half the x extent of Γ_l (mm).
    """
    msh, ft, names, ct, cells = read_user_mesh(v.mesh_file, comm, 2, USER_GROUPS,
                                               cells=USER_CELLS)
    x_l = place_user_layer(msh, ft, names["lubricated"])
    if "coating" in cells and "layer" not in cells:
        raise InputError(f"{v.mesh_file!r} has the cell group 'coating' but no "
                         "'layer' (the layer's cells, modulus E)")
    moduli = {"layer": v.E, "coating": v.E_c}
    materials = ({tag: material(moduli[name]) for name, tag in cells.items()} if cells
                 else material(v.E))
    return msh, ct, ft, names, materials, x_l


def place_user_layer(msh: dmesh.Mesh, ft: dmesh.MeshTags, tag: int) -> float:
    """Move a user's layer: Γ_l (facets ``tag``) highest at y = 0, x extent centred at 0.

    Returns x_l, half the x extent of Γ_l (mm).
    """
    comm = msh.comm
    msh.topology.create_connectivity(1, 2)
    x = msh.geometry.x
    nodes = np.unique(dmesh.entities_to_geometry(msh, 1, ft.find(tag), False).ravel())
    lo = comm.allreduce(float(np.min(x[nodes, 0], initial=np.inf)), op=MPI.MIN)
    hi = comm.allreduce(float(np.max(x[nodes, 0], initial=-np.inf)), op=MPI.MAX)
    top = comm.allreduce(float(np.max(x[nodes, 1], initial=-np.inf)), op=MPI.MAX)
    x[:, 0] -= 0.5 * (lo + hi)
    x[:, 1] -= top
    return 0.5 * (hi - lo)


def check_user_ends(film: Film, v: Params) -> None:
    """Raise InputError unless the user's Γ_l is one open curve ending at X = ±x_l.

    The pressure conditions (p = 0 at both ends, the JFO inlet at X = −x_l)
    need it; a closed or split curve has 0 or more than 2 end points.
    """
    ends = film_boundary(film)
    x_l = v.x_l
    if len(ends) != 2 or not np.allclose(np.sort(ends[:, 0]), [-x_l, x_l], atol=1e-9 * x_l):
        raise InputError(f"the group 'lubricated' of {v.mesh_file!r} must be one open "
                         f"curve ending at its two x extremes (has {len(ends)} end "
                         f"point(s) at x = {', '.join(f'{e:.4g}' for e in ends[:, 0])})")


NAMES = {"lubricated": LUBRICATED, "bottom": BOTTOM}


def cylinder_arc(R: float, n: int, alpha: float
                 ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int32], str]:
    """Lower arc θ ∈ [−π/2 − α, −π/2 + α] of the circle of radius R about 0 (mm).

    ``n`` interval3 facets (v0, v1, midpoint), counter-clockwise so that the facet
    normal (t_y, −t_x) points out of the cylinder, into the film.
    Returns (nodes, facets, "interval3").
    """
    th = np.linspace(-0.5 * math.pi - alpha, -0.5 * math.pi + alpha, 2 * n + 1)
    nodes = R * np.c_[np.cos(th), np.sin(th)]
    k = 2 * np.arange(n)
    return nodes, np.c_[k, k + 2, k + 1].astype(np.int32), "interval3"


name = "ehl-cylinder-layer"
#: writes a checkpoint every step: `--resume` continues an interrupted run
resumable = True
doc = "soft-EHL: rigid cylinder sliding on a coated elastic layer (finite or linear)"


@dataclass(frozen=True)
class Params(FluidParams):
    """The parameters of ``ehl-cylinder-layer`` (``--set KEY=VALUE``)."""

    W: float = param(1.0, "N/mm", "final load per unit length", lower=0.0)
    steps: int = param(
        10, "-",
        "load increments (W/steps, 2W/steps, …, W)",
        lower=1, upper=1000, closed=True)
    mu: float = param(1e-7, "MPa·s", "viscosity (1e-7 MPa·s = 0.1 Pa·s)", lower=0.0)
    U: float = param(1000.0, "mm/s", "sliding speed of the cylinder", lower=0.0)
    R: float = param(10.0, "mm", "cylinder radius", lower=0.0)
    H: float = param(5.0, "mm", "layer thickness (coating included)", lower=0.0)
    E: float = param(10.0, "MPa", "Young's modulus of the layer", lower=0.0)
    t_c: float = param(0.1, "mm", "coating thickness (0: no coating)", lower=0.0, closed=True)
    E_c: float = param(100.0, "MPa", "Young's modulus of the coating", lower=0.0)
    nu: float = param(0.45, "-", "Poisson's ratio (layer and coating)", lower=-1.0, upper=0.5)
    x_l: float = param(3.0, "mm", "half length of the lubricated zone (p = 0 at ±x_l)", lower=0.0)
    model: str = param(
        "finite", "-",
        "finite deformation or geometrically linear (EHL)",
        choices=("finite", "linear"))
    shear: bool = param(True, "-", "Couette and Poiseuille shear tractions on the layer")
    supg: bool = param(True, "-", "SUPG stabilisation of the Reynolds equation")
    formulation: str = formulation_param("displacement")
    penalty: float = param(
        1e-6, "-",
        "relative cavitation penalty ε/ε_ref, ε_ref = 24 μ R/h_r², h_r = rigid film at W",
        lower=0.0)
    mesh: int = param(
        1, "-",
        "refinement: element size 0.04/2^mesh mm along Γ_l",
        lower=0, upper=6, closed=True)
    degree: int = param(2, "-", "Lagrange degree of the displacement", choices=(1, 2))
    countersurface: str = param(
        "analytic", "-",
        "cylinder in closed form, or meshed (interval3 arc, C++ projection kernel)",
        choices=("analytic", "mesh"))
    cs_facets: int = param(
        400, "-",
        "interval3 facets of the meshed cylinder arc",
        lower=1, upper=100000, closed=True)
    cavitation: str = param(
        "penalty", "-",
        "penalty (Swift–Stieber limit) or jfo (mass-conserving, void fraction λ)",
        choices=("penalty", "jfo"))
    alpha: float = param(
        0.0, "-",
        "lubrication surface S_α = (1 − α) P(γ_l) + α γ_l (0: S = P(γ_l), 1: S = γ_l)",
        lower=0.0, upper=1.0, closed=True)
    speeds: str = param(
        "", "mm/s",
        "comma-separated sliding speeds for continuation in U at the final load W "
        "(empty: none); records the friction coefficient vs μU")
    compare: str = param(
        "none", "-",
        "one load sweep per variant in the same run: linear (model = finite and "
        "linear, Fig. 22) or alpha (α = 0, 0.5, 1, Fig. 23); results prefixed by "
        "the variant",
        choices=("none", "linear", "alpha"))
    mesh_file: str = param(
        "", "-",
        "your own layer: a 2D gmsh .msh with physical groups lubricated (Γ_l, one "
        "open curve under the cylinder) and bottom (u = 0), and optionally the cell "
        "groups layer (E) and coating (E_c; else one material E); replaces H, x_l "
        "(half the x extent of Γ_l), mesh and t_c; moved so that Γ_l's highest node "
        "is at y = 0, its x extent centred below the cylinder axis")


#: variants of ``compare``: (summary key prefix, plot label, parameter overrides)
COMPARE: dict[str, tuple[tuple[str, str, dict[str, Any]], ...]] = {
    "linear": (("finite", "finite deformation", {"model": "finite"}),
               ("linear", "geometrically linear", {"model": "linear"})),
    "alpha": (("alpha0", "α = 0 (S = P(γ_l))", {"alpha": 0.0}),
              ("alpha0.5", "α = 0.5", {"alpha": 0.5}),
              ("alpha1", "α = 1 (S = γ_l)", {"alpha": 1.0})),
}


COMPARE_PLOT = {"linear": "profiles_finite_vs_linear.png", "alpha": "profiles_alpha.png"}


UNITS = {"W": "N/mm", "h_min": "mm", "h_central": "mm", "p_max": "MPa",
         "friction_coefficient": "-", "clearance": "mm", "U": "mm/s", "mu_U": "N/mm"}


def validate(v: Params) -> None:
    """Geometric consistency of the layer and the lubricated zone.

    With ``mesh_file`` H, t_c and x_l come from the mesh; x_l ≤ 0.8 R is then
    checked when the mesh is read (:meth:`build`).
    """
    if not v.mesh_file:
        if v.t_c >= v.H:
            raise InputError(f"coating t_c = {v.t_c} mm must be thinner than "
                             f"H = {v.H} mm")
        if v.x_l >= 3 * v.H:
            raise InputError(f"x_l = {v.x_l} mm must be < 3H = {3 * v.H} mm")
        check_film_length(v.x_l, v.R)
    speeds = speed_list(v)
    viscosity(v)
    density(v, v.cavitation)
    if v.cavitation == "jfo" and not v.U > 0:
        raise InputError("cavitation=jfo needs U > 0")
    if v.compare != "none" and speeds:
        raise InputError("speeds (continuation in U) is not available with compare")
    if v.compare == "alpha" and v.model != "finite":
        raise InputError("compare=alpha is a study of the finite-deformation model")


def check_film_length(x_l: float, R: float) -> None:
    """Raise InputError unless the film zone |X| ≤ x_l lies below the cylinder (x_l ≤ 0.8 R)."""
    if x_l > 0.8 * R:
        raise InputError(f"x_l = {x_l:.6g} mm must be < 0.8 R (film beyond the cylinder)")


def scales(v: Params, W: float | None = None, U: float | None = None
           ) -> tuple[float, float, float]:
    """Rigid film h_r (mm), pressure scale (MPa) and penalty ε (MPa·s/mm) at W and U."""
    W, U = (v.W if W is None else W), (v.U if U is None else U)
    h_r = rigid_clearance(W, v.mu, U, v.R)
    ell = math.sqrt(2 * v.R * h_r)
    return h_r, 6 * v.mu * U * ell / h_r**2, v.penalty * 12 * v.mu * ell**2 / h_r**3


def arc_half_angle(v: Params) -> float:
    """Half angle (rad) of the meshed arc: covers the film zone |x| ≤ x_l with 25 % margin."""
    return math.asin(min(0.95, 1.25 * v.x_l / v.R))


class Model(NamedTuple):
    """What :func:`build` assembles: the layer, the film under the rigid cylinder, the problem."""

    layer: Body
    film: Film
    problem: Problem


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD, intermediate: bool = False,
          name: str = "ehl_cylinder") -> Model:
    """Body, film and problem (unloaded; the cylinder at the rigid clearance of W/steps).

    ``name``: the problem's name (options prefix ``tribofx_<name>_``; a variant of
    ``compare`` is ``ehl_cylinder_<variant>``).

    ``alpha = 0`` uses S = P(γ_l) unless ``intermediate`` (then the general S_α
    kinematics with α = 0, for checking that they coincide).  ``mesh_file``:
    the user's layer (see the module docstring), ``x_l`` taken from it.
    """
    H = v.H
    law = "linear" if v.model == "linear" else "neo-hookean"

    def mat(E: float) -> Material:
        mu, lm = lame_parameters(E, v.nu)
        return (law, {"mu": mu, "lmbda": lm})

    if v.mesh_file:
        msh, ct, ft, names, materials, x_l = read_user_layer(v, comm, mat)
        v = v.replace(x_l=x_l)
        check_film_length(x_l, v.R)
    else:
        msh, ct, ft = coated_layer(3 * H, H, v.t_c, v.x_l, 0.04 / 2 ** v.mesh,
                                   H / 5, comm)
        names = NAMES
        materials = {LAYER: mat(v.E)} | ({COATING: mat(v.E_c)} if v.t_c > 0
                                           else {})
    layer = Body(msh, ft, names, "plane_strain", materials, cell_tags=ct,
                 degree=v.degree, velocity=(v.U, 0.0), name="layer",
                 formulation=v.formulation)
    layer.add_dirichlet("bottom", np.zeros(2))
    if v.countersurface == "mesh":
        nodes, facets, ctype = cylinder_arc(v.R, v.cs_facets, arc_half_angle(v))
        cylinder = rigid_surface_mesh(nodes + [0.0, v.R], facets, ctype)
    else:
        cylinder = rigid_cylinder(np.array([0.0, v.R]), v.R)
    h_r, p_s, eps = scales(v, v.W / v.steps)
    film = Film(layer, "lubricated", cylinder, Fluid(viscosity(v), density(v, v.cavitation)),
                scales=FilmScales(pressure=p_s, film=h_r, speed=v.U),
                cavitation=named_cavitation(v.cavitation, eps if v.penalty > 0 else None),
                model=v.model, shear=v.shear, supg=v.supg,
                alpha=v.alpha if (v.alpha > 0 or intermediate) else None)
    if v.mesh_file:
        check_user_ends(film, v)
    if v.cavitation == "jfo":
        film.add_inlet(lambda X: np.isclose(X[0], -v.x_l))
    else:
        film.add_pressure_bc()
    problem = Problem([layer, film], name=name, max_it=25)
    cast("AnalyticObstacle | MeshedObstacle", film.counterpart).offset.value[1] = h_r
    film.jfo_initial_guess()
    return Model(layer, film, problem)


def sweep(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
          prefix: str = "", journal: SweepJournal | None = None) -> Model:
    """Load sweep (and speed continuation) of one variant; results prefixed ``prefix``.

    ``journal``: a :class:`tribofx.restart.SweepJournal`; the variant
    (:class:`tribofx.sweep.SweepVariant`) journals its legs — the load march, then
    the march to each speed — after every converged load and speed, and a resumed
    variant continues where it stopped.
    """
    name = prefix[:-1] or v.model
    run = build(v, name=options_name("ehl_cylinder", prefix[:-1]))
    layer, film, problem = run.layer, run.film, run.problem
    assert layer.velocity is not None   # built with the sliding velocity (build)
    journal = journal or SweepJournal(None, layer.mesh.comm, v)
    record.data["num_dofs"] = problem.num_dofs
    var = SweepVariant(journal, name, run, problem.state_fields() + [layer.velocity],
                       record, vtx_fields(run), prefix, ("steps", "speed", "profiles"),
                       layer.mesh.comm, progress)
    steps, speed, profiles, its = (var[k] for k in ("steps", "speed", "profiles", "its"))

    def write(m: Mapping[str, Any]) -> None:
        assert layer.velocity is not None   # built with the sliding velocity (build)
        var.write([m["W"], float(layer.velocity.value[0])])

    def on_step() -> None:
        m = measures(run, v)
        profiles.append(dict(m.pop("profile"), W=m["W"]))
        steps.append(m)
        write(m)
        if progress is not None:
            progress.update(1)

    def on_speed() -> None:
        m = measures(run, v)
        m.pop("profile")
        assert layer.velocity is not None   # built with the sliding velocity (build)
        m["U"] = float(layer.velocity.value[0])
        speed.append(m)
        write(m)

    if prefix:
        record.data.setdefault("variant_newton_iterations", {})[name] = its
    loads, inner = load_control(run, v, on_step, verbose, its)
    # the variant journals its legs (the loads, then each speed): the inner position
    # search's secant state and the film's scales are part of its position
    var.track(inner=inner)
    var.keep("scales", film.scale_values, lambda kept: film.set_scales(**kept))
    if var.resumed:
        var.resume()
        problem.refresh()
    with var:
        try:
            first_speed = not var.finished("loads")
            var.march("loads", loads, v.W, steps=v.steps, predictor=False)
            if speed_list(v):
                if first_speed:
                    speed.append(dict(steps[-1], U=v.U))
                speed_sweep(run, v, inner, v.W, speed_list(v), on_speed, its, journal=var)
        finally:
            _report(steps, speed, profiles, v, record, prefix)
    return run


def run(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
        checkpoint: str | os.PathLike[str] | None = None, resume: bool = False) -> Model:
    """Load sweep W/steps … W (per variant of ``compare``); records the film measures.

    ``checkpoint``: directory of the sweep's checkpoint (written after every
    converged load and speed); ``resume``: continue from it.
    """
    journal = SweepJournal(checkpoint, MPI.COMM_WORLD, v, resume)
    record.result("mu_U", v.mu * v.U, "N/mm")
    if v.compare == "none":
        return sweep(v, record, progress, verbose, journal=journal)
    record.result("variants", [name for name, _, _ in COMPARE[v.compare]])
    first = None
    for name, label, over in COMPARE[v.compare]:
        run = sweep(v.replace(**over), record, progress, verbose, prefix=f"{name}_",
                        journal=journal)
        first = first or run
        if MPI.COMM_WORLD.rank == 0:
            record.profile["variants"][name]["label"] = label
            record.profile["compare"] = v.compare
    assert first is not None   # every compare has variants
    return first


def measures(run: Model, v: Params) -> dict[str, Any]:
    """Film measures on all ranks: h_min, h_central, p_max, W, friction, clearance."""
    film = run.film
    prof, f = film.profile(everywhere=True), film.force()
    xx = prof["y"][:, 0] if v.model == "finite" else prof["X"][:, 0]
    return {"h_min": float(prof["h"].min()), "h_central": float(np.interp(0, xx, prof["h"])),
            "p_max": float(prof["p"].max()), "x_p_max": parabolic_vertex(xx, prof["p"]),
            "profile": {"x": xx, "p": prof["p"], "h": prof["h"]}, "W": -float(f[1]),
            "tangential_force": float(f[0]),
            "friction_coefficient": abs(f[0] / f[1]) if f[1] < 0 else math.nan,
            "clearance": float(cast("AnalyticObstacle | MeshedObstacle",
                                    film.counterpart).offset.value[1])}


def _report(steps: list[dict[str, Any]], speed: list[dict[str, Any]],
            profiles: list[dict[str, Any]], v: Params, record: RunRecord, prefix: str) -> None:
    keys = ("W", "h_min", "h_central", "p_max", "friction_coefficient", "clearance")
    if steps:
        for k in keys[1:5]:
            record.result(prefix + k, steps[-1][k], UNITS[k])
        record.result(prefix + "W_reached", steps[-1]["W"], "N/mm")
    for k in keys:
        record.result(f"{prefix}steps_{k}", [m[k] for m in steps], UNITS[k])
    for m in speed:
        m["mu_U"] = v.mu * m["U"]
    if len(speed) > 1:
        for k in ("U", "mu_U", "friction_coefficient", "h_min", "p_max", "clearance"):
            record.result(f"{prefix}speed_{k}", [m[k] for m in speed], UNITS[k])
    if MPI.COMM_WORLD.rank == 0:
        prof = record.profile or {"variants": {}}
        prof["variants"][prefix[:-1] or v.model] = {
            "label": prefix[:-1] or v.model, "steps": profiles,
            "speed": ([m["mu_U"] for m in speed], [m["friction_coefficient"] for m in speed])}
        record.profile = prof


def progress_total(v: Params) -> int:
    """Points the progress bar counts: the loads of every variant."""
    return v.steps * (1 if v.compare == "none" else len(COMPARE[v.compare]))


def vtx_fields(run: Model) -> dict[str, list[fem.Function]]:
    """Displacement (bulk) and film pressure (Γ_l submesh)."""
    layer, film = run.layer, run.film
    return {"displacement": [layer.u], "pressure": [film.p]}


def plot(profile: dict[str, Any], outdir: Path) -> None:
    """``profiles.png`` (or the ``compare`` plot) and ``friction_vs_speed.png``."""
    from ..plots import plot_film_profiles, plot_friction_vs_speed

    variants = profile["variants"]
    if "compare" in profile:
        title = ("coated layer: finite deformation vs geometrically linear"
                 if profile["compare"] == "linear" else "coated layer: lubrication surface S_α")
        plot_film_profiles(None, outdir / COMPARE_PLOT[profile["compare"]], title,
                           variants)
        return
    (name, var), = variants.items()
    plot_film_profiles(var["steps"], outdir / "profiles.png",
                       f"coated layer, model = {name}")
    if len(var["speed"][0]) > 1:
        plot_friction_vs_speed({None: var["speed"]}, outdir / "friction_vs_speed.png")


def load_control(run: Model, v: Params, on_step: Callable[[], object] | None = None,
                 verbose: bool = False, record: list[Iterations] | None = None
                 ) -> tuple[Continuation, Continuation]:
    """Load control by the cylinder position: (outer load march, inner position search).

    The inner secant on 1/W (linear in s for a rigid film, s = 2.45 μUR/W, the
    first update) finds the position s at which the film carries the held
    load; the outer march steps the load with step cutting.  ``on_step()`` runs
    at every converged load; ``record`` receives the Newton iterations of the
    trials of each load.
    """
    film, problem = run.film, run.problem
    cylinder = cast("AnalyticObstacle | MeshedObstacle", film.counterpart)   # rigid
    inner = Continuation(problem, ConstantParameter(cylinder.offset, 1),
                         response=lambda: -1 / film.force()[1], rtol=1e-6, max_trials=30,
                         verbose=verbose)
    held = Hold(inner, 0.0, transform=lambda W: 1 / W, slope=slope(run, v))
    return Continuation(held, held, response=lambda: held.target, record=record,
                        on_accept=on_step), inner


def slope(run: Model, v: Params) -> Callable[[float], float]:
    """d(1/W)/ds = 1/(2.45 μUR) of the rigid film at the current speed (1/(N·mm⁻¹·mm))."""
    assert run.layer.velocity is not None   # built with the sliding velocity (build)
    U = run.layer.velocity.value
    return lambda W: 1 / rigid_clearance(1.0, v.mu, U[0], v.R)


def set_speed(run: Model, v: Params, U: float) -> None:
    """Sliding speed U (mm/s) with the penalty, SUPG and tolerance scales that follow it."""
    layer, film = run.layer, run.film
    assert layer.velocity is not None   # built with the sliding velocity (build)
    layer.velocity.value[0] = U
    h_r, p_s, eps = scales(v, U=U)
    film.set_scales(p_c=p_s, eps=eps, film_scale=h_r, speed_scale=U)


def speed_sweep(run: Model, v: Params, inner: Continuation, W: float, speeds: Sequence[float],
                on_speed: Callable[[], object] | None = None,
                record: list[Iterations] | None = None,
                journal: SweepVariant | None = None) -> None:
    """Continuation in the sliding speed at the load W (N/mm) reached last by ``inner``.

    Each speed of ``speeds`` (mm/s) is reached by a geometric march (a failed step
    is cut in log U) with the load held by the cylinder position; penalty, SUPG
    and tolerance scales follow U.  ``on_speed()`` runs after every converged
    speed step.  ``journal``: the sweep's variant, which journals each speed as a
    leg ``speed<j>`` (a resumed run continues there).
    """
    layer = run.layer
    assert layer.velocity is not None   # built with the sliding velocity (build)
    held = Hold(inner, W, transform=lambda W: 1 / W, slope=slope(run, v))
    sweep = Continuation(held, ConstantParameter(
        layer.velocity, 0, on_set=lambda U: set_speed(run, v, U)),
        record=record, on_accept=on_speed)
    for j, U in enumerate(speeds):
        journalled_march(journal, f"speed{j}", sweep, U, predictor=False, geometric=True)
