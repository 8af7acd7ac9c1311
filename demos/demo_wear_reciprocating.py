# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # Reciprocating pin-on-flat wear with separation of time scales
#
# This demo illustrates how to:
#
# * put a **Contact** interface with Lagrangian (incremental) Coulomb friction on
#   the shaped **Body** of a pin, and a **Wear** interface driven by the
#   *cycle-averaged* wear rate (``averaged=True``);
# * describe one fast-time loading cycle, a reciprocating stroke of the rigid
#   flat, by a ``ReciprocatingCycle``;
# * let the **Stepper** do the time-scale separation: per slow step one cycle
#   at the fixed worn shape, the wear increment accumulated node by node, the
#   averaged rate driving the shape step (explicit θ = 0 on the slow time);
# * check the worn area against Archard's law over the sliding distance and
#   against the time integral of the averaged rate.
#
# ## Equations (chapter §4.2, eqs. 21–23; §5.1)
#
# The rounded pin of ``demo_wear_pin.py`` (W = H = 2 mm, R = 4 mm, E = 40 MPa,
# q = 2 MPa) rubs with friction μ = 0.3 on a flat moving back and forth with
# peak-to-peak stroke 2A at V.  At fixed slow time t the deformation problem is
# a quasi-static frictional contact problem in the fast time τ (eq. 21).  Each
# cycle starts with gross sliding (contact memory erased, flat at −A, run-in to
# the centre), then +A, −2A, +A.  The wear increment of a node (eq. 22) is the
# dissipation form (13)–(14) summed over the fast sub-steps j,
#
# $$
# \Delta W = \sum_j K\, T_T^j\cdot \Delta s_j, \qquad K = k/\mu, \qquad
# \dot{\overline W} = \Delta W / \Delta\tau \quad (23),
# $$
#
# (zero in stick), and the slow time follows (28) with the averaged rate,
# (w_{n+1} − w_n)·a = −Δt W̄̇, Δt = (cycles per step)·Δτ.
#
# ## Changing it
#
# ``stroke``, ``fast_steps`` (a multiple of 4) and ``cycles`` per slow step below;
# ``scheme=IMPLICIT`` (θ = 1) in ``Wear`` makes the slow time implicit (a Picard iteration,
# one cycle per iterate).  The same run is the case ``wear-pin`` with
# ``--set mode=cyclic``.  Units: mm, N, s, MPa.

# +
import argparse
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI
from tribofx.forms.hyperelastic import lame_parameters
from tribofx.meshes.pin import NAMES, pin_body

from tribofx.body import Body
from tribofx.continuation import ConstantParameter, Continuation
from tribofx.interfaces import Contact, Wear
from tribofx.obstacles import rigid_plane
from tribofx.output import write_summary, write_vtx
from tribofx.references import hertz
from tribofx.scheme import EXPLICIT
from tribofx.stepper import ReciprocatingCycle, Stepper

parser = argparse.ArgumentParser(description="reciprocating wear demo")
parser.add_argument("--quick", action="store_true", help="T = 200 s, 8 sub-steps (CI)")
parser.add_argument("--out", default=None, help="write summary.json, VTX, checkpoint")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
# -

# ## The configuration
#
# 10 × 10 mesh, stroke 2A = 2 mm at V = 10 mm/s (Δτ = 0.4 s, sliding distance
# 4 mm per cycle), 16 fast sub-steps per cycle, 125 cycles per slow step
# (Δt = 50 s), k = 5·10⁻⁶ mm³/(N·mm), T = 1000 s (2500 cycles); ``--quick``:
# 8 sub-steps, T = 200 s.  Δt must stay below the explicit critical step ∼ h/E
# (eq. 31; ≈ 150 s here).

# +
W, H, R, q, V, k, E, nu, mu_f = 2.0, 2.0, 4.0, 2.0, 10.0, 5e-6, 40.0, 0.3, 0.3
stroke, fast_steps, cycles = 2.0, 8 if args.quick else 16, 125
T, n = 200.0 if args.quick else 1000.0, 10
msh, facet_tags = pin_body(W, H, R, n, comm)
mu, lmbda = lame_parameters(E, nu)
body = Body(msh, facet_tags, NAMES, "plane_strain", ("neo-hookean", {"mu": mu, "lmbda": lmbda}),
            shape=True, aux=(E, 0.3))
