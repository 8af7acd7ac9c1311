"""Soft-EHL: elastic ball sliding against a rigid plane (chapter §8.3, 3D quarter model).

A neo-Hookean ball (radius R, centre (0, 0, R)) is pressed with the load W
against a rigid plane sliding under it (ball-on-disc, pure sliding).  Quarter
model: lower hemisphere, half y ≥ 0, u_y = 0 on the symmetry plane y = 0, the
mid-plane z = R held and the plane z = z_p moved instead (the same rigid
translation; the clearance s = −z_p of the undeformed ball's lowest point is
reported).  Ball frame: the ball is at rest, the plane slides at V = 2U e_x, so
v̄ = U e_x (U the entrainment speed; μU the chapter's control parameter).

Configuration on the core: a 3D :class:`~tribofx.body.Body`, a
:class:`~tribofx.interfaces.Film` on the lubricated cap Γ_l (polar angle ≤ θ_l)
against :func:`~tribofx.obstacles.rigid_plane` moving with ``V_counter`` = 2U e_x
(p = 0 on the cap's boundary circle, zero flux on y = 0, penalty cavitation,
SUPG, traction (46), ``shear`` switching its shear part, ``model=linear`` the
classical EHL model with a small-strain ball), one
:class:`~tribofx.problem.Problem`, and :class:`~tribofx.continuation.Continuation`
for the plane position along the paths of :mod:`tribofx.cases.ehl_ball`
(Hertz start and a secant on W; large loads by a thick film, then the speed
marched down).

Defaults (mm, N, s, MPa; Stupkiewicz et al. 2016): R = 12.7, E = 1.19, ν = 0.45
(E* = 1.49 ≈ 240/R², Hertz a ≈ R/2 at 40 N); μ = 1e-8 (10 mPa·s), U = 1e4:
μU = 1e-4 N/mm (0.1 N/m); W = 10 N in 3 steps; θ_l = 40°.  The solid is the
mixed (u, p) one and the film's terms are taken at the nodes (``quadrature=auto``:
the vertex rule; Gauss points with JFO and on ``mesh=0``, :func:`film_rule`):
together they remove the node-to-node zig-zag of a thin film over a nearly
incompressible ball (a locked P1 surface; the chord sag h_e²/8R inside a facet) at
a third of the unknowns the displacement solid with Gauss points needs.
Element size a/(4·2^mesh) within 1.6 a; ``mesh`` and ``edge_refine`` default to
the cheapest pair of :data:`LEVELS` that resolves the film's outlet constriction
at the run's W and U (elements along the contact edge ≤ 2ℓ, ℓ = a (h_c R/a²)^{2/3});
the default point keeps ``mesh=1``.  The chapter's point W = 40 N, μU = 0.078 N/m
(Figs. 25–26) gets ``mesh=1 edge_refine=2`` (a/8, a/32 along the contact edge; 29k
unknowns) and needs θ_l = 60° (a smaller cap is refused at once); each load is
reached on a thick film at 30U and the last one marched down in speed in ratios
≤ 2 (110 s on 2 ranks: ``benchmarks/bench_ehl_ball_chapter_point.py``).  The
displacement solid (``formulation=displacement``) needs ``mesh=2 edge_refine=1``
there (64k unknowns); on ``mesh=1`` it converges to a film that zig-zags node to
node in the Hertzian zone and dips far below the Hamrock–Dowson film (h_central
2.3 µm against 16.8 µm).  A mesh set explicitly that does not resolve the outlet
runs with a warning; a point no built mesh resolves is refused at validation.
The chapter's point with the three models of Fig. 26:

    tribofx run ehl-ball --set W=40 --set U=7800 --set theta_l=60 --set compare=all

A soft disc (``E2`` finite, ``nu2``, ``H2``): the plane becomes the top of an
elastic half block [−L₂, L₂] × [0, L₂] × [−H₂, 0] (L₂ = 1.25 R sin θ_l, H₂ default
4 a(W)) held at its bottom, whose support Constant the load search moves in
place of the plane's offset (``Model.position``); its material slides at 2U (the
ball at rest), the film is :class:`~tribofx.interfaces.TwoBodyFilm` in 3D, the
dry start puts the Hertz pressure on both surfaces, and E* is the pair's.

``cavitation=jfo``: the mass-conserving film on the cap's triangles (void fraction λ,
:func:`tribofx.forms.jfo.jfo_on_surface`); the rim is an open end supplied with the
content c_in where v̄ points in (``ReynoldsFilm.add_inflow``), flooded (the rim's gap)
for the loads; a finite ``supply`` then starves the film at W, c_in marched down in
ratios ≤ 1.5 (:func:`supply_march`): the inlet meniscus moves in and the central
film falls (h_c/h_cff 0.99, 0.96, 0.82 at c_in = 4, 2, 1 h_cff; W = 2 N, mesh 1).
Not robust on every step sequence: near the rim λ ≈ 1 − h_c/h_rim ≈ 0.99, and from
some converged states Newton steps to λ ≥ 1, where the clamped rows are singular.

Your own ball (``mesh_file``, a gmsh quarter ball with the groups ``lubricated``,
``midplane``, ``symmetry``): :mod:`tribofx.cases.ehl_ball`.

``compare=all``: full model, no shear tractions and geometrically linear in one
run (Fig. 26; prefixes ``full_``, ``no-shear_``, ``linear_``); ``speeds`` (mm/s)
continues every variant at the final load in U (friction coefficient against
μU, Fig. 27).  Results: h_central (on the axis at x = 0), h_min (and where),
p_max, friction coefficient (x-force of the traction on the ball / W; without
shear only its pressure part), the Couette friction coefficient (drag / W, for
every variant), the plane's friction coefficient (x-force of the film on the
plane / W, :meth:`tribofx.interfaces.Film.counter_force`: the shear stress of
the film at the plane, every variant; see below), the clearance; Hertz and
Hamrock–Dowson references; plots
``film_map.png``, ``centerline.png``, ``friction_vs_speed.png``; VTX of u and p at the
end and as time series (``[variant_]displacement_series.bp``, ``..._pressure_series.bp``,
one time index per converged load and speed, its (W, U) in ``series_points``).
The position of h_min is the vertex of a quadratic fitted to the film nodes
around the smallest nodal h (:func:`tribofx.positions.paraboloid_vertex`).

``film_oscillation`` (the node-to-node zig-zag of h) and the friction on the ball
and on the plane: :mod:`tribofx.cases.ehl_ball`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple, cast

import numpy as np
from dolfinx import fem
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms.hyperelastic import lame_parameters
from ..hold import Hold
from ..interfaces import JFO, Film, FilmScales, Fluid, Penalty, Quadrature, TwoBodyFilm
from ..meshes.ball import BALL_NAMES, cap_height, quarter_ball
from ..meshes.block3d import BOTTOM, SIDES, SYMMETRY_Y, TOP, contact_block
from ..meshes.user import read_user_mesh
from ..motions import Rolling, Sliding
from ..obstacles import rigid_plane
from ..params import InputError, param
from ..positions import oscillation_indicator, paraboloid_vertex
from ..problem import NewtonDivergence, Problem, options_name
from ..references import composite_modulus, hamrock_dowson, hertz
from ..restart import SweepJournal
from ..sweep import SweepVariant, journalled_march, journalled_points
from . import film_setup
from .film_setup import FluidParams, at_points, density, film_boundary, speed_list, viscosity

if TYPE_CHECKING:
    import os
    from collections.abc import Callable, Mapping, Sequence
    from pathlib import Path

    import numpy.typing as npt
    from tqdm import tqdm

    from ..continuation import Iterations
    from ..obstacles import AnalyticObstacle
    from ..output import RunRecord
    from ..references import HertzContact

__all__ = ["DISC_NAMES", "FILM_OSCILLATION_TOL", "LEVELS", "MAX_EDGE_RATIO", "UNITS",
           "USER_GROUPS", "VARIANTS", "Z", "EntrainmentSpeed", "Model", "Params", "ball_fine_size",
           "build", "check_curvature", "checked_outlet_width", "disc_size", "doc", "e_star",
           "edge_size", "film_oscillation", "film_rule", "follow_control", "hertz_contact",
           "hertz_slope", "hertz_start", "large_load", "load", "load_sweep", "measures",
           "mesh_levels", "name", "outlet_width", "place_user_ball", "plot", "position_control",
           "progress_total", "resolves_outlet", "resumable", "run", "scales", "set_scales",
           "speed_constants", "speed_march", "speed_parameter", "surface_speeds", "sweep",
           "thick_film_sweep", "user_rim", "validate", "vtx_fields"]


#: largest element size along the contact edge, in units of the outlet width ℓ
MAX_EDGE_RATIO = 2.0


#: (mesh, edge_refine) in the order of their cost, by solid.  The mixed solid needs
#: the fine elements along the contact edge only (29k unknowns at 40 N for mesh=1
#: edge_refine=2: film_oscillation 0.017); the displacement solid locks inside the
#: Hertzian zone and zig-zags there unless the whole zone is refined (mesh=1
#: edge_refine=2 gave h_c 2.4 µm against 16.8; mesh=2 edge_refine=1, 64k: 0.062)
LEVELS = {"mixed": ((1, 0), (1, 1), (1, 2), (2, 2), (3, 2)),
          "displacement": ((1, 0), (2, 1), (2, 2), (3, 2))}


def outlet_width(v: Params) -> float:
    """Width ℓ = a (h_c R / a²)^{2/3} (mm) of the outlet constriction at ``v``'s W and U."""
    a = hertz(v.W, v.R, v.E, v.nu).a
    h_c = hamrock_dowson(v.W, v.mu, v.U, v.R, composite_modulus(v.E, v.nu))[0]
    return a * (h_c * v.R / a**2) ** (2 / 3)


