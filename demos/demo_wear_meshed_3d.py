# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
# ---

# # Finite wear in 3D against a meshed, curved rigid countersurface, with friction
#
# This demo illustrates how the core composes into a configuration that is not a
# case: a hyperelastic block (a shaped **Body**) pressed onto a rigid cylinder
# given as a *surface mesh* (``rigid_surface_mesh``: the C++ closest-point kernel
# projects the slave nodes before every residual and Jacobian evaluation), which
# slides along its axis; frictional **Contact** with Eulerian slip, **Wear** by
# the dissipation form of Archard's law (eqs. 13–14, 17), and the implicit
# θ-scheme (28) of the **Stepper** in (u, λ_N, λ_T, w, ζ).
#
# Checks: (i) the worn volume ∫(1 − det G) dV̂ equals Σ Δt k V F_N(t_{n+1}), F_N
# the normal contact force: in Coulomb sliding K T_T·v_T = k|T_N|V, and the
# swept Nanson vector of (28) makes the discrete volume balance exact (Newton
# tolerances, 1e-9); (ii) the same run on the analytic cylinder: the flat facets
# of the meshed one lie inside it by at most the chord sag s = R(1 − cos(Δθ/2)),
# so the meshed run wears less, by at most the volume between the two surfaces
# over the contact area A_c (the difference of the worn depths relaxes towards
# the local sag and never exceeds it): |V_mesh − V_analytic| ≤ A_c s.
# Units: mm, N, s, MPa.

# +
import argparse
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")
import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
from dolfinx import mesh
from mpi4py import MPI
from tribofx.forms.hyperelastic import lame_parameters

from tribofx.body import Body
from tribofx.interfaces import Contact, Wear
from tribofx.obstacles import rigid_cylinder, rigid_surface_mesh
from tribofx.scheme import IMPLICIT
from tribofx.stepper import Stepper

parser = argparse.ArgumentParser(description="3D wear against a meshed cylinder")
parser.add_argument("--quick", action="store_true", help="coarser block (CI)")
parser.add_argument("--out", default=None, help="output folder (checkpoint)")
args, _ = parser.parse_known_args()
comm = MPI.COMM_WORLD
E, nu, mu_f, k, V, R, delta = 10.0, 0.3, 0.3, 1e-3, 1.0, 2.0, 0.02
n = 6 if args.quick else 10  # elements across the 1 mm width of the block

# the block [−0.5, 0.5] × [0, 0.5] × [0, 0.5] mm, its faces tagged by name
msh = mesh.create_box(comm, [[-0.5, 0, 0], [0.5, 0.5, 0.5]], [n, n // 2, n // 2],
                      mesh.CellType.tetrahedron)
faces = {"contact": lambda x: np.isclose(x[2], 0.0), "top": lambda x: np.isclose(x[2], 0.5),
         "sides": lambda x: np.isclose(abs(x[0]), 0.5),
         "ends": lambda x: np.isclose(x[1], 0.0) | np.isclose(x[1], 0.5)}
found = [mesh.locate_entities_boundary(msh, 2, marker) for marker in faces.values()]
facets, order = np.concatenate(found), np.argsort(np.concatenate(found))
values = np.repeat(np.arange(1, 5, dtype=np.int32), [len(f) for f in found])
ft = mesh.meshtags(msh, 2, facets[order], values[order])

# the meshed cylinder: flat quadrilaterals on the circle of radius R (axis e_y), top at z = 0
theta, ys = np.linspace(-0.6, 0.6, 49), np.linspace(-0.25, 0.75, 5)
nodes = np.array([[R * np.sin(t), y, R * np.cos(t) - R] for y in ys for t in theta])
quads = np.array([[j * 49 + i, j * 49 + i + 1, (j + 1) * 49 + i, (j + 1) * 49 + i + 1]
                  for j in range(4) for i in range(48)], dtype=np.int32)  # t₀ × t₁ radial


def wear_run(countersurface):
    mu, lmbda = lame_parameters(E, nu)
    body = Body(msh, ft, dict(zip(faces, range(1, 5))), "3d", ("neo-hookean", {
        "mu": mu, "lmbda": lmbda}), shape=True, aux=(E, 0.3), velocity=np.zeros(3))
    body.add_dirichlet("top", np.zeros(3))
    for name, comp in (("top", 2), ("sides", 0), ("ends", 1)):
        body.add_shape_dirichlet(name, comp)
    contact = Contact(body, "contact", countersurface, rho_n=E * n, friction=mu_f,
                      slip="eulerian", V_master=(0.0, V, 0.0))
    wear = Wear(contact, k=k, scheme=IMPLICIT)
    stepper = Stepper([body, contact, wear], wear, name="demo_meshed3d",
                      checkpoint=f"{args.out}/checkpoint" if args.out else None)
    contact.counterpart.offset.value[2] = delta  # the cylinder indents the block by δ
    stepper.problem.solve()
    stepper.problem.commit()
    out = []  # t, worn volume, normal force, max depth, contact area
    stepper.run(20.0, 5.0, on_step=lambda st, r: out.append(
        (st.t, wear.worn_volume(), contact.traction_magnitudes()[0], wear.max_depth(),
         contact.measures()[0])))
    return np.array(out)


meshed = wear_run(rigid_surface_mesh(nodes, quads, "quadrilateral"))
analytic = wear_run(rigid_cylinder(np.array([0.0, 0.0, -R]), R, axis=(0.0, 1.0, 0.0)))
for m, a in zip(meshed, analytic) if comm.rank == 0 else ():
    print(f"t = {m[0]:4.0f} s: worn volume {m[1]:.6e} mm³ (analytic cylinder {a[1]:.6e}), "
          f"F_N = {m[2]:.5f} N, max depth {m[3]:.5f} mm, contact area {m[4]:.4f} mm²")
# -

# ## Checks

# +
archard = np.cumsum(5.0 * k * V * meshed[:, 2])  # Σ Δt k V F_N(t_{n+1})
assert np.allclose(meshed[:, 1], archard, rtol=1e-9), (meshed[:, 1], archard)
sag = R * (1 - np.cos(0.6 / 48))  # of the facets, Δθ = 1.2/48
assert np.all(np.abs(meshed[:, 1] - analytic[:, 1]) <= meshed[:, 4].max() * sag), sag
assert meshed[-1, 3] > 0.25 * delta  # a finite shape change (a quarter of the indentation)
if comm.rank == 0:
    print("demo_wear_meshed_3d: all checks passed")
# -
