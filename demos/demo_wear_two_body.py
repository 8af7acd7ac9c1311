# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # Reciprocating pin-on-flat: two elastic bodies, both worn (chapter §5.1)
#
# This demo illustrates how to:
#
# * put two deformable **Body** objects, each with its own shape field, in
#   contact through a **TwoBodyContact** (master–slave closest-point
#   projection on the *current* master surface, C++ kernel);
# * put a **Wear** interface on each side of that contact
#   (``contact.wear_surface("slave")`` and ``("master")``), each with its own
#   Archard coefficient;
# * drive a deformable master back and forth by a prescribed displacement
#   (``ReciprocatingCycle(..., drive=...)``) and let the **Stepper** separate
#   the time scales for both shapes at once;
# * check Archard, eq. (18) and the energy balance of the cycles.
#
# ## Equations (chapter §3, eqs. 13–18, 21–23)
#
# The friction traction T_T of a slave point and its slip ξ̄̇ relative to the
# master give the nominal dissipation Ḋ⁽¹⁾ = T_T·ξ̄̇ (17).  Archard's law in
# the dissipation form wears the slave by Ẇ⁽¹⁾ = K⁽¹⁾ Ḋ⁽¹⁾ and the master by
#
# $$
# \dot W^{(2)} = \frac{j^{(2)}}{j^{(1)}} K^{(2)} \dot D^{(1)} \quad (18),
# $$
#
# at the master point x̄⁽²⁾ the slave point faces.  In the nodal scheme a slave
# node passes the volume K⁽²⁾ ΔD⁽¹⁾ w⁽¹⁾ to the two nodes of its master segment
# (weights 1 − ξ, ξ), which is (18) with its area factors (ds = j dS on both
# sides).  Over one fast cycle (run-in from −A, then +A, −2A, +A) the
# increments are summed (22) and averaged (23); the averaged rates drive the
# shape evolution law (28) of both bodies, here explicitly (θ = 0).
#
# ## Changing it
#
# ``K_pin``, ``K_block``, ``E_pin``, ``E_block`` and ``scheme=IMPLICIT`` in the two
# ``Wear`` calls (implicit on the slow time, a Picard iteration of cycles).
# The same problem is the case ``tribofx run wear-reciprocating`` (parameters
# in ``tribofx list``).  Units: mm, N, s, MPa.

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
from tribofx.meshes import block as block_mesh
from tribofx.meshes import pin as pin_mesh

from tribofx.body import Body
from tribofx.continuation import ConstantParameter, Continuation
from tribofx.interfaces import TwoBodyContact, Wear
from tribofx.output import write_summary, write_vtx
from tribofx.scheme import EXPLICIT
from tribofx.stepper import ReciprocatingCycle, Stepper

parser = argparse.ArgumentParser(description="two-body reciprocating wear demo")
parser.add_argument("--quick", action="store_true", help="coarse mesh, 200 cycles (CI)")
parser.add_argument("--out", default=None, help="write summary.json and VTX")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
# -

# ## The two bodies
#
# Pin 2 × 2 mm with a half-round tip (R = 2 mm), E = 20 MPa, pressed by F =
# 1 N/mm on its top, sides held laterally; block 6 × 1.5 mm, E = 10 MPa, its
# bottom moved by the drive.  The pin's tip is the slave (the finer surface).

# +
W, H, R, F, E_pin, E_block, nu, mu_f = 2.0, 2.0, 2.0, 1.0, 20.0, 10.0, 0.3, 0.3
K_pin, K_block, A, V = 1e-4, 5e-5, 0.5, 10.0
n = 10 if args.quick else 20
cycles, dt = (200, 20.0) if args.quick else (2000, 40.0)

msh, ft = pin_mesh.pin_body(W, H, R, n, comm)
mu, lmbda = lame_parameters(E_pin, nu)
pin = Body(msh, ft, pin_mesh.NAMES, "plane_strain", ("neo-hookean", {"mu": mu, "lmbda": lmbda}),
           shape=True, aux=(E_pin, 0.3), name="pin")
load = fem.Constant(msh, 0.0)
pin.add_traction("top", load * ufl.as_vector([0.0, -F / W]))
pin.add_dirichlet("sides", 0.0, component=0)
pin.add_shape_dirichlet("sides", 0)
pin.add_shape_dirichlet("top", 1)

h_block = 4 * (W / n) / 3
bmsh, bft = block_mesh.block_mesh(comm, (-3.0, -1.5), (3.0, 0.0), round(6 / h_block),
                                  round(1.5 / h_block))
mu, lmbda = lame_parameters(E_block, nu)
block = Body(bmsh, bft, block_mesh.NAMES, "plane_strain",
             ("neo-hookean", {"mu": mu, "lmbda": lmbda}), shape=True, aux=(E_block, 0.3),
             name="block")
