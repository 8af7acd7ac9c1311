# ---
# jupytext:
#   text_representation:
#     extension: .py
#     format_name: light
# ---

# # The O-ring over a reciprocating stroke (transient soft EHL, past chapter §8.1)
#
# The chapter solves the seal's outstroke and instroke as two steady states.
# This demo runs the rod through its stroke, U(t) = U cos(2πt/T), and shows how to:
#
# * make a **Film** transient (``Film.transient``): the JFO rows (57) gain the
#   rate of the fluid content θh on the moving lubrication surface, here taken
#   node by node (``lumped=True``);
# * give the film an **open end** (``ReynoldsFilm.add_inflow``): where the rod
#   enters the seal it brings back the layer it carried out; where it leaves, the
#   end is a natural outlet; a full film leaks out there at p ≈ 0;
# * step it with the core's **Stepper**, whose *schedule* sets the rod speed and
#   the supply at each step;
# * check the transient film against the steady one: at a long period the film
#   follows the steady outstroke of the same speed, up to a lag ∝ 1/T;
# * run the whole cycle (T = 0.1 s) and keep the oil's books: what the sealed end
#   lets in minus what the air end lets out is what the film gains, step by step.
#
# ## Equations
#
# On S (the rod cylinder), per unit reference length of the ring's arc Γ_l,
#
#     d(θ h J_S w)/dt + d/dX [w θ (h v̄ − h³/(12μ) ∂p/∂s)] = 0,
#     p ≥ 0, λ = 1 − θ ≥ 0, pλ = 0,
#
# (w = 2πr, v̄ = U/2) with backward differences in time.  At the air end the
# Couette flux w θ h v_n is replaced, where it enters (v_n < 0), by w c_in v_n:
# c_in is the content the rod carried out there at the mirror time of the
# outstroke (``tribofx.cases.ehl_oring.AirLayer``).
#
# ## Changing it
#
#     tribofx run ehl-oring --set stroke=cycle --set sigma=2e-4 --set arc_refine=1   # a cycle
#     tribofx run ehl-oring --set stroke=cycle --set sigma=2e-4 --set arc_refine=1 \
#         --set scheme=bdf2 --set cycles=2                                  # two, BDF2
#
# A smooth rod's film closes just after the reversal (at U = 0 only the squeeze
# holds it); ``sigma`` makes the rod rough (Greenwood–Tripp asperities carry
# where the film collapses).  Units: mm, N, s, MPa.

# +
import argparse
import math
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
from mpi4py import MPI

from tribofx.cases import ehl_oring
from tribofx.cases.ehl_oring import build, cycle_stepper, solve_to
from tribofx.output import write_summary
from tribofx.params import resolve

parser = argparse.ArgumentParser(description="O-ring over a reciprocating stroke")
parser.add_argument("--quick", action="store_true",
                    help="density 2, and 4 steps of the fast cycle instead of the whole (CI)")
parser.add_argument("--out", default=None, help="write summary.json here")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
# -

# ## The seal, made transient
#
# The case's seal (``tribofx.cases.ehl_oring``) at U = 400 mm/s and
# p_s = 1 MPa, its film transient with the lumped rate and the air end open;
# the steady outstroke is the state at t = 0.  The period is long (T = 10 s), so
# that the film should follow the rod's slow deceleration.

# +
U0, T = 400.0, 10.0
v = resolve(ehl_oring.Params, {"mesh": "2" if args.quick else "4", "stroke": "cycle",
                                  "period": str(T), "scheme": "bdf2",
                                  "arc_refine": "0" if args.quick else "1"})
# the seal at U0, transient, its steady outstroke, and the Stepper whose schedule sets
# the rod speed, the air end's supply and the vertex-rule share ω at each step
stepper = cycle_stepper(v)
seal = stepper.seal
stepper.run(T / 8, T / 40)            # to U = 400 cos 45° = 282.8 mm/s, 5 steps
cycle = seal.measures()
# -

