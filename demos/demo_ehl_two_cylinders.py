# ---
# jupytext:
#   text_representation:
#     extension: .py
#     format_name: light
# ---

# # Two soft cylinders rolling on a film: soft-EHL between two deformable bodies
#
# The chapter's soft-EHL has one rigid body (§6–8) and calls two deformable
# bodies "a challenging task for future work".  This demo illustrates how to:
#
# * put a film between two ``Body`` objects, ``TwoBodyFilm(upper, "lubricated",
#   lower, "lubricated", μ, ...)``: the Reynolds equation lives on the upper
#   body's current surface S = γ_l, each of its nodes is projected onto the lower
#   body's *current* surface by the C++ closest-point kernel (refitted every
#   evaluation), and the gap h and the lower surface's velocity w at the
#   projection enter the film as nodal unknowns;
# * carry the fluid traction (46) to both bodies: collocated at the nodes (t) and
#   put by the kernel on the upper body's rows (−w_k t_k) and, at the projection,
#   on the lower body's (w_k N_m(ξ̄) t_k) — action equals reaction;
# * roll both surfaces (Eulerian: the material moves through the fixed meshes,
#   v = F V with V the rotation about each centre, ``tribofx.motions.Rolling``);
# * find the approach δ at which the film carries the load W (a secant on 1/W,
#   nearly linear in δ for a rigid film: Martin's h = 4.9 μ u_m R*/W).
#
# The weak form on S (eq. 49 with A = F_t + n⊗N, ds_S = |det A| dS,
# v̄ = ½(I − n⊗n)(F V₁ + w)), penalty cavitation and SUPG:
#
# $$ \int_S \Big(\frac{h^3}{12\mu}\nabla_S p - h\bar v\Big)\cdot\nabla_S\delta p\,ds
#    + \int \varepsilon^{-1}\min(p,0)\,\delta p = 0, \qquad
#    h_k = (x_k - \bar x_k)\cdot n^{(2)}(\bar x_k). $$
#
# The check: two identical cylinders (R = 10 mm, E = 10 MPa, ν = 0.45) in pure
# rolling are, at small strain, one cylinder of R* = R/2 and E* on a rigid
# plane (Hertz: only R* and E* enter).  The single cylinder is the chapter's
# ``Film`` against a rigid plane sliding at the same speed.
#
# ## Changing it
#
#     tribofx run ehl-two-cylinders --set U2=500          # rolling and sliding
#     tribofx run ehl-two-cylinders --set R2=inf          # a cylinder on a block
#     tribofx run ehl-two-cylinders --set E2=inf --set R2=inf   # on a rigid plane

# +
import argparse
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
from dolfinx import fem
from mpi4py import MPI
from tribofx.forms.hyperelastic import lame_parameters
from tribofx.meshes.roller import ROLLER_NAMES, roller

from tribofx.body import Body
from tribofx.continuation import ConstantParameter, Continuation
from tribofx.interfaces import Film, FilmScales, Fluid, Penalty, TwoBodyFilm
from tribofx.motions import Rolling, Sliding
from tribofx.obstacles import rigid_plane
from tribofx.output import write_summary
from tribofx.problem import Problem
from tribofx.references import hertz, rigid_clearance

parser = argparse.ArgumentParser(description="two soft cylinders rolling on a film")
parser.add_argument("--quick", action="store_true", help="coarser mesh, fewer load steps (CI)")
parser.add_argument("--out", default=None, help="write summary.json here")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD

R, E, nu, U, W, mu = 10.0, 10.0, 0.45, 1000.0, 0.5, 1e-7    # mm, MPa, -, mm/s, N/mm, MPa·s
ref = hertz(W, R, E, nu, R, E, nu, line=True)                 # R* = 5 mm, E*, a, p0
h0 = rigid_clearance(W / 2, mu, 2 * U, ref.R_star)            # Martin's film at W/2
x_l, h_fine = 3.5 * ref.a, ref.a / (6 if args.quick else 12)
steps = 2 if args.quick else 4


def body(msh, ft, E_, name):
    """A neo-Hookean plane-strain body on a roller mesh (boundaries lubricated, loaded, free)."""
    mu_s, lm = lame_parameters(E_, nu)
    return Body(msh, ft, ROLLER_NAMES, "plane_strain", ("neo-hookean", {"mu": mu_s,
                                                                         "lmbda": lm}),
                name=name)


def press(problem, lift, film, sign=1.0):
    """Reach W in ``steps`` loads by the approach δ (the secant on 1/W); return the profile."""
    control = Continuation(problem, ConstantParameter(lift, 1, scale=sign),
                           response=lambda: 1.0 / (sign * film.force()[1]), rtol=1e-6,
                           max_trials=30)
    slope = -1.0 / (4.9 * mu * U * ref.R_star)               # Martin: d(1/W)/dδ
    for k in range(1, steps + 1):
        control.reach(1.0 / (W * k / steps), slope=slope if k == 1 else None)
    return film.profile(everywhere=True)