def checked_outlet_width(v: Params) -> float:
    """Return :func:`outlet_width`, or raise InputError (one line) if it is not finite."""
    try:
        ell = outlet_width(v)
    except (ArithmeticError, ValueError):
        ell = math.nan
    if not 0 < ell < math.inf:
        raise InputError(f"W = {v.W:g} N, U = {v.U:g} mm/s, R = {v.R:g} mm, "
                         f"E = {v.E:g} MPa give no finite film scale (Hamrock–Dowson)")
    return ell


def edge_size(v: Params, mesh: int, edge_refine: int) -> float:
    """Element size (mm) along the contact edge: a/(4·2^mesh)/2^edge_refine."""
    return hertz(v.W, v.R, v.E, v.nu).a / (4 * 2**mesh) / 2**edge_refine


def mesh_levels(v: Params) -> tuple[int, int, bool]:
    """``(mesh, edge_refine, resolved)`` of the run.

    Both set by the user: those (``resolved`` says whether they meet the rule).
    One set: the cheapest value of the other that resolves the outlet (h_edge ≤
    2ℓ); none: the cheapest entry of :data:`LEVELS` that does.  If none does,
    the finest candidate with ``resolved`` False.
    """
    mesh, refine = v.mesh, v.edge_refine
    if mesh is not None and refine is not None:
        candidates = [(mesh, refine)]
    elif mesh is not None:
        candidates = [(mesh, e) for e in range(4)]
    elif refine is not None:
        candidates = [(m, refine) for m in (1, 2, 3)]
    else:
        candidates = list(LEVELS[v.formulation])
    ell = outlet_width(v)
    for m, e in candidates:
        if edge_size(v, m, e) <= MAX_EDGE_RATIO * ell * (1 + 1e-12):
            return m, e, True
    return (*candidates[-1], False)


Z = 2  # the plane's normal direction, index of its offset

#: the soft disc's boundaries (:func:`tribofx.meshes.block3d.contact_block`, half model)
DISC_NAMES = {"lubricated": TOP, "support": BOTTOM, "symmetry": SYMMETRY_Y, "free": SIDES}


def ball_fine_size(v: Params) -> float:
    """Element size near the contact (mm): a/(4·2^mesh), a the Hertz radius at W."""
    return hertz_contact(v).a / (4 * 2 ** mesh_levels(v)[0])


#: largest speed ratio of one step of a speed march (a larger one starts the held-load
#: secant far from the new film: at 40 N the step 30U → U fails and is cut, at 40 trials
#: each time; steps of ratio 2 converge in 2–3 position trials each)
MAX_SPEED_RATIO = 2.0
# content ratio of a step of supply_march (c_in from the rim's gap to `supply`)
MAX_SUPPLY_RATIO = 1.5


USER_GROUPS = ("lubricated", "midplane", "symmetry")   # the groups of a user's ball


def _group_nodes(msh: dmesh.Mesh, ft: dmesh.MeshTags, tag: int) -> npt.NDArray[np.int32]:
    """Return the local geometry nodes of the facets tagged ``tag``."""
    msh.topology.create_connectivity(2, 3)
    return np.unique(dmesh.entities_to_geometry(msh, 2, ft.find(tag), False).ravel())


def place_user_ball(msh: dmesh.Mesh, ft: dmesh.MeshTags, names: Mapping[str, int], v: Params,
                    a: float) -> None:
    """Move a user's ball: symmetry plane to y = 0, cap centred at x = 0, lowest at z = 0.

    Raises InputError if the symmetry group is not a plane y = const (to 10⁻⁹ R).
    """
    comm, x = msh.comm, msh.geometry.x

    def extent(nodes: npt.NDArray[np.int32], k: int) -> tuple[float, float]:
        return (comm.allreduce(float(np.min(x[nodes, k], initial=np.inf)), op=MPI.MIN),
                comm.allreduce(float(np.max(x[nodes, k], initial=-np.inf)), op=MPI.MAX))

    y0, y1 = extent(_group_nodes(msh, ft, names["symmetry"]), 1)
    if y1 - y0 > 1e-9 * v.R:
        raise InputError(f"the group 'symmetry' of {v.mesh_file!r} must be a plane "
                         f"y = const (spans y = {y0:.6g} … {y1:.6g} mm)")
    cap = _group_nodes(msh, ft, names["lubricated"])
    x0, x1 = extent(cap, 0)
    z0, _ = extent(cap, 2)
    x -= np.array([0.5 * (x0 + x1), y0, z0])
    check_curvature(msh, cap, v, a)


