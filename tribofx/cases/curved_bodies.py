"""Curved bodies of the Hertz-type cases: their ``dim``, and a user's body (``mesh_file``).

* ``dim``: 2 (a plane-strain cylinder), 3 (a sphere, quarter model) or
  ``axisymmetric`` (a sphere by its meridian section): :func:`dimension` parses
  it, :func:`geometric_dim` gives the mesh's dimension and :func:`hertz_dim` the
  Hertz reference's (``hertz``, ``ehl-squeeze``).
* :func:`read_hertz_body` serves ``hertz`` and ``two-cylinders``: the body is moved
  onto its symmetry planes and its first-contact point, and its curvature there
  is checked against the Hertz reference's within :data:`CURVATURE_TOL`.
"""


from __future__ import annotations

import math
from typing import TYPE_CHECKING, cast

import numpy as np
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..meshes.user import boundary_facet_size, read_user_mesh
from ..params import InputError

if TYPE_CHECKING:
    import numpy.typing as npt

# hertz_reference is re-exported from tribofx.references

__all__ = ["AXISYMMETRIC", "CURVATURE_TOL", "body_kind", "dimension", "geometric_dim",
           "hertz_dim", "read_hertz_body"]


#: the ``dim`` of a sphere modelled by its meridian section (an axisymmetric body)
AXISYMMETRIC = "axisymmetric"


def dimension(text: str) -> int | str:
    """Parse ``dim``: 2, 3 or "axisymmetric" (ValueError otherwise)."""
    text = str(text).strip()
    return AXISYMMETRIC if text == AXISYMMETRIC else int(text)


def geometric_dim(dim: int | str) -> int:
    """Dimension of the mesh: 2 for the cylinder and the meridian section, else 3."""
    return 2 if dim == AXISYMMETRIC else cast("int", dim)


def hertz_dim(dim: int | str) -> int:
    """Dimension of the Hertz reference: 2 (line contact, the cylinder) or 3 (a sphere)."""
    return 3 if dim == AXISYMMETRIC else cast("int", dim)


def body_kind(dim: int | str) -> str:
    """Return the :class:`tribofx.body.Body` kind of ``dim``: plane strain, 3D or axisymmetric."""
    return {2: "plane_strain", 3: "3d", AXISYMMETRIC: "axisymmetric"}[dim]


#: relative tolerance on the curvature of a user's body at its first-contact point
#: (of 1/R*, the composite curvature of the Hertz reference): ±5 % moves the Hertz
#: size a ∝ R*^½ (line) or R*^⅓ (point) by at most 2.5 %
CURVATURE_TOL = 0.05


def _gmin(comm: MPI.Comm, a: npt.NDArray[np.float64]) -> float:
    return comm.allreduce(float(np.min(a, initial=np.inf)), op=MPI.MIN)


def _gmax(comm: MPI.Comm, a: npt.NDArray[np.float64]) -> float:
    return comm.allreduce(float(np.max(a, initial=-np.inf)), op=MPI.MAX)