motion = block.add_dirichlet("bottom", np.zeros(2))
for name, c in (("bottom", 0), ("bottom", 1), ("sides", 0)):
    block.add_shape_dirichlet(name, c)
# -

# ## Contact, the wear of both sides, the cycle and the stepper

# +
contact = TwoBodyContact(pin, "contact", block, "top", rho_n=E_block / (W / n), friction=mu_f)
# Wear's k is the coefficient of the pressure form; in the dissipation form K = k/μ
wear_pin = Wear(contact.wear_surface("slave"), k=K_pin * mu_f, scheme=EXPLICIT, averaged=True,
                name="wear_pin")
wear_block = Wear(contact.wear_surface("master"), k=K_block * mu_f, scheme=EXPLICIT, averaged=True,
                  name="wear_block")


def drive(position):
    """Move the block's bottom to ``position``; translate the block as Newton's predictor."""
    block.u.x.array.reshape(-1, 2)[:, 0] += position - float(motion.value[0])
    motion.value[0] = position


cycle = ReciprocatingCycle(contact, 2 * A, 8 if args.quick else 16, V, drive=drive,
                           force=lambda: block.reaction("bottom", 0))
stepper = Stepper([pin, block, contact, wear_pin, wear_block], [wear_pin, wear_block],
                  cycle=cycle, parameters=[load, motion], name="demo_two_body",
                  problem_kw={"max_it": 40})
# -

# ## Loading and the slow time
#
# Newton starts from the pin pushed 0.08 mm into the block, so that the tip
# nodes start in contact; the load factor goes to 1 in two steps.

# +
pin.u.x.array.reshape(-1, 2)[:, 1] = -0.08
Continuation(stepper.problem, ConstantParameter(load)).march(1.0, steps=2, predictor=False)
stepper.start()
w_ref = contact.surface.nodal(ufl.TestFunction(contact.Q) * contact.dsc)
n_own = contact.Q.dofmap.index_map.size_local
history = []


def log(st, report):
    d = st.last_increments[0]         # the pin's K ΔD over the step's cycle
    cycle_d = comm.allreduce(float(d[:n_own] @ w_ref[:n_own]), op=MPI.SUM) / K_pin
    history.append({"t": st.t, "cycles": st.t / cycle.period,
                    "pin": wear_pin.worn_volume(), "block": wear_block.worn_volume(),
                    "cycle_dissipation": cycle_d, "drive_work": cycle.work,
                    "work_bound": cycle.work_bound, "dt": report.dt})


stepper.run(cycles * cycle.period, dt, on_step=log)
if comm.rank == 0:
    print(f"{stepper.problem.num_dofs} unknowns in the contact problem, "
          f"{stepper.shape.num_dofs} in the shape step of both bodies")
    print(" cycles  worn pin (mm²/mm)  worn block  cycle dissipation  drive work")
    for r in history:
        print(f"{r['cycles']:7.0f}  {r['pin']:17.6f}  {r['block']:10.6f}  "
              f"{r['cycle_dissipation']:17.5f}  {r['drive_work']:10.5f}")
if args.out:
    write_vtx(comm, f"{args.out}/pin.bp", [pin.u, pin.w])
    write_vtx(comm, f"{args.out}/block.bp", [block.u, block.w])
    write_summary(comm, f"{args.out}/summary.json", {"case": "demo_wear_two_body",
                                                     "history": history})
# -

# ## Checks
#
# * Archard (14) for the pin: worn area = K_pin × the dissipated energy
#   Σ (Δt/Δτ) D_cycle, and eq. (18): the block's worn area is K_block/K_pin
#   times the pin's.  Both hold to the tolerance of the shape step (28) (its
#   swept Nanson vector makes the swept volume exact): 1e-7 relative.
# * Energy: over a closed cycle the drive's work ∮ F dx equals the frictional
#   dissipation, to the error bound ½ Σ |ΔF||Δx| of its trapezoidal rule.

# +
energy = sum(r["cycle_dissipation"] * r["dt"] / cycle.period for r in history)
last = history[-1]
assert abs(last["pin"] - K_pin * energy) <= 1e-7 * last["pin"], (last["pin"], K_pin * energy)
assert abs(last["block"] - K_block / K_pin * last["pin"]) <= 1e-7 * last["block"], last
for r in history:
    assert abs(r["drive_work"] - r["cycle_dissipation"]) <= r["work_bound"], r
if comm.rank == 0:
    print(f"worn pin {last['pin']:.6f} = K_pin × {energy:.3f} N·mm/mm dissipated; "
          f"block/pin = {last['block'] / last['pin']:.8f}")
    print("demo_wear_two_body: all checks passed")
# -
