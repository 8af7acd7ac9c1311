# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # The wear groove of a rigid ball sliding on an elastic half-space
#
# This demo illustrates how to:
#
# * build a 3D hyperelastic **Body** on a structured block whose shape mapping
#   is an *image* Function w₃ (``shape=w3``): the block is written on its worn
#   configuration, but w₃ is not an unknown of the block;
# * add a frictionless **Contact** interface with a rigid sphere (nodal
#   augmented Lagrangian, multiplier λ_N on the top-surface facet submesh);
# * add a **SteadyWear** interface: quasi-steady Archard wear in the frame of the
#   ball, whose shape unknown w₂ lives on *one cross-section* mesh, replicated on
#   every rank and extruded to the block, w₃ = P w₂ — a
#   :class:`tribofx.reduced.ReducedProblem` assembles the monolithic system with
#   the Jacobian blocks J_{u w₂} = J_{u w₃} P and (Δt/L) Pᵀ J_{r ·};
# * integrate slow time with the **Stepper** (θ = 1: one monolithic Newton in
#   (u, λ_N, w₂, ζ) per step, step cutting, state save/restore);
# * check the result against references: Hertz at t = 0, Archard's global
#   balance, a groove conforming to the ball, the rigid sinking of the groove.
#
# ## Equations (chapter §4.3, §5.3)
#
# A rigid ball (R = 5 mm, F = 10 N) slides at V = 100 mm/s over a steel-like
# half-space (E = 200 GPa, ν = 0.3), as in a ball-on-disk test with track
# length L = 2π·10 mm.  In the frame of the ball the worn half-space moves at
# V = −V e_x; every unknown lives on the initial block (eq. 19): X = X̂ + w₃,
# x = X̂ + u, F = (I + Grad u) G⁻¹, G = I + Grad w₃.  The material velocity is
# v = F V (eq. 26), the slip velocity its tangential part v_T (eq. 27), and the
# nominal Archard rate in pressure form (eq. 14) is Ẇ j_w = k |λ_N| ‖v_T‖ per
# unit initial area.  One pass per cycle drags every point of the groove once
# through the contact, so the groove sinks at the path average (eqs. 22–23)
#
# $$
# \bar{\dot W}(y) = \frac{1}{L} \int \dot W(x, y)\, dx .
# $$
#
# The groove is uniform along x, so w₃ = (0, w_y, w_z)(y, z) = P w₂.  The shape
# update (28), θ = 1, lumped on the top line of the cross-section, with the
# mid-step Nanson vector a = cof(G_{n+½}) N̂ (exact swept area) reads
#
# $$
# (w_2 - w_{2,n})\cdot a = -\Delta t\, \bar{\dot W}_{n+1},
# $$
#
# its interior following the auxiliary plane elasticity with the multiplier ζ.
# Then the groove area grows by Δt (1/L) ∫ Ẇ j_w dŜ per step, and by vertical
# equilibrium ∫ |λ_N| dS ≈ F/2 (half model): the full groove area grows at
# k F V / L (Archard).  Once the groove conforms to the ball, its half-width is
# b = (3 R k F s / (2L))^{1/3} after the sliding distance s = V t
# (:func:`tribofx.references.rigid_groove_halfwidth`) and its depth b²/(2R).
#
# ## Changing it
#
# ``scheme=EXPLICIT`` (θ = 0) in ``SteadyWear`` gives the explicit scheme (stable only for
# small Δt, see ``benchmarks/bench_wear_groove.py``); ``law="spatial"`` the
# spatial Archard law (eqs. 15–16); a graded layer multiplies E and k by
# :func:`tribofx.forms.wear_groove.graded_factor` of the worn depth (Fig. 10b,
# the second run below).  The same configuration is the case
# ``wear-ball-halfspace`` (``tribofx run wear-ball-halfspace --set graded=true``).
# Units: mm, N, s, MPa.

# +
import argparse
import math
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI
from tribofx.forms import wear_groove as gf
from tribofx.forms.hyperelastic import lame_parameters
from tribofx.meshes import halfspace as hs

from tribofx.body import Body
from tribofx.interfaces import Contact
from tribofx.interfaces.steady_wear import SteadyWear
from tribofx.obstacles import rigid_sphere
from tribofx.output import write_summary, write_vtx
from tribofx.references import hertz, rigid_groove_halfwidth
from tribofx.scheme import IMPLICIT
from tribofx.stepper import Stepper

parser = argparse.ArgumentParser(description="wear groove demo")
parser.add_argument("--quick", action="store_true", help="coarse mesh, two steps (CI)")
parser.add_argument("--out", default=None, help="write summary.json, plots and VTX here")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
# -

# ## The configuration
#
# The block [−27a, 27a] × [0, 27a] × [−27a, 0] (a the Hertz radius; half model,
# symmetry y = 0) is a tensor product of graded grids, fine near the contact:
# h = 0.45 a across the groove and h/2 along x (``--quick``: h = 0.9 a, and
# 2 steps of 50 s instead of 10 of 100 s).  The cross-section mesh is the same
# grid without x, created on ``COMM_SELF``.

