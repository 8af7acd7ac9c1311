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
for the plane position along the paths of :mod:`tribofx.cases.ehl_ball_paths`
(Hertz start and a secant on W; large loads by a thick film, then the speed
marched down).

Defaults (mm, N, s, MPa; Stupkiewicz et al. 2016): R = 12.7, E = 1.19, ν = 0.45
(E* = 1.49 ≈ 240/R², Hertz a ≈ R/2 at 40 N; ν < 0.5 against P1 locking);
μ = 1e-8 (10 mPa·s), U = 1e4: μU = 1e-4 N/mm (0.1 N/m); W = 10 N in 3 steps;
θ_l = 40°; element size a/(4·2^mesh) within 1.6 a.  ``mesh`` and ``edge_refine``
default to the cheapest pair that resolves the film's outlet constriction at the
run's W and U (:mod:`tribofx.cases.ehl_ball_mesh`: elements along the contact
edge ≤ 2ℓ, ℓ = a (h_c R/a²)^{2/3}); the default point keeps ``mesh=1`` (≈ 11k
unknowns).  The chapter's point W = 40 N, μU = 0.078 N/m (Figs. 25–26) gets
``mesh=2 edge_refine=1`` (element size a/16, a/32 along the contact edge; 64k
unknowns) and needs θ_l = 60° (a smaller cap is refused at once); the speed is
marched down from 30U in ratios ≤ 2 (9 min on 2 ranks, MUMPS).  Coarser meshes
converge too but to a film that zig-zags node to node in the Hertzian zone and
dips far below the Hamrock–Dowson film on the symmetry line (``mesh=1``, a/8:
h_central 2.3 µm against 16.8 µm at 25k unknowns); set explicitly, they run
with a warning.  A point no built mesh resolves is refused at validation:

    tribofx run ehl-ball --set W=40 --set U=7800 --set theta_l=60 --set compare=all