def check_curvature(msh: dmesh.Mesh, cap: npt.NDArray[np.int32], v: Params, a: float
                    ) -> None:
    """Raise InputError unless the cap's curvature at the contact is 1/R within 5 %.

    Least squares z = c + k ρ²/2 over the cap's nodes within ρ = √(x² + y²) ≤ a
    (Hertz a at W; owned nodes, summed over the ranks): R sets the Hertz start,
    the scales and the references, so it must be the ball's radius where the
    film forms.  A cap with fewer than 6 nodes there is too coarse to resolve
    the contact.
    """
    comm = msh.comm
    own = cap[cap < msh.geometry.index_map().size_local]
    X = msh.geometry.x[own]
    rho2 = X[:, 0] ** 2 + X[:, 1] ** 2
    near = rho2 <= a * a
    q, z = 0.5 * rho2[near], X[near, 2]
    sums = comm.allreduce(np.array([len(q), q.sum(), (q * q).sum(), z.sum(),
                                    (q * z).sum()]), op=MPI.SUM)
    n, sq, sqq, sz, sqz = sums
    det = n * sqq - sq * sq
    if n < 6 or not det > 0:
        raise InputError(f"the cap of {v.mesh_file!r} has {int(n)} node(s) within the "
                         f"Hertz radius a = {a:.3g} mm of the contact point (needs >= 6)")
    k = (n * sqz - sq * sz) / det
    if not abs(k * v.R - 1) <= 0.05:
        raise InputError(f"the cap of {v.mesh_file!r} has the radius of curvature "
                         f"{1 / k if k else math.inf:.4g} mm at the contact: R = "
                         f"{v.R} mm must match it within 5 %")


def user_rim(film: Film, v: Params, a: float) -> npt.NDArray[np.float64]:
    """Return the nodes (k, 3) of the rim of a user's cap: ∂Γ_l less the edges on y = 0.

    Raises InputError if there is none, or if the cap does not reach 1.5 a(W)
    from the contact point (the least rim radius √(x² + y²)).
    """
    tol = 1e-9 * v.R
    rim = film_boundary(film, keep=lambda X: ~np.all(np.abs(X[:, :, 1]) < tol, axis=1))
    if not len(rim):
        raise InputError(f"the group 'lubricated' of {v.mesh_file!r} has no rim off "
                         "the symmetry plane (p = 0 there)")
    r_cap = float(np.min(np.hypot(rim[:, 0], rim[:, 1])))
    if r_cap < 1.5 * a:
        raise InputError(f"the cap of {v.mesh_file!r} reaches r = {r_cap:.3g} mm < "
                         f"1.5 a = {1.5 * a:.3g} mm (Hertz a at W = {v.W} N)")
    return rim


NAMES = BALL_NAMES


name = "ehl-ball"
#: writes a checkpoint every step: `--resume` continues an interrupted run
resumable = True
doc = "soft-EHL: elastic ball sliding on a rigid plane (3D, finite/no-shear/linear)"


@dataclass(frozen=True)
class Params(FluidParams):
    """The parameters of ``ehl-ball`` (``--set KEY=VALUE``)."""

    W: float = param(10.0, "N", "final load on the whole ball", lower=0.0)
    steps: int = param(3, "-", "load increments (W/steps, …, W)", lower=1, upper=100, closed=True)
    mu: float = param(1e-8, "MPa·s", "viscosity (1e-8 MPa·s = 10 mPa·s)", lower=0.0)
    U: float = param(1e4, "mm/s", "entrainment speed U = V/2 (plane slides at 2U)", lower=0.0)
    R: float = param(12.7, "mm", "ball radius", lower=0.0)
    E: float = param(1.19, "MPa", "Young's modulus of the ball", lower=0.0)
    nu: float = param(0.45, "-", "Poisson's ratio of the ball", lower=-1.0, upper=0.5)
    E2: float = param(
        math.inf, "MPa",
        "Young's modulus of the disc under the ball (inf: the rigid plane; finite: an "
        "elastic half block sliding at 2U, the two-body film)",
        lower=0.0, infinite=True)
    nu2: float = param(0.45, "-", "Poisson's ratio of the disc (E2 finite)", lower=-1.0,
                       upper=0.5)
    SRR: float = param(
        2.0, "-",
        "slide-to-roll ratio 2(U2 − U1)/(U1 + U2) of the ball's (U1) and the countersurface's "
        "(U2) surface speeds, U = (U1 + U2)/2: 2 the ball at rest and the countersurface "
        "sliding at 2U (the chapter's), 0 pure rolling (the ball rolls about its centre)",
        lower=-2.0, upper=2.0, closed=True)
    H2: float | None = param(
        None, "mm",
        "thickness of the disc (E2 finite; default 4 a(W), a the Hertz radius of the pair; "
        "its half-width 1.25 R sin theta_l covers the cap)",
        lower=0.0)
    theta_l: float = param(
        40.0, "deg",
        "polar angle of the lubricated cap",
        lower=5.0, upper=75.0, closed=True)
    model: str = param(
        "finite", "-",
        "finite deformation or geometrically linear (EHL)",
        choices=("finite", "linear"))
    shear: bool = param(True, "-", "Couette and Poiseuille shear tractions on the ball")
    supg: bool = param(True, "-", "SUPG stabilisation of the Reynolds equation")
    formulation: str = film_setup.formulation_param("mixed")
    quadrature: str = film_setup.quadrature_param("auto")
    penalty: float = param(
        1e-4, "-",
        "relative cavitation penalty ε/ε_ref, ε_ref = 12 μ a²/h_c³ (Hertz a, "
        "Hamrock–Dowson h_c at W)",
        lower=0.0)
    cavitation: str = param(
        "penalty", "-",
        "penalty (Swift–Stieber limit, p = 0 on the rim) or jfo (mass-conserving, void "
        "fraction λ; the rim an open end supplied with the content `supply`)",
        choices=("penalty", "jfo"))
    supply: float = param(
        math.inf, "mm",
        "cavitation=jfo: the lubricant content c_in carried in through the rim where the "
        "flow enters (layers t₁ + t₂ on the two surfaces; below the flooded film: a "
        "starved contact); inf: flooded (c_in = the rim's gap)",
        lower=0.0, infinite=True)
    mesh: int | None = param(
        None, "-",
        "element size a/(4·2^mesh) near the contact (default: "
        "chosen with edge_refine from W and U to resolve the outlet, edge_size)",
        lower=0, upper=3, closed=True)
    h_coarse: float = param(4.0, "mm", "element size far from the contact", lower=0.0)
    edge_refine: int | None = param(
        None, "-",
        "refinement levels of a band along the edge of the contact zone (the "
        "film's outlet ridge and side lobes): size h/2^level within 0.1 a of the "
        "circle of radius 0.95 a(W) on the undeformed cap (h the size near the "
        "contact; at 40 N the side-lobe minima lie at 0.94 a; default: with mesh)",
        lower=0, upper=3, closed=True)
    start_speed: float = param(
        30.0, "-",
        "loads with Hertz a(W) > R/3: each load is reached at start_speed·U by "
        "displacement control (thick film), then U is continued down to U",
        lower=1.0, closed=True)
    speeds: str = param(
        "", "mm/s",
        "comma-separated entrainment speeds for continuation in U at the final load "
        "(empty: none); records the friction coefficient vs μU")
    compare: str = param(
        "none", "-",
        "all: load sweep (and speeds) of the full model, without shear tractions and "
        "geometrically linear in one run",
        choices=("none", "all"))
    mesh_file: str = param(
        "", "-",
        "your own quarter ball: a 3D gmsh .msh with physical groups lubricated (the "
        "cap, p = 0 on its rim), midplane (u = 0), symmetry (plane y = const); "
        "replaces theta_l, mesh, h_coarse, edge_refine (R, E, nu: Hertz start, scales; cap "
        "curvature 1/R within 5 %); moved: symmetry at y = 0, cap centred at x = 0, "
        "lowest at z = 0")