# +
E, nu, R, F, V, L, k = 2.0e5, 0.3, 5.0, 10.0, 100.0, 2 * math.pi * 10.0, 1.0e-7
a, p0, delta = hertz(F, R, E, nu)[:3]
h = (0.9 if args.quick else 0.45) * a
T, dt = (100.0, 50.0) if args.quick else (1000.0, 100.0)
mu, lmbda = lame_parameters(E, nu)


def solve_groove(graded=None):
    lz, nc = (1.8, (3, 3, 4)) if args.quick else (1.35, (4, 5, 6))
    gx, gy, gz = hs.grids(27 * a, 27 * a, 27 * a, h, 1.8 * a, 5.4 * a, lz * a, nc, hx=h / 2)
    msh, facet_tags = hs.halfspace_block(comm, gx, gy, gz)
    section, section_tags = hs.cross_section(MPI.COMM_SELF, gy, gz)

    # the body: the block on its worn configuration, w3 the image of the section field;
    # a graded layer multiplies E (and k) by a factor of the worn depth (Fig. 10b)
    w3 = fem.Function(fem.functionspace(msh, ("Lagrange", 1, (3,))), name="shape_change_3d")
    factor = 1.0
    if graded is not None:
        depth = gf.material_depth(ufl.SpatialCoordinate(msh), w3)
        factor = gf.graded_factor(depth, *graded)
    body = Body(msh, facet_tags, hs.NAMES, "3d",
                ("neo-hookean", {"mu": mu * factor, "lmbda": lmbda * factor}),
                quadrature_degree=2, shape=w3, force_scale=F, stiffness=mu)
    body.add_dirichlet("ends", 0.0, component=0)   # rollers on x = ±L_x
    body.add_dirichlet("sym", 0.0, component=1)    # symmetry y = 0
    body.add_dirichlet("far", 0.0, component=1)    # roller y = L_y
    area = (gx[-1] - gx[0]) * gy[-1]
    body.add_traction("bottom", ufl.as_vector([0.0, 0.0, 0.5 * F / area]))  # pushes F/2 up

    # the interfaces: frictionless contact with the ball, steady wear on the cross-section
    contact = Contact(body, "top", rigid_sphere(np.array([0.0, 0.0, R]), R), rho_n=E / h)
    # (shape rows to 1e-12 of the block size: small against a step's worn-depth increment)
    wear = SteadyWear(contact, section, section_tags, hs.SECTION_NAMES, hs.prolongation,
                      k * factor, V, L, aux=(E, 0.3), scheme=IMPLICIT, rtol=1e-12,
                      fixed={"sym": [0], "far": [0], "bottom": [0, 1]})

    # slow time: the stepper builds the monolithic problem of (u, λ_N, w₂, ζ), a
    # ReducedProblem (the class SteadyWear asks for: w₂ lives on the cross-section)
    stepper = Stepper([body, contact, wear], wear, name="demo_groove",
                      problem_class=wear.problem_class)

    # t = 0: the block lifted by the Hertz approach δ, then the contact problem (Δt = 0)
    body.u.x.array.reshape(-1, 3)[:, 2] = delta
    report = stepper.problem.solve()
    stepper.problem.commit()
    n_own = contact.Q.dofmap.index_map.size_local
    lam = contact.lam_n.x.array[:n_own]
    X = contact.X_sub[:n_own, :2]
    history = [{"t": 0.0, "area": 0.0, "rate": 2 * wear.averaged_rate_integral(),
                "newton": report.iterations, "zeta": 0.0}]
    hertz_bracket = []
    for axis in (0, 1):  # last active and first inactive node on each axis
        on = np.abs(X[:, 1 - axis]) < 1e-12
        r = np.abs(X[on, axis])
        hertz_bracket.append((comm.allreduce(r[lam[on] < 0].max(initial=0.0), op=MPI.MAX),
                              comm.allreduce(r[lam[on] >= 0].min(initial=np.inf), op=MPI.MIN)))

    def on_step(st, rep):  # zeta: the final max |r_j / w_j| (mm) of the shape-update rows
        history.append({"t": st.t, "area": 2 * wear.groove_area(),
                        "rate": 2 * wear.averaged_rate_integral(), "newton": rep.iterations,
                        "zeta": rep.reports[0].blocks[-1][-1]})

    stepper.run(T, dt, on_step=on_step)
    lp = wear.line_profile()
    y, pint = wear.averaged_pressure()
    lam = contact.lam_n.x.array[:n_own]
    on = np.abs(X[:, 0]) < 1e-12  # the pressure across the groove at x = 0
    parts = comm.gather(np.column_stack([X[on, 1], np.maximum(-lam[on], 0.0)]), root=0)
    p_x0 = None if parts is None else np.concatenate(parts)
    p_x0 = None if p_x0 is None else p_x0[np.argsort(p_x0[:, 0])]
    if args.out:  # ParaView fields and a summary
        out = f"{args.out}/{'graded' if graded else 'homogeneous'}"
        write_vtx(comm, f"{out}/displacement.bp", [body.u, body.w])
        write_vtx(comm, f"{out}/contact.bp", [contact.lam_n])
        write_summary(comm, f"{out}/summary.json", {
            "case": "demo_wear_ball_halfspace", "graded": graded, "history": history,
            "profile": lp["worn"], "pressure_integral": np.column_stack([y, pint])})
    return {"history": history, "bracket": hertz_bracket, "profile": lp, "y": y, "pint": pint,
            "p_x0": p_x0,
            "unknowns": stepper.problem.num_dofs,
            "shape_share": stepper.shape_unknown_fraction()}


