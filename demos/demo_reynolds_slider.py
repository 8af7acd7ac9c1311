# ---
# jupytext:
#   text_representation:
#     extension: .py
#     format_name: light
# ---

# # Hydrodynamic lubrication of a plane inclined slider bearing
#
# This demo illustrates how to:
#
# * solve the steady Reynolds equation of thin-film lubrication (chapter §6.3–6.4,
#   the traditional planar form §6.6) between rigid surfaces with a
#   **RigidFilm** — the film interface of the core on a given gap, the
#   lubrication surface being the mesh itself — and one **Problem**;
# * check the pressure against the classical analytic solution and the L2 error
#   against the theoretical convergence rate of P1 and P2 elements.
#
# ## Equations
#
# A rigid pad at rest over a plane sliding at U (v̄ = U/2, ∂h/∂t = 0), gap
# h = h0 (1 + K − K x/L) on 0 ≤ x ≤ L.  Flux q = −h³/(12μ) p' + h v̄ (eq. 40), weak
# form (49) with p = 0 at both ends:
#
# $$ \int_0^L \Big(\frac{h^3}{12\mu}\, p' - h\,\bar v\Big)\, \delta p'\, dx = 0 . $$
#
# Integrating twice (Hamrock et al., Cameron), with s = x/L,
# p(x) = 6μUL K s(1 − s)/(h0² (2 + K)(1 + K − Ks)²), p_max = 3μULK/(2h0²(1 + K)(2 + K))
# at x = L(1 + K)/(2 + K), W/B = 6μUL²/(K²h0²)(ln(1 + K) − 2K/(2 + K))
# (``tribofx.references.slider_reference``).
#
# ## Changing it
#
#     tribofx run reynolds-slider --set K=2 --set degree=2 --set mesh=50
#
# Defaults: L = 10 mm, h0 = 10 µm, K = 1, U = 1 m/s, μ = 0.1 Pa·s (1e-7 MPa·s):
# p_max = 2.5 MPa, W/B = 15.9 N/mm.  Units: mm, N, s, MPa.

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
from tribofx.output import write_summary
from tribofx.plots import plot_slider
from tribofx.problem import Problem
from tribofx.references import slider_pressure, slider_reference

parser = argparse.ArgumentParser(description="inclined slider demo")
parser.add_argument("--quick", action="store_true", help="(the demo is fast anyway)")
parser.add_argument("--out", default=None, help="write summary.json and the plot here")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
K, L, h0, U, mu = 1.0, 10.0, 0.01, 1000.0, 1e-7


def solve(n, degree, K=K):
    """The slider on n elements of degree ``degree``: (film, Newton report)."""
    film = RigidFilm(mesh.create_interval(comm, n, [0.0, L]),
                     lambda x: h0 * (1 + K - K * x / L), 0.5 * U, Fluid(mu), degree=degree,
                     scales=FilmScales(film=h0, speed=0.5 * U))
    film.add_pressure_bc()                     # p = 0 at x = 0 and x = L
    report = Problem([film], name="slider").solve()
    return film, report
# -

# ## The default slider, 200 P1 elements

# +
film, report = solve(200, 1)
ref = slider_reference(K, L, h0, U, mu)
load = film.integral(film.p)
prof = comm.bcast(film.profile(), root=0)
p_max = float(prof["p"].max())
if comm.rank == 0:
    print(f"W/B = {load:.5f} N/mm (analytic {ref['load']:.5f}), p_max = {p_max:.5f} MPa "
          f"(analytic {ref['p_max']:.5f}); Newton iterations {report.iterations}")
if args.out:
    write_summary(comm, f"{args.out}/summary.json", {"load": load, "p_max": p_max,
                                                     "analytic": ref["load"]})
    if comm.rank == 0:
        plot_slider(dict(prof, K=K, L=L, h0=h0, U=U, mu=mu), f"{args.out}/pressure.png")
# -

# ## Mesh convergence of the L2 error of the pressure (K = 2)

# +
rates = {}
for degree in (1, 2):
    errs = []
    for n in (16, 32, 64):
        f, _ = solve(n, degree, K=2.0)
        exact = slider_pressure(ufl.SpatialCoordinate(f.sub)[0], 2.0, L, h0, U, mu)
        errs.append(math.sqrt(f.integral((f.p - exact) ** 2)))
    rates[degree] = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    if comm.rank == 0:
        print(f"P{degree}: L2 errors {['%.2e' % e for e in errs]}, rates {rates[degree]}")
# -

# ## Checks
#
# * The problem is linear: one Newton step.
# * Load and peak pressure within 0.5 % (P1 with Δx = L/200: O(Δx²) ≈ 1e-4).
# * L2 error of Lagrange degree k converges as O(h^(k+1)) for this smooth solution:
#   the finest rates within 0.15 of 2 and 3.

# +
assert report.iterations == 1
assert abs(load / ref["load"] - 1) < 5e-3 and abs(p_max / ref["p_max"] - 1) < 5e-3
assert abs(rates[1][-1] - 2) < 0.15 and abs(rates[2][-1] - 3) < 0.15
if comm.rank == 0:
    print("demo_reynolds_slider: all checks passed")
# -