#: variants of ``compare=all``: (prefix, label, overrides)
VARIANTS = (("full", "finite deformation", {"model": "finite", "shear": True}),
            ("no-shear", "finite, no shear tractions", {"model": "finite", "shear": False}),
            ("linear", "geometrically linear", {"model": "linear", "shear": True}))


UNITS = {"W": "N", "h_central": "mm", "h_min": "mm", "p_max": "MPa",
         "x_h_min": "mm (sub-element)", "y_h_min": "mm (sub-element)",
         "friction_coefficient": "-", "couette_friction_coefficient": "-",
         "plane_friction_coefficient": "-", "clearance": "mm", "U": "mm/s",
         "mu_U": "N/mm", "film_oscillation": "-"}


#: film_oscillation above which the run warns (a zig-zag of ±5 % of the film)
FILM_OSCILLATION_TOL = 0.05


def e_star(v: Params) -> float:
    """Contact modulus E* (MPa): E/(1 − ν²) on the rigid plane, composite on the disc."""
    return composite_modulus(v.E, v.nu, v.E2, v.nu2)


def hertz_contact(v: Params, W: float | None = None) -> HertzContact:
    """Hertz contact of the ball on the rigid plane (or the disc) at W (default ``v.W``, N)."""
    return hertz(v.W if W is None else W, v.R, v.E, v.nu, E2=v.E2, nu2=v.nu2)


def disc_size(v: Params) -> tuple[float, float]:
    """Half-width and thickness (mm) of the disc (E2 finite): 1.25 R sin θ_l and ``H2``."""
    H = 4 * hertz_contact(v).a if v.H2 is None else v.H2
    return 1.25 * v.R * math.sin(math.radians(v.theta_l)), H


def validate(v: Params) -> None:
    """Check that the cap holds the contact and the inlet: R sin θ_l ≥ 1.5 a(W).

    With ``mesh_file`` the cap of the mesh is checked when it is read (:meth:`build`).
    """
    a = hertz_contact(v).a
    r_cap = v.R * math.sin(math.radians(v.theta_l))
    if r_cap < 1.5 * a and not v.mesh_file:
        raise InputError(f"cap radius R sin θ_l = {r_cap:.3g} mm < 1.5 a = {1.5 * a:.3g} mm "
                         f"(Hertz a at W = {v.W} N): increase theta_l")
    if not v.U > 0 or not v.mu > 0:
        raise InputError("U and mu must be positive (entrainment)")
    if v.cavitation == "jfo" and (v.mesh_file or v.model == "linear" or v.compare == "all"):
        raise InputError("cavitation=jfo is built for the built ball and the finite model "
                         "(compare=none)")
    if v.cavitation == "jfo" and v.quadrature == "vertex":
        raise InputError("cavitation=jfo takes quadrature=gauss (or auto): Newton on the "
                         "JFO rows with the vertex rule does not converge")
    if math.isfinite(v.supply) and v.cavitation != "jfo":
        raise InputError("supply (a starved inlet) needs cavitation=jfo")
    if math.isfinite(v.E2) and (v.model == "linear" or v.compare == "all"):
        raise InputError("the soft disc (E2 finite) has the finite-deformation film only: "
                         "model=finite, compare=none")
    checked_outlet_width(v)
    auto = v.mesh is None or v.edge_refine is None
    if auto and not v.mesh_file and not mesh_levels(v)[2]:
        raise InputError(
            f"no built mesh{'' if v.mesh is None else ' with mesh=' + str(v.mesh)}"
            f"{'' if v.edge_refine is None else ' edge_refine=' + str(v.edge_refine)}"
            f" resolves the film's outlet at W = {v.W:g} N, U = {v.U:g} mm/s "
            f"(width {outlet_width(v):.3g} mm): raise U, refine, or give mesh_file")
    viscosity(v)
    density(v)
    speed_list(v)


def scales(v: Params, W: float | None = None, U: float | None = None
           ) -> tuple[float, float, float, float]:
    """Hertz a (mm), p0 (MPa), Hamrock–Dowson h_c (mm) and penalty ε (MPa·s/mm)."""
    W, U = (v.W if W is None else W), (v.U if U is None else U)
    h = hertz_contact(v, W)
    h_c = hamrock_dowson(W, v.mu, U, v.R, e_star(v))[0]
    return h.a, h.p0, h_c, v.penalty * 12 * v.mu * h.a**2 / h_c**3


def set_scales(film: Film, v: Params, W: float, U: float) -> None:
    """SUPG pressure scale p0, penalty ε and tolerance scales at load W and speed U."""
    _, p0, h_c, eps = scales(v, W, U)
    film.set_scales(p_c=p0, eps=eps, film_scale=h_c, speed_scale=U)