# -

# ## 1. Two soft cylinders, both rolling at U

# +
m1, f1 = roller(R, x_l, h_fine, R / 4, x_l, comm)             # above the origin
m1.geometry.x[:, 1] += h0                                     # the film h0 at the start
m2, f2 = roller(R, x_l + 2 * ref.a, h_fine, R / 4, x_l + 2 * ref.a, comm, below=True)
upper, lower = body(m1, f1, E, "upper"), body(m2, f2, E, "lower")
upper.add_dirichlet("loaded", np.zeros(2))                    # the upper flat face held
lift = lower.add_dirichlet("loaded", np.zeros(2))             # the lower one lifted by δ
p_c = ref.p0
eps = 1e-4 * 12 * mu * 2 * ref.R_star / h0**2                 # penalty ≪ the film's scale
film = TwoBodyFilm(upper, "lubricated", lower, "lubricated", Fluid(mu),
                   motion1=Rolling((0, R + h0), R), U1=U,     # counter-clockwise
                   motion2=Rolling((0, -R), -R), U2=U,        # clockwise
                   cavitation=Penalty(eps), scales=FilmScales(pressure=p_c, film=h0, speed=U))
film.add_pressure_bc()                                        # p = 0 at both ends
problem = Problem([upper, lower, film], name="two_rollers", max_it=25)
two = press(problem, lift, film)
on_upper, on_lower = film.forces()
balance = [abs(b.reaction("loaded", 1) + f[1]) for b, f in ((upper, on_upper),
                                                            (lower, on_lower))]
# -

# ## 2. One cylinder of R*, E* on a rigid plane (the chapter's film)

# +
m3, f3 = roller(ref.R_star, x_l, h_fine, ref.R_star / 4, x_l, comm)
m3.geometry.x[:, 1] += h0
single = body(m3, f3, E / 2, "single")                        # (1 − ν²)/E* = 2(1 − ν²)/E
single.add_dirichlet("loaded", np.zeros(2))
film1 = Film(single, "lubricated", rigid_plane([0, 0], [0, 1]), Fluid(mu),
             motion=(Rolling((0, ref.R_star + h0), ref.R_star), fem.Constant(m3, U)),
             V_counter=(Sliding((1, 0)), fem.Constant(m3, U)),
             cavitation=Penalty(eps), scales=FilmScales(pressure=p_c, film=h0, speed=U))
film1.add_pressure_bc()
one = press(Problem([single, film1], name="one_roller", max_it=25),
            film1.counterpart.offset, film1)
# -

# ## Results

# +
def measures(prof):
    """h at x = 0, h_min, p_max of a film profile (mm, mm, MPa)."""
    i0 = np.argmin(np.abs(prof["X"][:, 0]))
    return {"h_central": float(prof["h"][i0]), "h_min": float(prof["h"].min()),
            "p_max": float(prof["p"].max())}


res = {"two": measures(two), "one": measures(one)}
if comm.rank == 0:
    for k in ("h_central", "h_min", "p_max"):
        print(f"{k:10s} two cylinders {res['two'][k]:.5g}, one of R*, E* {res['one'][k]:.5g}")
    print(f"film force on the upper / lower body: {on_upper} / {on_lower} N/mm; "
          f"Hertz p0 {ref.p0:.4f} MPa, a {ref.a:.4f} mm")
if args.out:
    write_summary(comm, f"{args.out}/summary.json", {**res, "balance": balance})
# -

# ## Checks
#
# * The film carries W and its forces on the two bodies are equal and opposite;
#   each body's support reaction (its own rows) balances the film force on it,
#   to the momentum rows' tolerance.
# * Small-strain equivalence: h_central, h_min and p_max of the pair equal the
#   single cylinder's within p₀/E* + (a/R*)² (finite strain, first order in the
#   contact strain p₀/E* = 7 %; the curvature of the lubricated surfaces,
#   (a/R*)² = 2 %); measured about 1 %.

# +
assert abs(on_upper[1] / W - 1) < 1e-5
# the same nodal tractions summed twice: round-off of W (the friction component, 1e-6 W
# in pure rolling, is not compared relative to itself)
assert np.allclose(on_upper, -on_lower, rtol=0, atol=1e-12 * W)
for b in (upper, lower):
    assert max(balance) < 2 * b.V.dofmap.index_map.size_global * b.tolerances()[b.u].atol
tol = ref.p0 / ref.E_star + (ref.a / ref.R_star) ** 2
for k in ("h_central", "h_min", "p_max"):
    assert abs(res["two"][k] / res["one"][k] - 1) < tol, (k, res)
if comm.rank == 0:
    print("demo_ehl_two_cylinders: all checks passed")
# -