runs = {"homogeneous": solve_groove()}
if not args.quick:  # E and k twice the substrate values at the surface, 10 µm deep
    runs["graded"] = solve_groove(graded=(1.0, 0.01))
if comm.rank == 0:
    for name, r in runs.items():
        print(f"{name}: {r['unknowns']} unknowns, Ψ share {100 * r['shape_share']:.1f} %")
        print("   t (s)   groove area (mm²)   (2/L)∫k p v dA (mm²/s)   Newton")
        for s in r["history"]:
            print(f"{s['t']:8.0f}   {s['area']:17.4e}   {s['rate']:22.4e}   {s['newton']:6d}")
# -

# ## Checks
#
# * t = 0 (Hertz): the contact radius a lies between the last active and the
#   first inactive node on each axis (a bracket of one node spacing).
# * Each implicit step: the groove area grows by Δt times the rate of the new
#   state, since the mid-step Nanson vector makes Σ_j ∫ η_j (w − w_n)·a dŝ the exact
#   swept area; the error is the final residual of the shape-update rows, at most
#   max_j |r_j / ∫ η_j dŝ| times the line length 27a, on both halves, plus the
#   round-off of ∫ (1 − det G) dÂ (ε per unit area: 100 ε (27a)² per half).
# * Archard's global balance: the rate (2/L) ∫ k |λ_N| ‖v_T‖ dA is k F V / L up to
#   ‖v_T‖/V − 1 (the surface strain, ≤ p₀/E = 0.8 % at the peak, less on
#   average) and the tilt of the ball normal ((a/R)²/2 ≈ 10⁻⁴): 1 %.
# * Full run only (a groove conforming to the ball needs t ≫ the time to
#   outgrow the Hertz contact): half-width b = 3A/(4d) of the parabolic groove of
#   area A and depth d against b² = 2Rd (15 %: elastic edge rounding, one
#   element across 10 % of b) and against the rigid-ball groove of the same
#   sliding distance (10 %: b ∝ A^{1/3} with A within 1 %, plus the edge); the
#   path-integrated pressure ∫ p dx uniform across 60 % of the groove (rigid
#   sinking at a uniform rate, Fig. 10a; 10 % for the mesh); the graded layer
#   lowers ∫ p dx at 0.8 b relative to the centre by more than 0.1 (Fig. 10b: the
#   shallow edges wear faster at the same pressure).

# +
r = runs["homogeneous"]
for lo, hi in r["bracket"]:
    assert lo <= a <= hi, (lo, a, hi)
hist = r["history"]
for s0, s1 in zip(hist[:-1], hist[1:]):
    da = s1["area"] - s0["area"]
    bound = 2 * (s1["zeta"] * 27 * a + 100 * np.finfo(float).eps * (27 * a) ** 2)
    assert abs(da - (s1["t"] - s0["t"]) * s1["rate"]) <= bound, (da, s1)
    assert abs(s1["rate"] / (k * F * V / L) - 1) < 0.01, s1["rate"]
if not args.quick:
    A, d = hist[-1]["area"], float(r["profile"]["depth"].max())
    b = 3 * A / (4 * d)
    assert abs(b**2 / (2 * R * d) - 1) < 0.15, (b, d)
    assert abs(b / float(rigid_groove_halfwidth(k, F, R, V * T, L)) - 1) < 0.10, b
    inner = r["y"] < 0.6 * b
    assert np.all(np.abs(r["pint"][inner] / r["pint"][0] - 1) < 0.10)
    edge = {name: np.interp(0.8 * b, q["y"], q["pint"]) / q["pint"][0]
            for name, q in runs.items()}
    assert edge["graded"] < edge["homogeneous"] - 0.1, edge
if args.out and comm.rank == 0:
    from tribofx.plots import plot_pressure_across

    entries = [(name, q["p_x0"], np.column_stack([q["y"], q["pint"]]))
               for name, q in runs.items()]
    plot_pressure_across(entries, f"{args.out}/pressure_across.png", T, 6 * a)
if comm.rank == 0:
    print("demo_wear_ball_halfspace: all checks passed")
# -