class Model(NamedTuple):
    """What :func:`build` assembles: the quarter ball, its film on the plane or disc, the problem.

    ``position``: the Constant whose z component (:data:`Z`) places the countersurface
    (the rigid plane's offset, or the disc's support); ``disc``: the soft disc (E2
    finite) or None; ``ball_speed``: the Constant of the ball's surface speed U1 (a
    rolling ball, ``SRR`` ≠ 2; None: the ball at rest); ``srr``: the slide-to-roll ratio;
    ``supply``: the Constant of the JFO rim's content c_in (mm; None: penalty), built
    flooded (the rim's gap) and marched down to ``supply`` by :func:`supply_march`.
    """

    ball: Body
    film: Film | TwoBodyFilm
    problem: Problem
    position: fem.Constant
    disc: Body | None = None
    ball_speed: fem.Constant | None = None
    srr: float = 2.0
    supply: fem.Constant | None = None


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD, name: str = "ehl_ball") -> Model:
    """Ball, film and problem, unloaded (``mesh_file``: the user's ball, module docstring).

    ``name``: the problem's name, options prefix ``tribofx_<name>_`` (a variant
    of ``compare=all`` is ``ehl_ball_full``, ``ehl_ball_no_shear``, ``ehl_ball_linear``).
    """
    a = hertz_contact(v).a
    th = math.radians(v.theta_l)
    if v.mesh_file:
        msh, ft, names = read_user_mesh(v.mesh_file, comm, 3, USER_GROUPS)
        place_user_ball(msh, ft, names, v, a)
    else:
        level, refine, _ = mesh_levels(v)
        h_fine = ball_fine_size(v)
        ring = (0.95 * a, h_fine / 2**refine, 0.1 * a) if refine else None
        msh, ct, ft = quarter_ball(v.R, th, h_fine, max(v.h_coarse, h_fine),
                                   1.6 * a, comm, ring=ring)
        names = NAMES
    mu, lm = lame_parameters(v.E, v.nu)
    law = "linear" if v.model == "linear" else "neo-hookean"
    ball = Body(msh, ft, names, "3d", (law, {"mu": mu, "lmbda": lm}), name="ball",
                formulation=v.formulation)
    ball.add_dirichlet("midplane", np.zeros(3))
    ball.add_dirichlet("symmetry", 0.0, component=1)
    _, p0, h_c, eps = scales(v, v.W / v.steps)
    cavitation = (JFO() if v.cavitation == "jfo" else Penalty(eps) if v.penalty > 0
                  else None)
    kw: dict[str, Any] = dict(scales=FilmScales(pressure=p0, film=h_c, speed=v.U),
                              cavitation=cavitation,
                              quadrature=Quadrature(film_rule(v), degree=2), shear=v.shear,
                              supg=v.supg)
    disc = ball_speed = supply = None
    film: Film | TwoBodyFilm
    U1, U2 = surface_speeds(v)
    # a rolling ball (SRR ≠ 2) turns about its centre: its lowest point moves along +x
    rolling = None if v.SRR == 2 else Rolling((0.0, 0.0, v.R), v.R, axis=(0.0, -1.0, 0.0))
    if math.isinf(v.E2):
        V_plane = np.array([2 * v.U if v.SRR == 2 else U2, 0.0, 0.0])
        if rolling is not None:
            ball_speed = fem.Constant(ball.mesh, U1)
            kw["motion"] = (rolling, ball_speed)
        film = Film(ball, "lubricated", rigid_plane(np.zeros(3), np.eye(3)[Z]),
                    Fluid(viscosity(v), density(v)), V_counter=V_plane, model=v.model, **kw)
        position = cast("AnalyticObstacle", film.counterpart).offset
    else:      # the soft disc: a half block under the ball, held at its bottom
        L2, H2 = disc_size(v)
        h_fine = ball_fine_size(v)
        mb, fb = contact_block(L2, H2, h_fine, max(v.h_coarse, h_fine), 1.6 * a, comm,
                               quarter=False, half=True)
        mu2, lm2 = lame_parameters(v.E2, v.nu2)
        disc = Body(mb, fb, DISC_NAMES, "3d", ("neo-hookean", {"mu": mu2, "lmbda": lm2}),
                    name="disc", formulation=v.formulation)
        disc.add_dirichlet("symmetry", 0.0, component=1)
        position = disc.add_dirichlet("support", np.zeros(3))
        # the disc's material slides at U2 under the ball (at rest, or rolling at U1)
        film = TwoBodyFilm(ball, "lubricated", disc, "lubricated",
                           Fluid(viscosity(v), density(v)), motion1=rolling, U1=U1,
                           motion2=Sliding((1.0, 0.0, 0.0)), U2=U2, **kw)
        ball_speed = film.U1 if rolling is not None else None
    if v.mesh_file:
        film.add_pressure_bc(at_points(user_rim(film, v, a), 1e-8 * v.R))
    else:
        z_cap = cap_height(v.R, th)
        on_rim = lambda X: np.abs(X[2] - z_cap) < 1e-6 * v.R   # noqa: E731
        if v.cavitation == "jfo":
            # the rim an open end: the supply enters where v̄ points in, the film
            # leaves where it points out, a Robin leak keeps p ≈ 0 (forms.jfo.jfo_inflow);
            # flooded (the rim's gap) until supply_march starves it
            supply = film.add_inflow(on_rim, z_cap)
            # no content crosses the symmetry plane y = 0 (on a disc S is the ball's
            # curved surface, where θ h v_n on the facets' chords is not zero there)
            film.add_symmetry(lambda X: np.abs(X[1]) < 1e-6 * v.R)
        else:
            film.add_pressure_bc(on_rim)
    bodies = [ball] if disc is None else [ball, disc]
    problem = Problem([*bodies, film], name=name, max_it=25)
    return Model(ball, film, problem, position, disc, ball_speed, v.SRR, supply)


def progress_total(v: Params) -> int:
    """Points the progress bar counts: the loads of every variant."""
    return v.steps * (len(VARIANTS) if v.compare == "all" else 1)


def run(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
        checkpoint: str | os.PathLike[str] | None = None, resume: bool = False) -> Model:
    """Load sweep (and speed sweep) of each variant; results prefixed by the variant.

    ``checkpoint``: directory of the sweep's checkpoint, written after every
    converged load and speed step (:class:`tribofx.restart.SweepJournal`);
    ``resume``: continue from it.
    """
    variants = VARIANTS if v.compare == "all" else (("", v.model, {}),)
    journal = SweepJournal(checkpoint, MPI.COMM_WORLD, v, resume)
    record.result("mu_U", v.mu * v.U, "N/mm")
    a, p0, _, _ = scales(v)
    hc, hm = hamrock_dowson(v.W, v.mu, v.U, v.R, e_star(v))
    for key, value in (("hertz_a", a), ("hertz_p0", p0), ("hamrock_dowson_h_c", hc),
                       ("hamrock_dowson_h_min", hm)):
        record.result(key, value, "MPa" if key == "hertz_p0" else "mm")
    if not v.mesh_file:
        level, refine, resolved = mesh_levels(v)
        record.data["mesh_levels"] = {"mesh": level, "edge_refine": refine}
        if not resolved:
            record.warn(f"mesh={level} edge_refine={refine}: elements of "
                        f"{edge_size(v, level, refine):.3g} mm along the contact edge "
                        f"> {MAX_EDGE_RATIO:g} × the outlet width {outlet_width(v):.3g} mm "
                        "at this W and U: expect a zig-zag or a spurious dip of the film")
        if level == 0 and (v.formulation, film_rule(v)) == ("mixed", "vertex"):
            # measured at the default point's speed: 2 and 3 N converge, 4 N does not
            # (a node's film reaches h <= 0 in the Newton homotopy); either alone does
            record.warn("mesh=0 with the mixed solid and the vertex rule: Newton may "
                        "not converge above a few N; use mesh >= 1, or "
                        "quadrature=auto or gauss on this mesh")
    record.data["variant_newton_iterations"] = {}
    record.profile = {"variants": {}, "W": v.W}
    first = None
    for name, label, over in variants:
        run = sweep(v.replace(**over), name, label, record, journal, progress, verbose)
        first = first or run
    assert first is not None   # every run has a variant
    return first


