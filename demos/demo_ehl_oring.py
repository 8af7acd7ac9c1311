# ---
# jupytext:
#   text_representation:
#     extension: .py
#     format_name: light
# ---

# # Soft-EHL of a reciprocating O-ring seal (chapter §8.1)
#
# This demo illustrates how to:
#
# * build an **axisymmetric Body** (the O-ring cross-section, nearly
#   incompressible Mooney–Rivlin) with a follower pressure p_s on its sealed side;
# * put two frictionless **Contact** interfaces against rigid planes on it (the
#   groove bottom, which is moved to squeeze the ring, and the air-side wall) and
#   a lubricating **Film** on its inner arc against the rod, which slides axially
#   with speed U;
# * solve the whole system — ring, film, both contacts — by one monolithic
#   Newton method (**Problem**) and drive it with **Continuation** in three
#   parameters in turn: the squeeze, the sealed pressure, the rod speed;
# * check the solved state against global equilibrium and the divergence theorem.
#
# ## Equations
#
# The ring (mesh coordinates (r, z)) has the 3×3 deformation gradient with the
# hoop stretch r/R and the measure 2πR dR dZ (virtual work 62), with
#
#     ψ = μ₁/2 (Ī₁ − 3) + μ₂/2 (Ī₂ − 3) + κ/2 (J − 1)².
#
# The housing contacts are Alart–Curnier augmented Lagrangian (eqs. 4, 8).  On
# the rod the lubrication surface S = P(γ_l) is the rod cylinder, h = r − r_rod,
# v̄ = ½U e_z, and the steady Reynolds equation (49) on the surface of revolution
# (weight 2π r_rod times the meridian stretch) with SUPG and the mass-conserving
# JFO cavitation (57): the void fraction λ beside p, p ≥ 0, λ ≥ 0, pλ = 0 node by
# node (52), a flooded inlet p = p_s, λ = 0 at the sealed end and a natural
# outlet at the air end, where the rod carries the leaking film away (θh v̄ = q,
# θ = 1 − λ); the fluid traction (46) —
# pressure (axisymmetric Nanson), Couette (μ/h)U e_z and Poiseuille
# −(h/2) grad_S p — loads the ring.
#
# ## Changing it
#
#     tribofx run ehl-oring --set p_s=1,5 --set U=400 --set mesh=8       # Fig. 17
#     tribofx run ehl-oring --set stroke=both                            # out vs in
#     tribofx run ehl-oring --set study=mesh --set mesh_levels=2,4,8     # Figs. 18-19
#
# The film's node-to-node zig-zag of Fig. 18 is volumetric locking: linear
# triangles of a nearly incompressible solid (κ = 1000 G) cannot take the smooth
# surface the film asks for.  The ring is therefore solved in the mixed (u, p)
# form (``formulation="mixed"``: a P1 volumetric stress p beside u, stabilised by
# β = 0.1 h²/G), and its film is smooth already on density 2; with
# ``formulation="displacement"`` the 400 mm/s film of Fig. 18 zig-zags by 24 % on
# density 2.  Here |U| = 1000 mm/s.  Parameters the
# chapter leaves open (the split μ₁/μ₂, κ, d, r_rod, squeeze, viscosity) are
# those of ``tribofx/cases/ehl_oring.py`` (Stupkiewicz 2009; Stupkiewicz &
# Marciniszyn, Tribol. Int. 42, 2009).  Units: mm, N, s, MPa.

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
from tribofx.forms.ehl_axisym import follower_pressure_traction
from tribofx.meshes.oring import HOUSING, LUBRICATED, SEALED, oring_section

from tribofx.body import Body
from tribofx.continuation import ConstantParameter, Continuation
from tribofx.interfaces import JFO, Contact, Film, FilmScales, Fluid
from tribofx.obstacles import rigid_plane
from tribofx.output import write_summary, write_vtx
from tribofx.positions import oscillation_indicator
from tribofx.problem import Problem
from tribofx.references import inverse_film

parser = argparse.ArgumentParser(description="O-ring soft-EHL demo")
parser.add_argument("--quick", action="store_true", help="density 2, one sealed pressure (CI)")
parser.add_argument("--out", default=None, help="write summary.json, plots and VTX here")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
# -

# ## The ring, the housing and the film
#
# d = 3.5 mm on a rod of radius 10 mm, 10 % squeeze; μ₁ + μ₂ = 3.66 MPa (chapter),
# κ = 1000 (μ₁ + μ₂); oil 0.05 Pa·s.  The ring starts 0.02 mm clear of the rod,
# touching the groove bottom and the air-side wall.  Mesh density n: elements of
# 0.1/n mm on the film arc.

