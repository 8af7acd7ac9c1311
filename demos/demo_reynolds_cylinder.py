# ---
# jupytext:
#   text_representation:
#     extension: .py
#     format_name: light
# ---

# # Rigid cylinder on a plane: the Reynolds equation with cavitation
#
# This demo illustrates how to:
#
# * solve the steady Reynolds equation (chapter §6.3–6.6) on a 1D interval for the
#   parabolic gap h = h0 + x²/(2R) of a cylinder near a plane with a **RigidFilm**
#   (entrainment speed u_m, v̄ = u_m, inlet at x_in);
# * treat the negative pressures of the diverging gap in three ways:
#   - ``none``: the full Sommerfeld solution, reported as half-Sommerfeld;
#   - ``penalty``: ∫ ε⁻¹ min(p, 0) δp dx added to (49): p ≥ 0 as a variational
#     inequality, whose rupture satisfies the Swift–Stieber conditions p = p' = 0,
#     but which is not mass conserving;
#   - ``jfo``: the mass-conserving JFO model (§6.5) with the void fraction λ and
#     the weak form (57)
#
# $$ \int (1-\lambda)\frac{h^3}{12\mu}\, p'\,\delta p'\, dx
#    + \int \big((1-\lambda)\, h\, u_m\big)'\, \delta p\, dx = 0, \qquad
#    \min(p/p_c, \lambda) = 0 \ \text{at the nodes (52)}, $$
#
#     solved by semismooth Newton, SUPG (Remark 3.2) in the advective zones;
# * a starved inlet (λ_in = 0.945): the supplied film crosses a cavitated inlet
#   zone and reforms with a jump of λ;
# * nested iteration: each mesh starts from the solution of the coarser one.
#
# References (NumPy quadrature, independent of the FE code,
# ``tribofx.references.cylinder_references``): half-Sommerfeld and Swift–Stieber
# (flooded or starved) for the same inlet.  R = 10 mm, h0 = 10 µm, u_m = 1 m/s,
# μ = 0.1 Pa·s, x ∈ [−2, 2] mm.  Units: mm, N, s, MPa.
#
# ## Changing it
#
#     tribofx run reynolds-cylinder --set cavitation=jfo --set inlet_void=0.945
#     tribofx run reynolds-cylinder --set cavitation=penalty --set penalty=1e-4

# +
import argparse
import math
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
import ufl
from dolfinx import mesh
from mpi4py import MPI

from tribofx.interfaces import FilmScales, Fluid, RigidFilm
from tribofx.interfaces.film_options import named_cavitation
from tribofx.output import write_summary
from tribofx.problem import Problem
from tribofx.references import cylinder_references

parser = argparse.ArgumentParser(description="cylinder–plane Reynolds demo")
parser.add_argument("--quick", action="store_true", help="200 instead of 400 elements (CI)")
parser.add_argument("--out", default=None, help="write summary.json here")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
R, h0, um, mu, x_in, x_out = 10.0, 0.01, 1000.0, 1e-7, -2.0, 2.0
ell = math.sqrt(2 * R * h0)                       # contact length
p_c = 12 * mu * um * ell / h0**2                  # pressure scale (SUPG, complementarity)
n_final = 200 if args.quick else 400


def solve(cavitation, void=0.0):
    """Nested iteration 50 → … → n_final elements; returns the film on the finest mesh."""
    prev = None
    for n in [n_final // 2**k for k in range(int(math.log2(n_final // 50)), -1, -1)]:
        film = RigidFilm(mesh.create_interval(comm, n, [x_in, x_out]),
                         lambda x: h0 + x**2 / (2 * R), um, Fluid(mu),
                         cavitation=named_cavitation(cavitation, 1e-6 * 12 * mu * ell**2 / h0**3),
                         supg=True, scales=FilmScales(pressure=p_c, film=h0, speed=um))
        if cavitation == "jfo":
            film.add_inlet(lambda y: np.isclose(y[0], x_in), void=void)
            film.jfo_initial_guess()
        else:
            film.add_pressure_bc()                # p = 0 at both ends
        if prev is not None:
            film.set_from_profile(prev)
        Problem([film], name=f"cylinder_{cavitation}", max_it=50, max_backtracks=8).solve()
        prev = comm.bcast(film.profile(), root=0)
    return film
# -

# ## The four variants against their references

# +
res = {}
for name, cav, void in (("none", "none", 0.0), ("penalty", "penalty", 0.0),
                        ("jfo", "jfo", 0.0), ("jfo-starved", "jfo", 0.945)):
    film = solve(cav, void)
    refs = cylinder_references(R, h0, um, mu, x_in, x_out, inlet_void=void)
    ref = refs["half_sommerfeld" if cav == "none" else "swift_stieber"]
    load = film.integral(ufl.max_value(film.p, 0) if cav == "none" else film.p)
    q_in, q_out = film.consistent_fluxes(inlet=lambda y: np.isclose(y[0], x_in))
    p_max = comm.allreduce(float(film.p.x.array.max()), op=MPI.MAX)
    res[name] = {"load": load, "p_max": p_max, "q_in": q_in, "q_out": q_out,
                 "ref_load": float(ref["load"]), "ref_p_max": float(ref["p_max"]),
                 "ref_flux": float(ref["flux"])}
    if comm.rank == 0:
        print(f"{name}: load {load:.5f} N/mm (reference {ref['load']:.5f}), p_max "
              f"{p_max:.5f} MPa ({ref['p_max']:.5f}), fluxes in {q_in:.5f} / out "
              f"{q_out:.5f} mm²/s")
if args.out:
    write_summary(comm, f"{args.out}/summary.json", res)
# -

# ## Checks
#
# * Load and peak within 1 % of the references (P1 with Δx = 0.01–0.02 mm over
#   ℓ = 0.45 mm, free boundaries inside elements; the references to 1e-8).
# * JFO conserves mass: consistent outflow = inflow to solver tolerance (1e-9), and
#   the outflow is the Swift–Stieber flux h(x_r) u_m to 0.1 % (rupture point located
#   to O(Δx²)); the penalty model creates fluid in the diverging gap (outflow ≫ inflow).

# +
for name, r in res.items():
    assert abs(r["load"] / r["ref_load"] - 1) < 0.01, (name, r)
    assert abs(r["p_max"] / r["ref_p_max"] - 1) < 0.01, (name, r)
for name in ("jfo", "jfo-starved"):
    r = res[name]
    assert abs(r["q_out"] - r["q_in"]) < 1e-9 * abs(r["q_in"])
    assert abs(r["q_out"] / r["ref_flux"] - 1) < 1e-3
assert res["penalty"]["q_out"] > 2 * res["penalty"]["q_in"]
if comm.rank == 0:
    print("demo_reynolds_cylinder: all checks passed")
# -