def sweep(vv: Params, name: str, label: str, record: RunRecord, journal: SweepJournal,
          progress: tqdm | None = None, verbose: bool = False) -> Model:
    """Run the loads, then the speeds of ``speeds``, of one variant; returns its run.

    The variant (:class:`tribofx.sweep.SweepVariant`) journals its legs — the
    loads, then the march to each speed — after every converged load and speed
    step (the state, the records, the position search's secant state, the march's
    increments, the film's scales); a resumed variant continues on the same
    sequence of steps.
    """
    key = name or vv.model
    run = build(vv, name=options_name("ehl_ball", name))
    film, problem = run.film, run.problem
    record.data["num_dofs"] = problem.num_dofs
    # (the plane's offset is state); the series' "time" is the point's index, its
    # (W, U) in series_points
    sv = SweepVariant(journal, key, run,
                      [*problem.state_fields(), *speed_constants(run),
                       *([run.supply] if run.supply is not None else [])],
                      record, vtx_fields(run), f"{name}_" if name else "",
                      ("steps", "speed"), run.ball.mesh.comm, progress)
    steps, speed, its_all = sv["steps"], sv["speed"], sv["its"]
    record.data["variant_newton_iterations"][key] = its_all
    var = {"label": label, "shear": vv.shear}
    record.profile["variants"][key] = var

    def write() -> None:
        sv.write([load(run), speed_parameter(run).get()])

    def on_step(W: float, its: Sequence[Iterations]) -> None:
        its_all.append([i for t in its for i in (t if isinstance(t, list) else [t])])
        if steps:   # the film map is kept for the last load only (checkpoint size)
            steps[-1].pop("profile", None)
        steps.append(dict(measures(run, vv), U=speed_parameter(run).get()))
        write()
        if progress is not None:
            progress.update(1)

    def on_speed() -> None:
        m = measures(run, vv)
        m.pop("profile")
        speed.append(dict(m, U=speed_parameter(run).get()))
        write()

    # the variant journals its legs (the loads, then each speed) with the film's scales
    sv.keep("scales", film.scale_values, lambda kept: film.set_scales(**kept))
    with sv:
        try:
            first_speed = not sv.finished("loads")
            inner = load_sweep(run, vv, on_step, verbose, journal=sv)
            if math.isfinite(vv.supply):     # starve the flooded film at W
                supply_march(run, vv, inner, vv.W, record=its_all, journal=sv)
                steps[-1] = dict(measures(run, vv), supply=vv.supply)
                write()
            if speed_list(vv) and first_speed:
                on_speed()
            for j, U in enumerate(speed_list(vv)):
                speed_march(run, vv, inner, vv.W, U, restart=not large_load(vv),
                            record=its_all, on_speed=on_speed, journal=sv, leg=f"speed{j}")
        finally:
            if steps:
                var.update({k: np.asarray(x) for k, x in steps[-1]["profile"].items()})
            _report(steps, speed, vv, record, f"{name}_" if name else "")
            var["speed"] = {k: [m[k] for m in speed] for k in (
                "mu_U", "friction_coefficient", "couette_friction_coefficient",
                "plane_friction_coefficient")}
    return run


def film_oscillation(h_axis: npt.ArrayLike, p_axis: npt.ArrayLike) -> float:
    """Zig-zag of h on the centre line where p > p_max/2 (see the module docstring)."""
    p_axis = np.asarray(p_axis)
    return oscillation_indicator(np.asarray(h_axis), p_axis, 0.5 * p_axis.max(initial=0))


def measures(run: Model, v: Params) -> dict[str, Any]:
    """h_central, h_min (x, y), p_max, W, friction coefficients, clearance (all ranks)."""
    film = run.film
    prof, f, fc = film.profile(everywhere=True), film.force(), film.couette_force()
    # the force on the countersurface: the plane's wall traction, or the disc's reaction
    f_plane = (film.counter_force() if run.disc is None
               else cast("TwoBodyFilm", film).forces()[1])
    xy = (prof["x"] if v.model == "finite" else prof["X"])[:, :2]
    on = np.abs(prof["X"][:, 1]) < 1e-9 * v.R          # the symmetry line y = 0
    order = np.argsort(xy[on, 0])
    xx, hh, pp = xy[on, 0][order], prof["h"][on][order], prof["p"][on][order]
    i = int(np.argmin(prof["h"]))
    # where h is least, between nodes (tribofx.positions); y ≥ 0 in the quarter model
    x_min, y_min = paraboloid_vertex(xy, prof["h"], "min")
    per_load = 1 / float(f[Z]) if f[Z] > 0 else math.nan
    return {"h_central": float(np.interp(0.0, xx, hh)), "h_min": float(prof["h"][i]),
            "film_oscillation": film_oscillation(hh, pp),
            "x_h_min": x_min, "y_h_min": max(y_min, 0.0),
            "p_max": float(prof["p"].max()),
            "profile": {"xy": xy, "h": prof["h"], "p": prof["p"], "x_axis": xx,
                        "h_axis": hh, "p_axis": pp},
            "W": 2.0 * float(f[Z]), "friction_force": 2.0 * float(f[0]),
            "friction_coefficient": abs(float(f[0])) * per_load,
            "couette_friction_coefficient": abs(float(fc[0])) * per_load,
            "plane_friction_coefficient": abs(float(f_plane[0])) * per_load,
            "clearance": -float(run.position.value[Z])}


def _report(steps: list[dict[str, Any]], speed: list[dict[str, Any]], v: Params,
            record: RunRecord, prefix: str) -> None:
    keys = ("h_central", "h_min", "x_h_min", "y_h_min", "p_max", "friction_coefficient",
            "couette_friction_coefficient", "plane_friction_coefficient", "clearance",
            "film_oscillation")
    for m in steps:  # a journal without film_oscillation: from its centre-line profile
        if "film_oscillation" not in m:
            m["film_oscillation"] = (film_oscillation(m["profile"]["h_axis"],
                                                          m["profile"]["p_axis"])
                                     if "profile" in m else math.nan)
    for m in steps + speed:   # ... or without the force on the plane: NaN
        m.setdefault("plane_friction_coefficient", math.nan)
    if steps:
        for k in keys:
            record.result(prefix + k, steps[-1][k], UNITS[k])
        if steps[-1]["film_oscillation"] > FILM_OSCILLATION_TOL:
            who = f"{prefix.rstrip('_')}: " if prefix else ""
            record.warn(f"{who}film zig-zags node to node by ±"
                        f"{100 * steps[-1]['film_oscillation']:.0f} % on the centre line "
                        f"(W = {steps[-1]['W']:.3g} N): the mesh does not resolve it; "
                        "refine (mesh, edge_refine)")
        record.result(prefix + "W_reached", steps[-1]["W"], "N")
    for k in ("W",) + keys:
        record.result(f"{prefix}steps_{k}", [m[k] for m in steps], UNITS[k])
    # the speed of each load (U, or the thick film's where the mesh does not resolve
    # an intermediate load at U: thick_film_sweep); not in journals written before
    if steps and all("U" in m for m in steps):
        record.result(f"{prefix}steps_U", [m["U"] for m in steps], "mm/s")
    for m in speed:
        m["mu_U"] = v.mu * m["U"]
    if len(speed) > 1:
        for k in ("U", "mu_U", "friction_coefficient", "couette_friction_coefficient",
                  "plane_friction_coefficient", "h_central", "h_min", "p_max"):
            record.result(f"{prefix}speed_{k}", [m[k] for m in speed], UNITS[k])


def vtx_fields(run: Model) -> dict[str, list[fem.Function]]:
    """Displacement (bulk) and film pressure (cap submesh)."""
    ball, film = run.ball, run.film
    return {"displacement": [ball.u], "pressure": [film.p]}


def plot(profile: dict[str, Any], outdir: Path) -> None:
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


def speed_parameter(run: Model, on_set: Callable[[float], object] | None = None
                    ) -> ConstantParameter | EntrainmentSpeed:
    """Entrainment speed U (mm/s) as a continuation parameter (the plane slides at 2U).

    With a slide-to-roll ratio the countersurface moves at (1 + SRR/2)U and the ball's
    surface at (1 − SRR/2)U (:class:`EntrainmentSpeed`, both Constants).
    """
    srr = run.srr
    counter, *ball = speed_constants(run)
    # (the plane's velocity, a vector Constant, or the disc's U2)
    parts = [ConstantParameter(counter, 0 if run.disc is None else None, scale=1 + srr / 2)]
    if not ball:
        parts[0].on_set = on_set
        return parts[0]
    parts.append(ConstantParameter(ball[0], None, scale=1 - srr / 2))
    return EntrainmentSpeed(parts, on_set)