# +
d, r_rod, squeeze, gap0, mu = 3.5, 10.0, 0.1, 0.02, 5e-8
mat = {"mu1": 2.93, "mu2": 0.73, "kappa": 3660.0}
U = 1000.0                                                # rod speed, outstroke (mm/s)
density = 2 if args.quick else 4
a = d / 2
center = (r_rod + a + gap0, 0.0)
msh, _, facets = oring_section(*center, a, density, comm=comm)
# quadrature degree 2 (exact for the P1 strain measures up to the 1/R hoop terms):
# left to UFL's estimate for the Mooney–Rivlin energy it is far higher and each
# Newton iteration about 14 times slower, for the same results (measured).  The mixed
# form adds the volumetric stress p (MPa) as an unknown: the energy
# ∫ ψ_r(F) + p (J − 1) − p²/(2κ) − β/2 |Grad p|² dV (forms/hyperelastic.py)
ring = Body(msh, facets, {"rod": LUBRICATED, "sealed": SEALED, "housing": (SEALED, HOUSING)},
            "axisymmetric", ("mooney-rivlin", mat), quadrature_degree=2, name="oring",
            formulation="mixed")
p_s = fem.Constant(msh, 0.1)                              # sealed pressure (MPa)
ring.add_follower_pressure("sealed", p_s)

E = 3 * (mat["mu1"] + mat["mu2"])                         # small-strain Young's modulus
r_start, r_groove = center[0] + a - 1e-3 * a, r_rod + d * (1 - squeeze)
bottom = Contact(ring, "housing", rigid_plane([r_start, 0.0], [-1.0, 0.0]), E / a,
                 name="bottom")
wall = Contact(ring, "housing", rigid_plane([0.0, a - 0.005], [0.0, -1.0]), E / a, name="wall")

h_ref = inverse_film(mu, U, 20.0)                         # film scale: Blok's inverse theory
film = Film(ring, "rod", rigid_plane([r_rod, 0.0], [1.0, 0.0]), Fluid(mu),
            scales=FilmScales(pressure=1.0, film=h_ref, speed=U), cavitation=JFO(),
            V_counter=[0.0, U], rtol=1e-8, require_open=True)
zs = film.sub.geometry.x[:, 1]
z_lo = comm.allreduce(float(zs.min(initial=np.inf)), op=MPI.MIN)
z_hi = comm.allreduce(float(zs.max(initial=-np.inf)), op=MPI.MAX)
# the flooded inlet on the sealed side (p = p_s, λ = 0); the air end is a natural outlet
p_end = film.add_inlet(lambda x: np.isclose(x[1], z_lo, atol=1e-8 * a), pressure=0.1)
Xq = film.Q.tabulate_dof_coordinates()
film.p.x.array[:] = np.where(Xq[:, 1] < 0.0, 0.1, 0.0)   # first guess: p_s on the sealed side
film.jfo_initial_guess(downstream=(0.0, 1.0))            # λ: the film ruptures past h_min

components = [ring, film, bottom, wall]
problem = Problem(components, name="oring", max_it=40, max_backtracks=10,
                  line_search="admissible", stall_window=10)
# -

# The film rows of the thick-film flanks (h up to 10³ times the film of the
# contact) have a round-off floor of about 4e-8 mm²/s, so the film's tolerances
# are 1e-8 of its scales (``rtol``).  A trial Newton step is accepted when it
# keeps the film open (``require_open``): ‖R‖ is a poor merit function here.
# An iteration whose residual has not halved in 10 iterations (``stall_window``)
# is stopped, so that the continuation cuts an over-long squeeze step early.

# ## Solution path
#
# The trace and the Reynolds equation are first solved alone on the initial
# geometry, so that the coupled Newton method starts from a film pressure
# consistent with the gap; then the groove bottom moves to r_g (squeeze), p_s
# rises to its targets.  The sealed pressure drives both the follower load and
# the film's pressure at the sealed end (``on_set``).  The first coupled solve
# has no physical parameter to cut if it fails (its active sets of contact and
# cavitation may cycle from the decoupled start): ``solve_by_homotopy`` then
# marches s from 0 to 1 in R(u) − (1 − s) R(u₀) = 0, cutting s on failure.

# +
for unknowns in ([film.u_s], [film.p, film.lam]):
    Problem(components, unknowns=unknowns, name="oring_start").solve_by_homotopy()
problem.solve_by_homotopy()
iterations = []


def set_pressure(value):
    p_s.value = value
    p_end.value = value


Continuation(problem, ConstantParameter(bottom.counterpart.offset, 0),
             record=iterations).march(r_groove - r_start, 10, predictor=False)
