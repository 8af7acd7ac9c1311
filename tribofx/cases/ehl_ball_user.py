"""A user's ball mesh for ``ehl-ball``: placed in the case's frame and checked.

``mesh_file`` gives the ball as a mesh with the facet groups ``lubricated``
(the cap Γ_l), ``midplane`` (held) and ``symmetry`` (a plane y = const).  The
case needs the ball in its frame — symmetry plane y = 0, cap centred at x = 0,
lowest point at z = 0 — with the radius of curvature R at the contact (R sets
the Hertz start, the scales and the references) and a cap that reaches past
the contact.  Units: mm; ``a`` is the Hertz radius at the load W.

Your own ball (``mesh_file``): a 3D gmsh ``.msh`` of the quarter ball with the
physical groups ``lubricated`` (Γ_l, the cap around the contact point),
``midplane`` (held, u = 0) and ``symmetry`` (a plane y = const, u_y = 0), read
and checked by :func:`tribofx.meshes.user.read_user_mesh`; any other boundary is
traction free.  It replaces theta_l, mesh, h_coarse and edge_refine (the cap and the
elements are the user's); R, E and ν still set the Hertz start, the scales
(penalty, SUPG pressure, tolerances) and the references, so R must be the
radius of the ball at the contact.  The mesh is moved so that the symmetry
plane is y = 0 (checked flat to 10⁻⁹ R: the centre line y = 0 of the results
is found by it), the middle of the cap's x extent is x = 0 and the cap's lowest
node z = 0 (the Hertz start is centred at the origin).  p = 0 on the cap's rim
(∂Γ_l off the symmetry line, any shape); the cap must reach 1.5 a(W) from the
contact point (rim radius √(x² + y²) checked, as R sin θ_l for the built cap),
and its curvature within a(W) of the contact point must be 1/R within 5 %
(least-squares fit, checked).  The case uses no element size of its own (SUPG
takes the cell size of Γ_l).
"""

import math

import numpy as np
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..params import InputError
from .film_setup import film_boundary

__all__ = ["USER_GROUPS", "check_curvature", "place_user_ball", "user_rim"]

USER_GROUPS = ("lubricated", "midplane", "symmetry")   # the groups of a user's ball


def _group_nodes(msh, ft, tag):
    """Return the local geometry nodes of the facets tagged ``tag``."""
    msh.topology.create_connectivity(2, 3)
    return np.unique(dmesh.entities_to_geometry(msh, 2, ft.find(tag), False).ravel())


def place_user_ball(msh, ft, names, v, a):
    """Move a user's ball: symmetry plane to y = 0, cap centred at x = 0, lowest at z = 0.

    Raises InputError if the symmetry group is not a plane y = const (to 10⁻⁹ R).
    """
    comm, x = msh.comm, msh.geometry.x

    def extent(nodes, k):
        return (comm.allreduce(float(np.min(x[nodes, k], initial=np.inf)), op=MPI.MIN),
                comm.allreduce(float(np.max(x[nodes, k], initial=-np.inf)), op=MPI.MAX))

    y0, y1 = extent(_group_nodes(msh, ft, names["symmetry"]), 1)
    if y1 - y0 > 1e-9 * v["R"]:
        raise InputError(f"the group 'symmetry' of {v['mesh_file']!r} must be a plane "
                         f"y = const (spans y = {y0:.6g} … {y1:.6g} mm)")
    cap = _group_nodes(msh, ft, names["lubricated"])
    x0, x1 = extent(cap, 0)
    z0, _ = extent(cap, 2)
    x -= np.array([0.5 * (x0 + x1), y0, z0])
    check_curvature(msh, cap, v, a)


def check_curvature(msh, cap, v, a):
    """Raise InputError unless the cap's curvature at the contact is 1/R within 5 %.

    Least squares z = c + k ρ²/2 over the cap's nodes within ρ = √(x² + y²) ≤ a
    (Hertz a at W; owned nodes, summed over the ranks): R sets the Hertz start,
    the scales and the references, so it must be the ball's radius where the
    film forms.  A cap with fewer than 6 nodes there is too coarse to resolve
    the contact.
    """
    comm = msh.comm
    own = cap[cap < msh.geometry.index_map().size_local]
    X = msh.geometry.x[own]
    rho2 = X[:, 0] ** 2 + X[:, 1] ** 2
    near = rho2 <= a * a
    q, z = 0.5 * rho2[near], X[near, 2]
    sums = comm.allreduce(np.array([len(q), q.sum(), (q * q).sum(), z.sum(),
                                    (q * z).sum()]), op=MPI.SUM)
    n, sq, sqq, sz, sqz = sums
    det = n * sqq - sq * sq
    if n < 6 or not det > 0:
        raise InputError(f"the cap of {v['mesh_file']!r} has {int(n)} node(s) within the "
                         f"Hertz radius a = {a:.3g} mm of the contact point (needs >= 6)")
    k = (n * sqz - sq * sz) / det
    if not abs(k * v["R"] - 1) <= 0.05:
        raise InputError(f"the cap of {v['mesh_file']!r} has the radius of curvature "
                         f"{1 / k if k else math.inf:.4g} mm at the contact: R = "
                         f"{v['R']} mm must match it within 5 %")


def user_rim(film, v, a):
    """Return the nodes (k, 3) of the rim of a user's cap: ∂Γ_l less the edges on y = 0.

    Raises InputError if there is none, or if the cap does not reach 1.5 a(W)
    from the contact point (the least rim radius √(x² + y²)).
    """
    tol = 1e-9 * v["R"]
    rim = film_boundary(film, keep=lambda X: ~np.all(np.abs(X[:, :, 1]) < tol, axis=1))
    if not len(rim):
        raise InputError(f"the group 'lubricated' of {v['mesh_file']!r} has no rim off "
                         "the symmetry plane (p = 0 there)")
    r_cap = float(np.min(np.hypot(rim[:, 0], rim[:, 1])))
    if r_cap < 1.5 * a:
        raise InputError(f"the cap of {v['mesh_file']!r} reaches r = {r_cap:.3g} mm < "
                         f"1.5 a = {1.5 * a:.3g} mm (Hertz a at W = {v['W']} N)")
    return rim