Your own ball (``mesh_file``, a gmsh quarter ball with the groups ``lubricated``,
``midplane``, ``symmetry``): :mod:`tribofx.cases.ehl_ball_user`.

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
and on the plane: :mod:`tribofx.cases.ehl_ball_outputs`.
"""

import math

import numpy as np
from mpi4py import MPI

from ..body import Body
from ..forms.hyperelastic import lame_parameters
from ..interfaces import Film
from ..meshes.ball import LUBRICATED, MIDPLANE, SYMMETRY, cap_height, quarter_ball
from ..meshes.user import read_user_mesh
from ..obstacles import rigid_plane
from ..params import InputError, Param
from ..problem import Problem
from ..references import composite_modulus, hamrock_dowson, hertz
from . import film_setup
from .ehl_ball_mesh import checked_outlet_width, mesh_levels, outlet_width
from .ehl_ball_outputs import BallOutputs
from .ehl_ball_paths import BallPaths, Z
from .ehl_ball_sweep import BallSweep
from .ehl_ball_user import USER_GROUPS, place_user_ball, user_rim
from .film_setup import VISCOSITY_PARAMS, at_points, density, speed_list, viscosity

__all__ = ["EHLBallCase"]

NAMES = {"lubricated": LUBRICATED, "midplane": MIDPLANE, "symmetry": SYMMETRY}


class EHLBallCase(BallSweep, BallOutputs, BallPaths):
    """Case ``ehl-ball``; see the module docstring."""

    name = "ehl-ball"
    doc = "soft-EHL: elastic ball sliding on a rigid plane (3D, finite/no-shear/linear)"
    params = (
        Param("W", float, 10.0, "N", "final load on the whole ball", lower=0.0),
        Param("steps", int, 3, "-", "load increments (W/steps, …, W)", lower=1, upper=100,
              closed=True),
        Param("mu", float, 1e-8, "MPa·s", "viscosity (1e-8 MPa·s = 10 mPa·s)", lower=0.0),
        Param("U", float, 1e4, "mm/s", "entrainment speed U = V/2 (plane slides at 2U)",
              lower=0.0),
        Param("R", float, 12.7, "mm", "ball radius", lower=0.0),
        Param("E", float, 1.19, "MPa", "Young's modulus of the ball", lower=0.0),
        Param("nu", float, 0.45, "-", "Poisson's ratio of the ball", lower=-1.0, upper=0.5),
        Param("theta_l", float, 40.0, "deg", "polar angle of the lubricated cap", lower=5.0,
              upper=75.0, closed=True),
        Param("model", str, "finite", "-", "finite deformation or geometrically linear (EHL)",
              choices=("finite", "linear")),
        Param("shear", bool, True, "-", "Couette and Poiseuille shear tractions on the ball"),
        Param("supg", bool, True, "-", "SUPG stabilisation of the Reynolds equation"),
        film_setup.formulation_param("displacement"), film_setup.quadrature_param(),
        Param("penalty", float, 1e-4, "-",
              "relative cavitation penalty ε/ε_ref, ε_ref = 12 μ a²/h_c³ (Hertz a, "
              "Hamrock–Dowson h_c at W)", lower=0.0),
        Param("mesh", int, None, "-", "element size a/(4·2^mesh) near the contact (default: "
              "chosen with edge_refine from W and U to resolve the outlet, ehl_ball_mesh)",
              lower=0, upper=3, closed=True),
        Param("h_coarse", float, 4.0, "mm", "element size far from the contact", lower=0.0),
        Param("edge_refine", int, None, "-",
              "refinement levels of a band along the edge of the contact zone (the "
              "film's outlet ridge and side lobes): size h/2^level within 0.1 a of the "
              "circle of radius 0.95 a(W) on the undeformed cap (h the size near the "
              "contact; at 40 N the side-lobe minima lie at 0.94 a; default: with mesh)",
              lower=0, upper=3,
              closed=True),
        Param("start_speed", float, 30.0, "-",
              "loads with Hertz a(W) > R/3: each load is reached at start_speed·U by "
              "displacement control (thick film), then U is continued down to U",
              lower=1.0, closed=True),
        Param("speeds", str, "", "mm/s",
              "comma-separated entrainment speeds for continuation in U at the final load "
              "(empty: none); records the friction coefficient vs μU"),
        Param("compare", str, "none", "-",
              "all: load sweep (and speeds) of the full model, without shear tractions and "
              "geometrically linear in one run", choices=("none", "all")),
        Param("mesh_file", str, "", "-",
              "your own quarter ball: a 3D gmsh .msh with physical groups lubricated (the "
              "cap, p = 0 on its rim), midplane (u = 0), symmetry (plane y = const); "
              "replaces theta_l, mesh, h_coarse, edge_refine (R, E, nu: Hertz start, scales; cap "
              "curvature 1/R within 5 %); moved: symmetry at y = 0, cap centred at x = 0, "
              "lowest at z = 0"),
    ) + VISCOSITY_PARAMS

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

    @staticmethod
    def e_star(v):
        """Plane-strain modulus E* = E/(1 − ν²) of the ball against the rigid plane (MPa)."""
        return composite_modulus(v["E"], v["nu"])

    @staticmethod
    def hertz_contact(v, W=None):
        """Hertz contact of the ball on the rigid plane at W (default ``v["W"]``, N)."""
        return hertz(v["W"] if W is None else W, v["R"], v["E"], v["nu"])

    @classmethod
    def validate(cls, v):
        """Check that the cap holds the contact and the inlet: R sin θ_l ≥ 1.5 a(W).

        With ``mesh_file`` the cap of the mesh is checked when it is read (:meth:`build`).
        """
        a = cls.hertz_contact(v).a
        r_cap = v["R"] * math.sin(math.radians(v["theta_l"]))
        if r_cap < 1.5 * a and not v["mesh_file"]:
            raise InputError(f"cap radius R sin θ_l = {r_cap:.3g} mm < 1.5 a = {1.5 * a:.3g} mm "
                             f"(Hertz a at W = {v['W']} N): increase theta_l")
        if not v["U"] > 0 or not v["mu"] > 0:
            raise InputError("U and mu must be positive (entrainment)")
        checked_outlet_width(v)
        auto = v["mesh"] is None or v["edge_refine"] is None
        if auto and not v["mesh_file"] and not mesh_levels(v)[2]:
            raise InputError(
                f"no built mesh{'' if v['mesh'] is None else ' with mesh=' + str(v['mesh'])}"
                f"{'' if v['edge_refine'] is None else ' edge_refine=' + str(v['edge_refine'])}"
                f" resolves the film's outlet at W = {v['W']:g} N, U = {v['U']:g} mm/s "
                f"(width {outlet_width(v):.3g} mm): raise U, refine, or give mesh_file")
        viscosity(v)
        density(v)
        speed_list(v)

    @staticmethod
    def speed_list(v):
        """Return the continuation speeds (mm/s) of ``speeds`` (one-line error if bad)."""
        return speed_list(v)

    @classmethod
    def scales(cls, v, W=None, U=None):
        """Hertz a (mm), p0 (MPa), Hamrock–Dowson h_c (mm) and penalty ε (MPa·s/mm)."""
        W, U = (v["W"] if W is None else W), (v["U"] if U is None else U)
        h = cls.hertz_contact(v, W)
        h_c = hamrock_dowson(W, v["mu"], U, v["R"], cls.e_star(v))[0]
        return h.a, h.p0, h_c, v["penalty"] * 12 * v["mu"] * h.a**2 / h_c**3

    @classmethod
    def set_scales(cls, film, v, W, U):
        """SUPG pressure scale p0, penalty ε and tolerance scales at load W and speed U."""
        _, p0, h_c, eps = cls.scales(v, W, U)
        film.set_scales(p_c=p0, eps=eps, film_scale=h_c, speed_scale=U)

    @classmethod
    def build(cls, v, comm=MPI.COMM_WORLD, name="ehl_ball"):
        """Ball, film and problem, unloaded (``mesh_file``: the user's ball, module docstring).

        ``name``: the problem's name, options prefix ``tribofx_<name>_`` (a variant
        of ``compare=all`` is ``ehl_ball_full``, ``ehl_ball_no_shear``, ``ehl_ball_linear``).
        """
        a = cls.hertz_contact(v).a
        th = math.radians(v["theta_l"])
        if v["mesh_file"]:
            msh, ft, names = read_user_mesh(v["mesh_file"], comm, 3, USER_GROUPS)
            place_user_ball(msh, ft, names, v, a)
        else:
            level, refine, _ = mesh_levels(v)
            h_fine = a / (4 * 2**level)
            ring = (0.95 * a, h_fine / 2**refine, 0.1 * a) if refine else None
            msh, ct, ft = quarter_ball(v["R"], th, h_fine, max(v["h_coarse"], h_fine),
                                       1.6 * a, comm, ring=ring)
            names = NAMES
        mu, lm = lame_parameters(v["E"], v["nu"])
        law = "linear" if v["model"] == "linear" else "neo-hookean"
        ball = Body(msh, ft, names, "3d", (law, {"mu": mu, "lmbda": lm}), name="ball",
                    formulation=v["formulation"])
        ball.add_dirichlet("midplane", np.zeros(3))
        ball.add_dirichlet("symmetry", 0.0, component=1)
        _, p0, h_c, eps = cls.scales(v, v["W"] / v["steps"])
        V_plane = np.array([2 * v["U"], 0.0, 0.0])
        film = Film(ball, "lubricated", rigid_plane(np.zeros(3), np.eye(3)[Z]), viscosity(v),
                    density=density(v), quadrature=v["quadrature"],
                    V_counter=V_plane, model=v["model"], shear=v["shear"], supg=v["supg"],
                    eps=eps if v["penalty"] > 0 else None, p_c=p0, film_scale=h_c,
                    speed_scale=v["U"], quadrature_degree=2)
        if v["mesh_file"]:
            film.add_pressure_bc(at_points(user_rim(film, v, a), 1e-8 * v["R"]))
        else:
            z_cap = cap_height(v["R"], th)
            film.add_pressure_bc(lambda X: np.abs(X[2] - z_cap) < 1e-6 * v["R"])
        problem = Problem([ball, film], name=name, max_it=25)
        return ball, film, problem