targets = [0.5] if args.quick else [0.5, 1.0]
states = {}
for target in targets:
    Continuation(problem, ConstantParameter(p_s, None, on_set=set_pressure),
                 record=iterations).march(target, 4, predictor=False)
    prof = film.profile(everywhere=True)
    order = np.argsort(prof["x"][:, 1])
    z, h, p, lam = (prof["x"][order, 1], prof["h"][order], prof["p"][order],
                    prof["lam"][order])
    F = film.force()
    half = target + 0.5 * (p.max() - target)              # loaded zone: half the rise
    states[target] = {"p_max": float(p.max()), "h_min": float(h.min()),
                      "h_at_p_max": float(h[np.argmax(p)]),
                      "load_per_circumference": float(F[0]) / (2 * math.pi * r_rod),
                      "oscillation": oscillation_indicator(h, p, half),
                      # flux per circumference: element midpoints of the loaded zone
                      # (full film), q = h U/2 − h³/(12μ) dp/dz, and the film the rod
                      # carries out of the air end, θ h U/2 (p = 0 there)
                      "flux": float(np.median([
                          0.5 * (h[i] + h[i + 1]) * U / 2 - (0.5 * (h[i] + h[i + 1]))**3
                          / (12 * mu) * (p[i + 1] - p[i]) / (z[i + 1] - z[i])
                          for i in range(len(z) - 1) if min(p[i], p[i + 1]) > half])),
                      "carried": float((1 - lam[-1]) * h[-1] * U / 2),
                      "z": z, "h": h, "p": p, "lam": lam}
    if comm.rank == 0:
        s = states[target]
        print(f"p_s = {target:g} MPa: p_max = {s['p_max']:.3f} MPa, h_min = "
              f"{1e3 * s['h_min']:.3f} µm, h(p_max) = {1e3 * s['h_at_p_max']:.3f} µm, "
              f"radial load {s['load_per_circumference']:.3f} N/mm, "
              f"oscillation {s['oscillation']:.3f}, flux {s['flux']:.4f} mm²/s, carried out "
              f"{s['carried']:.4f} mm²/s ({problem.num_dofs} unknowns)")
# -

# ## Checks
#
# * Axial equilibrium: the test field e_z has Grad e_z = 0 and no hoop term, so
#   the internal virtual work vanishes for it and the axial forces of the film,
#   p_s and the housing must balance.  The momentum rows stop at
#   max |R_i| ≤ atol_u, so |Σ_i R_i| ≤ n_u atol_u.
# * Mass conservation (JFO): the film the rod carries out of the air end,
#   (1 − λ) h U/2, is the flux of the loaded zone, computed here from the nodal
#   p and h; 2 % covers the spread of the P1 fluxes along the zone (< 1 %).  The
#   penalty model has no such balance: its cavity holds h U/2, up to 400 q.
# * The film carries the squeeze (positive radial load), the pressure peak lies
#   above p_s and the film is open; a higher p_s raises the peak and the load
#   (full run).

# +
forces = {"film": film.force(), "bottom": bottom.force(), "wall": wall.force()}
ds = ring.ds(ring.tag("sealed"))
t = follower_pressure_traction(p_s, ring.u, ufl.FacetNormal(msh))
forces["sealed"] = np.array([comm.allreduce(fem.assemble_scalar(fem.form(
    t[i] * ring.weight * ds)), op=MPI.SUM) for i in range(2)])
axial = sum(f[1] for f in forces.values())
bound = ring.V.dofmap.index_map.size_global * ring.tolerances()[ring.u].atol
last = states[targets[-1]]
if comm.rank == 0:
    print("axial forces (N): " + ", ".join(f"{k} {v[1]:.5f}" for k, v in forces.items())
          + f"; sum {axial:.2e} (bound {bound:.1e})")
assert abs(axial) <= bound, (axial, bound)
assert abs(last["carried"] / last["flux"] - 1) < 0.02, (last["carried"], last["flux"])
assert forces["film"][0] > 0 and last["h_min"] > 0
assert last["p_max"] > targets[-1]
if len(targets) > 1:
    assert states[1.0]["p_max"] > states[0.5]["p_max"]
    assert states[1.0]["load_per_circumference"] > states[0.5]["load_per_circumference"]
if args.out:
    write_vtx(comm, f"{args.out}/displacement.bp", [ring.u])
    write_vtx(comm, f"{args.out}/pressure.bp", [film.p])
    write_summary(comm, f"{args.out}/summary.json", {
        "case": "demo_ehl_oring", "unknowns": problem.num_dofs, "newton": iterations,
        "axial_force_sum": axial, **{f"ps{k:g}_{q}": v[q] for k, v in states.items()
                                     for q in ("p_max", "h_min", "h_at_p_max",
                                               "load_per_circumference", "oscillation",
                                               "flux", "carried")}})
    if comm.rank == 0:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
        for k, s in states.items():
            a1.plot(s["z"], s["p"], label=f"p_s = {k:g} MPa")
            a2.plot(s["z"], 1e3 * s["h"])
        a1.set_ylabel("p (MPa)")
        a1.legend()
        a2.set_ylabel("h (µm)")
        a2.set_ylim(0, 4e3 * last["h_at_p_max"])
        a2.set_xlabel("z (mm, air side > 0)")
        fig.tight_layout()
        fig.savefig(f"{args.out}/profiles.png", dpi=110)
        plt.close(fig)
if comm.rank == 0:
    print("demo_ehl_oring: all checks passed")
# -