# ## Against the steady outstroke at the same speed
#
# The steady seal (no time) solved at 282.8 mm/s.  The film's lag behind the
# rod is its response time (the contact's length over U, about 1 ms) times the
# relative deceleration (2π/T) tan 45°: below 1e-2 of h at T = 10 s
# (``tests/test_oring_cycle.py`` shows it falling like 1/T).

# +
U = U0 * math.cos(math.pi / 4)
steady = build(resolve(ehl_oring.Params, {"mesh": v.mesh, "U": str(U)}), 1000.0)
solve_to(steady, v, U, [1.0])
ref = steady.measures()
dev = {k: cycle[k] / ref[k] - 1 for k in ("h_min", "h_mean", "p_max")}
if comm.rank == 0:
    print(f"t = T/8, U = {seal.U:.1f} mm/s: h_min {1e3 * cycle['h_min']:.4f} µm "
          f"(steady {1e3 * ref['h_min']:.4f}), h_mean {1e3 * cycle['h_mean']:.4f} µm "
          f"(steady {1e3 * ref['h_mean']:.4f}); departures "
          + ", ".join(f"{k} {x:.2e}" for k, x in dev.items()))
assert all(abs(x) < 1e-2 for x in dev.values()), dev
# -

# ## The whole cycle, and the oil's books
#
# At T = 0.1 s (40 steps per period) the rod reverses twice.  At the reversal
# only the squeeze holds a smooth film, so the rod is made rough (σ = 0.2 µm:
# Greenwood–Tripp asperities carry where the film collapses), and the film arc
# is refined once (``arc_refine=1``, 12.5 µm elements, a cycle's default): at 25 µm the outlet
# constriction of the instroke is one node wide, h_min jumps from step to step
# and Newton may stall there.  The fluxes through the ends come from the
# discrete rows (``Film.consistent_fluxes``); over each step
#
#     C_{n+1} − C_n = Δt (q_sealed − q_air)   (backward Euler),
#
# C the oil in the film, to the solver's tolerance: the JFO film conserves mass,
# and the cycle's leakage is what the air end lets out.

# +
vc = resolve(ehl_oring.Params, {"stroke": "cycle", "scheme": "euler",
                                   **({"mesh": "2", "arc_refine": "0"} if args.quick else
                                      {"sigma": "2e-4", "arc_refine": "1"})})
cyc = cycle_stepper(vc)
film, Tc = cyc.seal.film, vc.period
books = [(0.0, film.content(), 0.0, 0.0, 0.0)]


def keep_books(st, report):
    """After each step: the oil, the end fluxes, and the bound of the books: N nodes ×
    the rows' stopping tolerance (mm³/s)."""
    q_sealed, q_air = film.consistent_fluxes()
    bound = film.Q.dofmap.index_map.size_global * film.tolerances()[film.p].atol
    books.append((st.t, film.content(), q_sealed, q_air, bound))


dt = Tc / vc.cycle_steps
cyc.run(4 * dt if args.quick else Tc, dt, on_step=keep_books)
t, C, q_s, q_a, bound = (np.array(col) for col in zip(*books))
step_error = np.abs(np.diff(C) - np.diff(t) * (q_s[1:] - q_a[1:]))
leak, intake = np.diff(t) @ q_a[1:], np.diff(t) @ q_s[1:]
if comm.rank == 0:
    print(f"{len(t) - 1} steps to t = {t[-1]:.4f} s: leakage {leak:.4f} mm³, intake "
          f"{intake:.4f} mm³, oil in the film {C[0]:.4f} → {C[-1]:.4f} mm³; the books "
          f"close to {step_error.max():.1e} mm³ per step")
# each step's books close to the sum of the interior rows, each below the rows'
# stopping tolerance at convergence: |error| ≤ Δt · N · atol
assert np.all(step_error <= np.diff(t) * bound[1:]), (step_error, bound)
if comm.rank == 0:
    print("all checks passed")
if args.out:
    write_summary(comm, f"{args.out}/summary.json",
                  {"case": "demo_oring_cycle", "U": seal.U, "cycle": cycle, "steady": ref,
                   "departures": dev, "leakage": leak, "intake": intake,
                   "content": [float(C[0]), float(C[-1])]})
# -
