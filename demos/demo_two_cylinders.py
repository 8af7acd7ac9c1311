# ---
# jupytext:
#   text_representation:
#     extension: .py
#     format_name: light
# ---

# # Two deformable bodies: elastic cylinders pressed together (chapter §2)
#
# This demo illustrates how to:
#
# * build two hyperelastic **Body** objects on two meshes (an upper and a lower
#   plane-strain half cylinder, each refined near the contact point);
# * couple them by **TwoBodyContact**: the slave nodes of the upper cylinder
#   are projected by the C++ kernel onto the *current* master surface of the
#   lower one at every Newton iteration, and the contact residual with its exact
#   tangent in the slave, master and multiplier unknowns is added to the block
#   system;
# * press them together by displacement control with **Continuation** on the
#   measured contact force, and compare with Hertz.
#
# ## Equations
#
# A slave node x is paired with its closest point x̄ = x₁ + ξ̄ (x₂ − x₁) on the
# current master segment, g_N = (x − x̄)·n (eq. 2).  With the nominal
# multipliers λ_N on the slave surface, T_N = min(λ_N + ρ_N g_N, 0) (eqs. 4,
# 9), the contact virtual work (8) at the slave nodes (vertex quadrature) is
#
# $$ \delta\Pi_c = \sum_i w_i\, T_{N,i}\, \delta g_{N,i},
#    \qquad \delta g_N = \mathbf n\cdot\big(\delta\mathbf x - (1-\bar\xi)\,\delta\mathbf x_1
#    - \bar\xi\,\delta\mathbf x_2\big), $$
#
# so the master nodes carry the reaction; the constraint rows are
# −w_i (λ_N − T_N)/ρ_N.  Hertz (line contact): 1/R* = 1/R₁ + 1/R₂,
# 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂, a = (4PR*/(πE*))^½, p₀ = 2P/(πa).
#
# ## Changing it
#
#     tribofx run contact-two-cylinders --set R2=0 --set E2=100     # on a stiff block
#     tribofx run contact-two-cylinders --set friction=0.3 --set mesh=3
#
# Units: mm, N, MPa.

# +
import argparse
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
from mpi4py import MPI
from tribofx.forms.hyperelastic import lame_parameters
from tribofx.meshes.hertz import NAMES, hertz_body

from tribofx.body import Body
from tribofx.continuation import ConstantParameter, Continuation
from tribofx.interfaces import TwoBodyContact
from tribofx.output import write_summary, write_vtx
from tribofx.plots import plot_hertz_pressure
from tribofx.problem import Problem
from tribofx.references import hertz

parser = argparse.ArgumentParser(description="two elastic cylinders against Hertz")
parser.add_argument("--quick", action="store_true", help="coarse mesh (CI)")
parser.add_argument("--out", default=None, help="write summary.json, plot and VTX here")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
# -

# ## The two cylinders
#
# R₁ = 10 mm, E₁ = 10 MPa, ν₁ = 0.3 above; R₂ = 15 mm, E₂ = 20 MPa, ν₂ = 0.2
# below; P = 0.2 N/mm.  Half models (x ≥ 0), elements a/12 (a/24) near contact.

# +
R1, E1, nu1, R2, E2, nu2, P = 10.0, 10.0, 0.3, 15.0, 20.0, 0.2, 0.2
ref = hertz(P, R1, E1, nu1, R2, E2, nu2, line=True)
h = ref.a / (12 if args.quick else 24)
bodies = []
for R, E, nu, below, name in ((R1, E1, nu1, False, "upper"), (R2, E2, nu2, True, "lower")):
    msh, facets = hertz_body(2, R, h, R / 6, 1.5 * ref.a, comm, below=below)
    mu, lmbda = lame_parameters(E, nu)
    body = Body(msh, facets, NAMES, "plane_strain", ("neo-hookean", {"mu": mu, "lmbda": lmbda}),
                name=name)
    body.add_dirichlet("symmetry_x", 0.0, component=0)
    bodies.append(body)
upper, lower = bodies
upper.add_dirichlet("loaded", np.zeros(2))               # the upper flat face is held
push = lower.add_dirichlet("loaded", 0.0, component=1)   # the lower one moves up by δ
contact = TwoBodyContact(upper, "contact", lower, "contact", rho_n=E1 / h)
problem = Problem([upper, lower, contact], name="two_cylinders")
# -

# ## Load control
#
# δ is found by a secant iteration on the contact force of the half model.

# +
control = Continuation(problem, ConstantParameter(push),
                       response=lambda: contact.forces(problem)[0][1])
control.reach(0.5 * P, 0.25 * ref.a**2 / ref.R_star)
d = contact.nodal_data(problem)
a = comm.allreduce(float(np.sum(d["weight"][d["active"]])), op=MPI.SUM)
p_max = comm.allreduce(float(np.max(d["p"], initial=0.0)), op=MPI.MAX)
on_upper, _ = contact.forces(problem)
support = upper.reaction("loaded", 1)                   # from the solid's own rows
if comm.rank == 0:
    print(f"{problem.num_dofs} unknowns: a = {a:.4f} mm (Hertz {ref.a:.4f}), p_max = "
          f"{p_max:.4f} MPa (Hertz {ref.p0:.4f}); load {2 * on_upper[1]:.6f} N/mm, "
          f"support of the upper face {support:.6f} N/mm")
# -

# ## Checks
#
# * equilibrium of the solved upper cylinder: the support of its held face,
#   from the solid's own rows, balances the contact force (to n_u · atol_u);
# * Hertz: the half-width is a nodal measure (error ≤ one element, h/a = 1/12
#   here); p₀ within 3 % (half-space theory at a/R* ≈ 0.07 with finite strain).

# +
bound = upper.V.dofmap.index_map.size_global * 2 * upper.tolerances()[upper.u].atol
assert abs(support + on_upper[1]) <= bound, (support, on_upper)
assert abs(a - ref.a) <= 1.5 * h and abs(p_max / ref.p0 - 1) < 0.03, (a, p_max)
if args.out:
    write_vtx(comm, f"{args.out}/upper.bp", [upper.u])
    write_vtx(comm, f"{args.out}/lower.bp", [lower.u])
    write_summary(comm, f"{args.out}/summary.json", {
        "case": "demo_two_cylinders", "contact_half_width": a, "hertz_contact_half_width": ref.a,
        "p_max": p_max, "hertz_p_max": ref.p0, "unknowns": problem.num_dofs})
    prof = contact.gather_profile(problem)
    if comm.rank == 0:
        plot_hertz_pressure({"r": prof["x"][:, 0], "p": prof["p"], "a": ref.a, "p0": ref.p0,
                             "dim": 2}, f"{args.out}/pressure.png")
if comm.rank == 0:
    print("demo_two_cylinders: all checks passed")
# -