class EntrainmentSpeed:
    """A continuation parameter U that sets several speeds, each ``scale``·U.

    ``parts``: :class:`~tribofx.continuation.ConstantParameter` s (the
    countersurface's and the ball's speeds); ``get`` reads the first with a non-zero
    scale; ``on_set(U)`` runs once after each change.
    """

    def __init__(self, parts: list[ConstantParameter],
                 on_set: Callable[[float], object] | None = None) -> None:
        self.parts, self.on_set = parts, on_set

    def get(self) -> float:
        """Return U (mm/s)."""
        return next(p for p in self.parts if p.scale != 0).get()

    def set(self, value: float) -> None:
        """Set every speed to its multiple of ``value`` (then ``on_set``)."""
        for p in self.parts:
            p.set(value)
        if self.on_set is not None:
            self.on_set(float(value))


def surface_speeds(v: Params) -> tuple[float, float]:
    """Return the ball's and the countersurface's surface speeds U1, U2 (mm/s)."""
    return (1 - v.SRR / 2) * v.U, (1 + v.SRR / 2) * v.U


def speed_constants(run: Model) -> list[fem.Constant]:
    """Return the Constants of the speeds: the countersurface's, then the ball's (if it rolls)."""
    counter = (cast("TwoBodyFilm", run.film).U2 if run.disc is not None
               else cast("fem.Constant", run.film.V_counter))
    return [counter] + ([run.ball_speed] if run.ball_speed is not None else [])