def read_hertz_body(
    path: str, comm: MPI.Comm, dim: int, a: float, radius: float, tol: float, name: str = "R",
    below: bool = False,
) -> tuple[dmesh.Mesh, dmesh.MeshTags, dict[str, int], float, float]:
    """Read a user's symmetry-reduced Hertz body, place it and check its curvature.

    The mesh (:func:`tribofx.meshes.user.read_user_mesh`, groups contact, loaded,
    symmetry_x and in 3D symmetry_y) is translated so that symmetry_x lies on
    x = 0 (symmetry_y on y = 0) and the first-contact point — the lowest node of
    ``contact`` (``below``: the highest, a body under the contact plane) — on
    the plane of the last coordinate = 0.  One-line :class:`InputError` if a
    symmetry group is not a plane (spread above 1e-6 of the body's size), the
    body is not on its positive side, or the curvature κ of ``contact`` at the
    first-contact point differs from 1/``radius`` (0: a flat) by more than
    ``tol`` (1/mm).

    κ is the least-squares fit of the circle (sphere) tangent to the plane at
    the origin, centred on the symmetry axis, r² + z² = 2z/κ (r the distance
    from the axis, z the height above the plane), to the owned contact nodes
    within r ≤ 2a of the axis (at least the 4 in 2D / 8 in 3D nearest nodes):
    κ = Σ 2z q / Σ q², q = r² + z², exact for nodes on a circle or a plane, and
    the local curvature of another profile.

    Returns ``(mesh, facet_tags, names, h, R_mesh)``: h the mean longest edge of
    the contact facets whose midpoint is within 1.5a of the first-contact point
    (the refined zone of the case's own mesh, or the nearest facets if none is;
    :func:`tribofx.meshes.user.boundary_facet_size`) — the element size gmsh
    aims at, as ``h_fine`` of the built mesh (the mean over the whole group
    would be dominated by the coarse far facets of a graded mesh); R_mesh = 1/κ
    (inf for κ ≤ 0).
    """
    required = ("contact", "loaded", "symmetry_x") + (("symmetry_y",) if dim == 3 else ())
    # (without ``cells``: the mesh, its facet tags and their names)
    msh, ft, names = cast("tuple[dmesh.Mesh, dmesh.MeshTags, dict[str, int]]",
                          read_user_mesh(path, comm, dim, required))
    fdim, v = dim - 1, dim - 1
    x = msh.geometry.x

    def nodes(group: str) -> npt.NDArray[np.int32]:
        return np.unique(dmesh.entities_to_geometry(msh, fdim, ft.find(names[group]),
                                                    False).ravel())

    size = max(_gmax(comm, x[:, k]) - _gmin(comm, x[:, k]) for k in range(dim))
    for k, group in enumerate(required[2:]):
        axis = "xy"[k]
        c = x[nodes(group), k]
        lo, hi = _gmin(comm, c), _gmax(comm, c)
        if hi - lo > 1e-6 * size:
            raise InputError(f"physical group {group!r} in {path!r} is not a plane {axis} = "
                             f"const ({axis} from {lo:.6g} to {hi:.6g} mm)")
        x[:, k] -= lo
        if _gmin(comm, x[:, k]) < -1e-6 * size:
            raise InputError(f"the body in {path!r} must lie on the side {axis} >= 0 of its "
                             f"plane {group!r}")
    s = -1.0 if below else 1.0
    contact = nodes("contact")
    x[:, v] -= _gmax(comm, x[contact, v]) if below else _gmin(comm, x[contact, v])
    # curvature at the first-contact point, from the owned contact nodes
    own = contact[contact < msh.geometry.index_map().size_local]
    r = np.concatenate(comm.allgather(np.linalg.norm(x[own, :v], axis=1)))
    z = np.concatenate(comm.allgather(s * x[own, v]))
    order = np.argsort(r, kind="stable")
    n = max(int(np.sum(r <= 2 * a)), 4 if dim == 2 else 8)
    q = r[order[:n]] ** 2 + z[order[:n]] ** 2
    kappa = float(np.sum(2 * z[order[:n]] * q) / np.sum(q * q))
    expected = 1.0 / radius if 0 < radius < math.inf else 0.0
    if not abs(kappa - expected) <= tol:
        got = f"radius {1 / kappa:.4g} mm" if kappa > 0 else f"curvature {kappa:.3g} 1/mm"
        want = f"{name} = {radius:g} mm" if expected else f"{name} = {radius:g} (a flat)"
        raise InputError(f"'contact' in {path!r} has the {got} at its first-contact point "
                         f"(its {'highest' if below else 'lowest'} node, moved to the "
                         f"origin), but {want}")
    # element size of the contact zone (midpoints within 1.5a of the first-contact point)
    h = boundary_facet_size(msh, ft, names["contact"], near=(np.zeros(dim), 1.5 * a))
    return msh, ft, names, h, (1 / kappa if kappa > 0 else math.inf)
