# ---
# jupytext:
#   text_representation:
#     extension: .py
#     format_name: light
# ---

# # Your own law: a pressure-dependent viscosity in a few lines of UFL
#
# This demo illustrates how to:
#
# * write a lubricant law as a plain UFL function of the film pressure and hand
#   it to a film as a **Law** — its parameters become `Constant`s of the film's
#   state, and the same expression enters every place the viscosity appears;
# * check it: against the library's own Barus law (the same physics written
#   twice must agree to round-off), against the exact solution of the Barus
#   slider, and by a Taylor test of the Newton tangent with `tribofx.testing`.
#
# ## Equations
#
# The plane inclined slider of `demo_reynolds_slider.py`, h = h0 (1 + K − K x/L),
# v̄ = U/2, p = 0 at both ends, now with μ = μ(p).  With the reduced pressure
# q = ∫₀^p μ₀/μ(s) ds the Reynolds equation becomes the isoviscous one in q; for
# Barus, μ = μ₀ e^{αp}, q = (1 − e^{−αp})/α, so p = −ln(1 − α p_iso)/α
# (`tribofx.references.barus_pressure`).
#
# ## Changing it
#
# Write any `law(p, **parameters)` returning UFL (use `ufl.max_value(p, 0)` for a
# cavitated film at ambient pressure) and pass `Law(law, mu0=..., ...)` as the
# viscosity of a `RigidFilm` or a `Film`; the cases select the built-in ones with
# `--set viscosity=barus --set alpha_p=0.02` (and `density=dowson-higginson`).
# Units: mm, N, s, MPa.

# +
import argparse
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from tribofx.cases.film_setup import rigid_film
from tribofx.laws import Law, named_viscosity
from tribofx.references import barus_pressure, slider_reference
from tribofx.testing import taylor_orders

parser = argparse.ArgumentParser(description="your own viscosity law")
parser.add_argument("--quick", action="store_true", help="(the demo is fast anyway)")
parser.add_argument("--out", default=None, help="(nothing is written)")
args, _ = parser.parse_known_args()
rank0 = MPI.COMM_WORLD.rank == 0
# -

# The slider's data and the isoviscous peak; α such that α p_iso,max = 0.5.

K, L, h0, U, mu0 = 1.0, 10.0, 0.01, 1000.0, 1e-7
p_iso = slider_reference(K, L, h0, U, mu0)["p_max"]
alpha = 0.5 / p_iso


def gap(x):
    return h0 * (1 + K - K * x / L)


# ## The law, in one function
#
# Here: Barus written out by hand.  Replace the body by your own law.


def my_viscosity(p, mu0, alpha):
    return mu0 * ufl.exp(alpha * ufl.max_value(p, 0))


# ## Solve with it, and with the library's Barus

n = 100
films = {}
for name, law in (("mine", Law(my_viscosity, mu0=mu0, alpha=alpha)),
                  ("library", named_viscosity("barus", mu0, alpha=alpha))):
    film, problem = rigid_film(MPI.COMM_WORLD, 0.0, L, n, 1, gap, 0.5 * U, law, h_ref=h0)
    report = problem.solve()
    films[name] = (film, problem, report)
    if rank0:
        print(f"{name}: {report.iterations} Newton iterations")

# ## Checks
#
# 1. The same law twice: the same pressures, to the Newton tolerance (the two
#    forms are the same UFL up to names, so in fact to round-off).

pa = films["mine"][0].p.x.array
pb = films["library"][0].p.x.array
diff = MPI.COMM_WORLD.allreduce(float(np.max(np.abs(pa - pb), initial=0.0)), op=MPI.MAX)
assert diff <= 1e-10 * p_iso, diff

# 2. The exact Barus slider: the nodal pressures of 100 P1 elements are
#    second-order accurate (tests/test_reynolds.py: relative L² error 1.8e-4 at
#    100 elements), and the largest nodal value misses the peak between two nodes
#    by at most ½|p''|(h/2)² ≈ 1e-4 relative (p'' ≈ p_max/(L/3)², h = 0.1 mm):
#    within 1e-3 of the exact peak.

film = films["mine"][0]
p_max = MPI.COMM_WORLD.allreduce(float(film.p.x.array.max(initial=0.0)), op=MPI.MAX)
p_exact = barus_pressure(p_iso, alpha)
if rank0:
    print(f"p_max = {p_max:.5f} MPa (exact {p_exact:.5f}; isoviscous {p_iso:.5f})")
assert abs(p_max / p_exact - 1) < 1e-3

# 3. The Newton tangent of your law is exact (ufl.derivative differentiates it):
#    the Taylor remainder decays at second order.

problem = films["mine"][1]
d = fem.Function(film.Q)
d.interpolate(lambda x: 0.1 * np.sin(np.pi * x[0] / L))
orders, _ = taylor_orders(problem, [d], eps0=1e-2)
if rank0:
    print("Taylor orders", orders)
assert np.all(orders > 1.8)
if rank0:
    print("demo_own_law: all checks passed")
