# ---
# jupytext:
#   text_representation:
#     extension: .py
#     format_name: light
# ---

# # Soft-EHL film against a meshed countersurface in 3D
#
# This demo illustrates how to:
#
# * put a lubricating **Film** (steady Reynolds equation (49) on S = P(γ_l), SUPG,
#   penalty cavitation, traction (46)) on a 3D hyperelastic **Body** — a soft ball;
# * let the countersurface be a **surface mesh** (``rigid_surface_mesh``: a gmsh
#   triangulation of a plane sliding at 2U), projected by the C++ lubrication
#   kernel at the nodes of Γ_l before every assembly, which also supplies ∂P/∂x,
#   ∂ν/∂x and ∂²P/∂x² for the exact tangent (eqs. 36–37);
# * find the plane position that carries the load W with a **Continuation**;
# * check it against the same problem with the closed-form plane (facets of a
#   plane are exact: the two must agree to solver tolerance) and Hamrock–Dowson.
#
# Not a case of ``tribofx run``: a configuration assembled from the core.  Units: mm, N, s, MPa.

# +
import argparse
import math
import os

os.environ.setdefault("UCX_TLS", "self,sm,tcp")

import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)
import numpy as np
from mpi4py import MPI
from tribofx.forms.hyperelastic import lame_parameters
from tribofx.meshes.ball import LUBRICATED, MIDPLANE, SYMMETRY, cap_height, quarter_ball
from tribofx.meshes.obstacles import plane_surface_mesh

from tribofx.body import Body
from tribofx.continuation import ConstantParameter, Continuation
from tribofx.interfaces import Film, FilmScales, Fluid, Penalty, Quadrature
from tribofx.obstacles import rigid_plane, rigid_surface_mesh
from tribofx.output import write_summary
from tribofx.problem import Problem
from tribofx.references import composite_modulus, hamrock_dowson, hertz

parser = argparse.ArgumentParser(description="soft-EHL ball on a meshed plane")
parser.add_argument("--quick", action="store_true", help="coarse mesh (CI)")
parser.add_argument("--out", default=None, help="write summary.json here")
args, _ = parser.parse_known_args()
# -

# Ball R = 12.7 mm, E = 1.19 MPa, ν = 0.45; μU = 1e-4 N/mm; W = 2 N (Hertz a ≈ 0.18 R).
# Quarter model (symmetry y = 0, mid-plane held, the plane moves), element size a/4
# (``--quick``) or a/8 at the contact.

# +
R, E, nu, mu, U, W = 12.7, 1.19, 0.45, 1e-8, 1e4, 2.0
hz = hertz(W, R, E, nu)
h_c = hamrock_dowson(W, mu, U, R, composite_modulus(E, nu))[0]
theta = math.radians(40.0)
msh, _, ft = quarter_ball(R, theta, hz.a / (4 if args.quick else 8), 4.0, 1.6 * hz.a)
lame = dict(zip(("mu", "lmbda"), lame_parameters(E, nu)))


def film_problem(countersurface, name):
    ball = Body(msh, ft, {"cap": LUBRICATED, "mid": MIDPLANE, "sym": SYMMETRY}, "3d",
                ("neo-hookean", lame), name=name)
    ball.add_dirichlet("mid", np.zeros(3))
    ball.add_dirichlet("sym", 0.0, component=1)
    film = Film(ball, "cap", countersurface, Fluid(mu),
                scales=FilmScales(pressure=hz.p0, film=h_c, speed=U),
                cavitation=Penalty(1e-4 * 12 * mu * hz.a**2 / h_c**3),
                quadrature=Quadrature(degree=2), V_counter=(2 * U, 0, 0), name=f"{name}_film")
    film.add_pressure_bc(lambda X: np.abs(X[2] - cap_height(R, theta)) < 1e-6 * R)
    # start: the dry ball under the Hertz pressure, film h_c below the contact point
    film.start_from_pressure(lambda x: hz.p0 * np.sqrt(np.maximum(
        0, 1 - (x[0] ** 2 + x[1] ** 2) / hz.a**2)), h_c, np.zeros(3))
    return film, Problem([ball, film], name=name)


def load(film):
    return 2 * film.force()[2]  # the half ball carries half of W


analytic, problem = film_problem(rigid_plane(np.zeros(3), np.eye(3)[2]), "analytic")
Continuation(problem, ConstantParameter(analytic.counterpart.offset, 2),
             response=lambda: load(analytic), rtol=1e-4, max_step=0.1 * hz.delta,
             admissible=lambda: analytic.min_film() > 0).reach(
    W, slope=1.5 * W / hz.delta)

# the meshed plane, solved at the position the analytic film found
plane = rigid_surface_mesh(*plane_surface_mesh(3, (-R, R), R / 4))
meshed, problem_m = film_problem(plane, "meshed")
meshed.counterpart.offset.value[:] = analytic.counterpart.offset.value
report = problem_m.solve()
res = {k: (f(analytic), f(meshed)) for k, f in (
    ("W", load), ("h_min", lambda f: f.min_film()),
    ("p_max", lambda f: MPI.COMM_WORLD.allreduce(f.p.x.array.max(), op=MPI.MAX)))}
if MPI.COMM_WORLD.rank == 0:
    for k, (x, y) in res.items():
        print(f"{k}: analytic plane {x:.8g}, meshed plane {y:.8g}")
    print(f"meshed plane: {problem_m.num_dofs} unknowns, {report.iterations} Newton iterations")
if args.out:
    write_summary(MPI.COMM_WORLD, f"{args.out}/summary.json", res)
# -

# ## Checks
#
# * A triangulated plane is exact (y, ν, ∂P/∂x of its facets are those of the
#   plane), so the meshed film is the analytic one up to the Newton tolerance
#   (per block 1e-10 of the scales) and kernel round-off: 1e-7 relative.
# * Hamrock–Dowson (1978) minimum film, at a/8 only (a/4 under-resolves the side
#   lobes where h_min sits): their fit is within ±20 %, plus the mesh: 25 %.

# +
for k, (x, y) in res.items():
    assert abs(y / x - 1) < 1e-7, (k, x, y)
h_min_hd = hamrock_dowson(W, mu, U, R, composite_modulus(E, nu))[1]
assert args.quick or abs(res["h_min"][1] / h_min_hd - 1) < 0.25, res
if MPI.COMM_WORLD.rank == 0:
    print("demo_film_meshed_3d: all checks passed")
# -