load = fem.Constant(msh, 0.0)
body.add_traction("top", load * ufl.as_vector([0.0, -q]))
body.add_dirichlet("sides", 0.0, component=0)
body.add_shape_dirichlet("sides", 0)
body.add_shape_dirichlet("top", 1)

# Lagrangian Coulomb friction: the slip is the projection point's increment per sub-step
contact = Contact(body, "contact", rigid_plane(np.zeros(2), np.array([0.0, 1.0])),
                  rho_n=E / (W / n), friction=mu_f, slip="lagrangian")
wear = Wear(contact, k=k, scheme=EXPLICIT, averaged=True)  # (28) driven by rate_bar
cycle = ReciprocatingCycle(contact, stroke, fast_steps, V, axis=0)
checkpoint = f"{args.out}/checkpoint" if args.out else None
stepper = Stepper([body, contact, wear], wear, cycle=cycle, parameters=[load],
                  checkpoint=checkpoint, name="demo_recip")
dt = cycles * cycle.period
# -

# ## Loading, the first cycle and the slow time

# +
a = hertz(q * W, R, E, nu, line=True).a
body.u.x.array.reshape(-1, 2)[:, 1] = -(a * a / (2 * R) + q * H / E)
Continuation(stepper.problem, ConstantParameter(load)).march(1.0, steps=1, predictor=False)
stepper.start()  # gross sliding from −A to the centre

history = []


def log(st, report):
    area, _ = contact.measures()
    history.append({"t": st.t, "cycles": st.t / cycle.period, "worn_area": wear.worn_volume(),
                    "depth": wear.max_depth() + 0.0, "half_width": area / 2,
                    "rate": wear.wear_rate_integral(),
                    "newton": report.iterations if report else 0})


log(stepper, None)
stepper.run(T, dt, on_step=log)
if comm.rank == 0:
    print(f"{stepper.problem.num_dofs} unknowns in the fast-time (contact) problem, "
          f"{stepper.shape.num_dofs} in the shape step")
    print(" t (s)  cycles  worn area (mm²/mm)  max depth (mm)  half-width (mm)  Newton")
    for h in history:
        print(f"{h['t']:6.0f}  {h['cycles']:6.0f}  {h['worn_area']:18.8f}  {h['depth']:14.5f}  "
              f"{h['half_width']:15.4f}  {h['newton']:6d}")
if args.out:
    write_vtx(comm, f"{args.out}/displacement.bp", [body.u, body.w])
    write_summary(comm, f"{args.out}/summary.json", {"case": "demo_wear_reciprocating",
                                                     "history": history})
# -

# ## Checks
#
# * The explicit slow step from t_n uses the rate averaged over the cycle at
#   t_n, so the worn area is Σ Δt ∫ W̄̇ dS (discrete conservation law of the
#   swept Nanson vector) to the Newton tolerances (~1e-9 relative).
# * Archard over the sliding distance s = 2·stroke·N: the worn area is below
#   k (qW) s — stick at the two stroke reversals, where the elastic tangential
#   displacement of the contact is recovered without slip, removes wear and
#   never adds any — by a deficit of O(compliance/stroke): 1.4–2.8 % for
#   strokes 4–2 mm in ``tests/test_wear.py`` (it halves with the stroke); 3 %.
# * Full run: the tip is worn flat (contact half-width > W/2 − h).

# +
t = np.array([h["t"] for h in history])
area = np.array([h["worn_area"] for h in history])
integral = np.concatenate([[0.0], np.cumsum(np.diff(t) * [h["rate"] for h in history[1:]])])
assert np.allclose(area, integral, rtol=1e-9, atol=1e-12), (area, integral)
archard = k * q * W * cycle.distance * history[-1]["cycles"]
assert 0.97 * archard < area[-1] < archard, (area[-1], archard)
if not args.quick:
    assert history[-1]["half_width"] > W / 2 - W / n, history[-1]
if comm.rank == 0:
    print(f"worn area {area[-1]:.6f} = {area[-1] / archard:.4f} × k q W (2 stroke) N")
    print("demo_wear_reciprocating: all checks passed")
# -