def hertz_start(run: Model, v: Params, W: float, U: float) -> None:
    """Dry ball under the Hertz pressure at W, the plane at the film h_c(W, U) (all ranks)."""
    h = hertz_contact(v, W)
    def pressure(x: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        return h.pressure(np.hypot(x[0], x[1]))

    h_c = scales(v, W, U)[2]
    if isinstance(run.film, TwoBodyFilm):   # the disc is moved with its support
        run.film.start_from_pressure(pressure, h_c, np.zeros(3), support=run.position)
    else:
        run.film.start_from_pressure(pressure, h_c, np.zeros(3))
    run.film.jfo_initial_guess(downstream=(1.0, 0.0, 0.0))   # JFO: λ of the start


def load(run: Model) -> float:
    """Load W (N) carried by the film on the whole ball: twice the half model's F_z."""
    return 2.0 * float(run.film.force()[Z])


def position_control(run: Model, v: Params, verbose: bool = False,
                     on_set: Callable[[float], object] | None = None,
                     record: list[Iterations] | None = None) -> Continuation:
    """Secant on the load W(z_p) in the plane position z_p (steps ≤ 0.1 δ_Hertz).

    A converged film with min h ≤ 0 or W ≤ 0 (an unphysical branch) is rejected.
    """
    film, problem = run.film, run.problem
    return Continuation(problem, ConstantParameter(run.position, Z, on_set),
                        response=lambda: load(run), rtol=1e-4, max_trials=40,
                        verbose=verbose, max_step=0.1 * hertz_contact(v).delta,
                        admissible=lambda: film.min_film() > 0 and load(run) > 0,
                        record=record)


def hertz_slope(v: Params) -> Callable[[float], float]:
    """dW/dz_p = 1.5 W/δ(W) (N/mm) of a Hertz contact, as a function of W."""
    return lambda W: 1.5 * W / hertz_contact(v, W).delta


def load_sweep(run: Model, v: Params,
               on_step: Callable[[float, Sequence[Iterations]], object] | None = None,
               verbose: bool = False, journal: SweepVariant | None = None) -> Continuation:
    """Reach W/steps, …, W at the speed U; returns the position controller.

    ``on_step(W, iterations)`` after each load (the Newton trials of the load).
    ``journal``: the sweep's variant, which journals the loads as its leg
    ``loads`` (and puts a resumed run back where it stopped).
    """
    if large_load(v):
        return thick_film_sweep(run, v, on_step, verbose, journal)
    film, problem = run.film, run.problem
    W1 = v.W / v.steps
    inner = position_control(run, v, verbose)
    offset = run.position.value   # the plane's (the disc's support)
    # each trial sequence starts at the current position: the converged first
    # state, then the Hertz state predicted for each further load
    held = Hold(inner, W1, slope=hertz_slope(v), guess=lambda: float(offset[Z]))
    if journal is not None:
        journal.track(inner=inner)
        if journal.resumed:
            journal.resume()
            problem.refresh()
    its0: Iterations = 0
    for k in journalled_points(journal, "loads", v.steps):
        if k == 0:
            hertz_start(run, v, W1, v.U)
            its0 = problem.solve_by_homotopy(verbose=verbose).iterations
            if not film.min_film() > 0:
                raise NewtonDivergence(
                    f"the first load W = {W1:g} N converged to a film with h <= 0 (contact "
                    "under-resolved by the mesh): raise mesh or use fewer load steps")
        else:
            held.predict = lambda W: hertz_start(run, v, W, v.U)
        held.target = v.W * (k + 1) / v.steps
        its = held.solve(verbose).iterations
        if on_step is not None:
            on_step(held.target, [its0, *its] if k == 0 else its)
    return inner


def thick_film_sweep(run: Model, v: Params,
                     on_step: Callable[[float, Sequence[Iterations]], object] | None = None,
                     verbose: bool = False, journal: SweepVariant | None = None
                     ) -> Continuation:
    """Large loads: displacement control on a thick film at U_s, then continue down to U.

    (i) At U_s = ``start_speed``·U the Hertz state at W_0 = min(W/steps, W/4)
    is solved (if it fails: U_s ×0.3, ×3, ×0.1, ×10, never below U); (ii) the
    plane is raised by displacement control until the film carries the next
    load (:meth:`Continuation.advance`, scales following the load reached);
    (iii) from that state U is marched down to U at fixed load
    (:meth:`speed_march`) and the load recorded — at W always, at an intermediate
    load only where the mesh, made for W, resolves that load's outlet at U
    (:func:`resolves_outlet`; elsewhere the load is recorded at U_s, ``steps_U``:
    at U a Newton step from such a film fails, the 13.3 N step of the chapter's
    point after 18 min), so that an intermediate load is never harder to reach
    than W; (iv) the next load continues from the state at U_s.  ``journal``: as
    for :func:`load_sweep`; its position keeps U_s, the load reached last and (as
    arrays) the state at U_s.
    """
    film, problem = run.film, run.problem
    U, speed = v.U, speed_parameter(run)
    at: dict[str, float] = {}     # the thick film's speed U_s and the load reached last
    carrier: list[Any] = []       # the state at U_s the next load starts from
    its: list[Iterations] = []
    # the search of the last load, which the speed legs use (a resumed run's)
    inner = follow_control(run, v, v.W, v.W, verbose)
    resumed = journal is not None and journal.resumed
    if journal is not None:
        journal.track(inner=inner)
        journal.keep("thick_film", lambda: dict(at), at.update)
        if resumed:
            carrier[:] = journal.resume()
            problem.refresh()
    if not resumed:
        W0 = min(v.W / v.steps, 0.25 * v.W)
        for f in (1.0, 0.3, 3.0, 0.1, 10.0):
            Us = max(U, f * v.start_speed * U)
            speed.set(Us)
            set_scales(film, v, W0, Us)
            hertz_start(run, v, W0, Us)
            try:
                its = [problem.solve(verbose=verbose).iterations]
            except NewtonDivergence:
                continue
            if film.min_film() > 0:
                break
        else:
            raise NewtonDivergence(f"the start load W = {W0:g} N did not converge: change "
                                   "start_speed or mesh")
        at.update(Us=Us, W_start=load(run))
    first = True
    for k in journalled_points(journal, "loads", v.steps, arrays=lambda: carrier):
        Us = at["Us"]
        if resumed and first:       # the next load starts from the thick-film state
            problem.restore(carrier)
            speed.set(Us)
            set_scales(film, v, at["W_start"], Us)
        first = False
        Wk = v.W * (k + 1) / v.steps
        inner = follow_control(run, v, Wk, at["W_start"], verbose, its)
        if journal is not None:
            journal.track(inner=inner)
        inner.advance(Wk, 0.05 * hertz_contact(v).delta)
        set_scales(film, v, Wk, Us)
        carrier[:] = problem.state()
        # (``inner`` records the Newton trials of each speed step)
        if Us != U and (k + 1 == v.steps or resolves_outlet(v, Wk)):
            speed_march(run, v, inner, Wk, U)
        if on_step is not None:
            on_step(Wk, its)
        its, at["W_start"] = [], Wk
        if k + 1 < v.steps and Us != U:
            problem.restore(carrier)
            speed.set(Us)
            set_scales(film, v, Wk, Us)
    return inner


def follow_control(run: Model, v: Params, Wk: float, W_start: float, verbose: bool = False,
                   record: list[Iterations] | None = None) -> Continuation:
    """Position control towards the load Wk whose scales follow the load reached.

    Every trial position sets the scales of the load reached last (≤ Wk;
    ``W_start`` before the first) at the current speed.
    """
    film, speed = run.film, speed_parameter(run)

    def follow(z: float) -> None:
        # (the search's responses are loads: floats)
        W_ref = min(cast(float, inner.history[-1][1]), Wk) if inner.history else W_start
        set_scales(film, v, W_ref, speed.get())

    inner = position_control(run, v, verbose, on_set=follow, record=record)
    return inner


def speed_march(run: Model, v: Params, inner: Continuation, W: float, U: float,
                restart: bool = False, record: list[Iterations] | None = None,
                on_speed: Callable[[], object] | None = None,
                journal: SweepVariant | None = None, leg: str = "speed") -> None:
    """Continue the converged state at load W in the entrainment speed to U (geometric).

    Each speed step re-finds the plane position for W (``inner``), starting
    from the Hertz state at the new speed (``restart``) or from the plane
    shifted by the Hamrock–Dowson change of the film, h_c((U_new/U_old)^0.64 − 1).
    A failed step is cut (six times at most).  ``on_speed()`` after every
    converged step; ``journal``: the sweep's variant, which journals the march as
    its leg ``leg``.
    """
    film = run.film
    offset = run.position.value   # the plane's (the disc's support)
    speed = speed_parameter(run, on_set=lambda Uv: set_scales(film, v, W, Uv))
    last = {"U": speed.get()}

    def shifted() -> float:
        h_c = measures(run, v)["h_central"]
        return float(offset[Z]) - h_c * ((speed.get() / last["U"]) ** 0.64 - 1)

    def accepted() -> None:
        last["U"] = speed.get()
        if on_speed is not None:
            on_speed()

    held = Hold(inner, W, slope=hertz_slope(v),
                        guess=(lambda: float(offset[Z])) if restart else shifted,
                        predict=(lambda Wt: hertz_start(run, v, Wt, speed.get()))
                        if restart else None)
    march = Continuation(held, speed, record=record, on_accept=accepted)
    # speed ratios of at most MAX_SPEED_RATIO per step (a failed step is cut further)
    steps = max(1, int(np.ceil(abs(np.log(U / speed.get())) / np.log(MAX_SPEED_RATIO))))
    kw: dict[str, Any] = dict(steps=steps, predictor=False, geometric=True,
                              min_fraction=2.0**-6)
    journalled_march(journal, leg, march, U, **kw)


def supply_march(run: Model, v: Params, inner: Continuation, W: float,
                 record: list[Iterations] | None = None,
                 journal: SweepVariant | None = None) -> None:
    """Starve the converged flooded film at load W: the rim's content c_in down to ``supply``.

    Geometric steps of ratio ≤ :data:`MAX_SUPPLY_RATIO` (a failed step is cut, six
    times at most), each re-finding the position that carries W (``inner``) from the
    current one: from the flooded film the inlet meniscus moves in step by step (a
    starved start from the flooded guess does not converge).  ``journal``: the
    sweep's variant, which journals the march as its leg ``supply``.
    """
    assert run.supply is not None       # a JFO film (build)
    offset = run.position.value
    held = Hold(inner, W, slope=hertz_slope(v), guess=lambda: float(offset[Z]))
    march = Continuation(held, ConstantParameter(run.supply), record=record)
    steps = max(1, int(np.ceil(np.log(float(run.supply.value) / v.supply)
                               / np.log(MAX_SUPPLY_RATIO))))
    journalled_march(journal, "supply", march, v.supply, steps=steps, predictor=False,
                     geometric=True, min_fraction=2.0**-6)


def resolves_outlet(v: Params, W: float) -> bool:
    """Whether the run's mesh resolves the outlet constriction of the load ``W`` at U.

    The mesh is made for the final load ``v.W`` (:func:`build`): size h/2^edge_refine
    within w = 0.1 a of the circle 0.95 a (a = a(v.W), h = :func:`ball_fine_size`),
    growing linearly to h at 2w (:func:`tribofx.meshes.ball.quarter_ball`).  The
    element size there at the contact edge 0.95 a(W) of a smaller load, against
    :data:`MAX_EDGE_RATIO` × ℓ(W, U) (:func:`outlet_width`).  At the chapter's point
    (40 N at 0.078 N/m, mesh=1 edge_refine=2) 13.3 N is not resolved at U (elements
    3.1 ℓ along its edge), 26.7 N is (1.5 ℓ, at the band's flank), 40 N too (1.03 ℓ).
    A user's mesh (``mesh_file``) is taken to resolve every load.
    """
    if v.mesh_file:
        return True
    _, refine, _ = mesh_levels(v)
    a = hertz_contact(v).a
    d = 0.95 * abs(hertz_contact(v, W).a - a)         # from the band's circle
    h = ball_fine_size(v)
    h_ring = h / 2**refine
    size = h_ring + (h - h_ring) * min(max(d / (0.1 * a) - 1.0, 0.0), 1.0)
    return size <= MAX_EDGE_RATIO * outlet_width(v.replace(W=W)) * (1 + 1e-12)


def film_rule(v: Params) -> str:
    """Return the film's quadrature rule (``auto``: vertex; Gauss with JFO or on mesh 0).

    Measured at 2–4 N: Newton on the JFO rows with the vertex rule meets a non-finite
    residual in its first steps (rigid plane and disc); on mesh 0 (a/4) the mixed
    solid with the vertex rule does not converge at 4 N, with Gauss points it does.
    """
    if v.quadrature != "auto":
        return str(v.quadrature)
    if v.cavitation == "jfo" or (not v.mesh_file and mesh_levels(v)[0] == 0):
        return "gauss"
    return "vertex"


def large_load(v: Params) -> bool:
    """Return True when the Hertz radius a(W) exceeds R/3 (W > 11.9 N, default ball)."""
    return hertz_contact(v).a > v.R / 3
