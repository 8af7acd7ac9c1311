"""Closest-point projection of points onto a surface mesh (C++ kernel).

The work is done by :func:`tribofx._cpp.closest_point_projection`, a serial
kernel (one call per MPI rank with its own points) that releases the GIL.
:mod:`tribofx.projection_ref` is a plain NumPy twin running the identical
algorithm, used for testing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["CELL_TYPES", "ProjectionResult", "closest_point_projection"]

#: Supported facet types: name -> (geometric dimension, nodes per facet).
CELL_TYPES: dict[str, tuple[int, int]] = {
    "interval": (2, 2),
    "interval3": (2, 3),
    "triangle": (3, 3),
    "triangle6": (3, 6),
    "quadrilateral": (3, 4),
    "quadrilateral9": (3, 9),
}


@dataclass(frozen=True)
class ProjectionResult:
    """Closest-point projection of ``n`` points; see :func:`closest_point_projection`."""

    facet: npt.NDArray[np.int32]
    xi: npt.NDArray[np.float64]
    x_bar: npt.NDArray[np.float64]
    gap: npt.NDArray[np.float64]
    normal: npt.NDArray[np.float64]
    tangents: npt.NDArray[np.float64]
    dxi_dx: npt.NDArray[np.float64]
    dxbar_dx: npt.NDArray[np.float64]
    dn_dx: npt.NDArray[np.float64]
    curvature: npt.NDArray[np.float64]
    inside: npt.NDArray[np.bool_]
    distance: npt.NDArray[np.float64]


def _validate(
    points: npt.ArrayLike, nodes: npt.ArrayLike, facets: npt.ArrayLike, cell_type: str
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Check the inputs and return C-contiguous float64/float64/int32 copies.

    Raises:
        ValueError: with a one-line message if any input is inconsistent.

    """
    if not isinstance(cell_type, str) or cell_type not in CELL_TYPES:
        raise ValueError(f"unknown cell_type {cell_type!r}; expected one of {list(CELL_TYPES)}")
    gdim, k = CELL_TYPES[cell_type]
    try:
        points = np.ascontiguousarray(points, dtype=np.float64)
        nodes = np.ascontiguousarray(nodes, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise ValueError(f"points and nodes must be float arrays ({e})") from None
    facets = np.asarray(facets)
    if points.ndim != 2 or points.shape[1] != gdim:
        raise ValueError(f"points must have shape (n, {gdim}) for {cell_type}, got {points.shape}")
    if nodes.ndim != 2 or nodes.shape[1] != gdim or nodes.shape[0] == 0:
        raise ValueError(f"nodes must have shape (nv>0, {gdim}) for {cell_type}, got {nodes.shape}")
    if not np.issubdtype(facets.dtype, np.integer):
        raise ValueError(f"facets must be an integer array, got dtype {facets.dtype}")
    if facets.ndim != 2 or facets.shape[1] != k or facets.shape[0] == 0:
        raise ValueError(f"facets must have shape (nf>0, {k}) for {cell_type}, got {facets.shape}")
    if facets.min() < 0 or facets.max() >= nodes.shape[0]:
        raise ValueError(f"facet node indices must lie in [0, {nodes.shape[0]})")
    if nodes.shape[0] > np.iinfo(np.int32).max:
        raise ValueError("too many nodes for int32 facet indices")
    if not (np.isfinite(points).all() and np.isfinite(nodes).all()):
        raise ValueError("points and nodes must be finite")
    return points, nodes, np.ascontiguousarray(facets, dtype=np.int32)


def closest_point_projection(
    points: npt.ArrayLike, nodes: npt.ArrayLike, facets: npt.ArrayLike, cell_type: str
) -> ProjectionResult:
    """Project points onto the closest point of a surface mesh.

    For each point ``x`` the facet and local coordinates ``xi_bar`` minimising
    ``|x - x(xi)|`` over the surface are found, with ``x(xi)`` the Lagrange
    map of the facet. A bounding box tree over the facets (boxes of the
    Bernstein control points, which enclose curved facets exactly) is searched
    nearest-first with pruning. On each candidate facet:

    1. the interior problem is solved: closed form for affine facets,
       otherwise Newton with the Hessian ``A`` below (Gauss-Newton if ``A`` is
       not SPD), each iterate projected onto the reference facet, at most 50
       iterations, step tolerance 1e-14 (or a stalled step below 1e-8),
       abandoned after 3 consecutive iterates on the boundary; it is accepted
       if it converged strictly inside to a point with SPD ``A``;
    2. otherwise (or, for curved facets, if a vertex is closer than that
       interior minimum) the closest point on the edges of the reference facet
       is taken (closed form / clamped 1D Newton compared with the end points).

    Among facets whose distances tie with the minimum ``dmin``
    (``dmin >= d (1 - 1e-12) - 1e-300``) the lowest facet index wins.

    Args:
        points: ``(n, gdim)`` float64 point coordinates.
        nodes: ``(nv, gdim)`` float64 surface-mesh node coordinates.
        facets: ``(nf, k)`` int32 (int64 accepted, converted) facet-to-node
            connectivity in basix/DOLFINx node ordering:

            * ``"interval"`` (k=2, gdim=2): v0, v1; ``"interval3"`` (k=3):
              v0, v1, midpoint. Reference interval ``[0, 1]``.
            * ``"triangle"`` (k=3, gdim=3), ``"triangle6"`` (k=6): v0, v1, v2,
              then edge nodes of (v1, v2), (v0, v2), (v0, v1). Reference
              triangle with v0=(0,0), v1=(1,0), v2=(0,1).
            * ``"quadrilateral"`` (k=4, gdim=3): v0=(0,0), v1=(1,0), v2=(0,1),
              v3=(1,1); ``"quadrilateral9"`` (k=9): vertices, then edge nodes
              of (v0,v1), (v0,v2), (v1,v3), (v2,v3), then the centre node.
              Reference square ``[0, 1]^2``.
        cell_type: One of :data:`CELL_TYPES`.

    Returns:
        ProjectionResult with C-contiguous arrays, ``tdim = gdim - 1``, the
        last axes packed row-major as listed (index order ``[point, a, i]``):

        * ``facet`` ``(n,)`` int32: closest facet.
        * ``xi`` ``(n, tdim)`` float64: reference coordinates ``xi_bar``.
        * ``x_bar`` ``(n, gdim)``: projection point ``x(xi_bar)``.
        * ``gap`` ``(n,)``: signed gap ``(x - x_bar) . n``.
        * ``normal`` ``(n, gdim)``: unit normal; 2D ``(t_y, -t_x)/|t|``,
          3D ``t_0 x t_1 / |t_0 x t_1|`` (orientation is the caller's).
        * ``tangents`` ``(n, tdim, gdim)``: ``[p, a, i] = dx_i/dxi_a``.
        * ``dxi_dx`` ``(n, tdim, gdim)``: ``[p, a, j] = dxi_bar_a/dx_j``
          ``= (A^-1)_ab t_b,j`` with ``A_ab = t_a.t_b - (x - x_bar).x_,ab``.
          For a projection clamped to an edge of the reference facet only the
          edge direction is free (restricted problem); at a vertex it is zero.
        * ``dxbar_dx`` ``(n, gdim, gdim)``: ``[p, i, j] = t_a,i dxi_a/dx_j``.
        * ``dn_dx`` ``(n, gdim, gdim)``: ``[p, i, j] = dn_i/dxi_a dxi_a/dx_j``
          (zero for affine facets).
        * ``curvature`` ``(n, tdim, tdim)``: ``b_ab = n . x_,ab``.
        * ``inside`` ``(n,)`` bool: ``xi_bar`` is interior (not clamped).
        * ``distance`` ``(n,)``: ``|x - x_bar|``.

    Raises:
        ValueError: if shapes, dtypes, ``cell_type`` or node indices are
            inconsistent.

    """
    from tribofx import _cpp

    points, nodes, facets = _validate(points, nodes, facets, cell_type)
    out = _cpp.closest_point_projection(points, nodes, facets, cell_type)
    return ProjectionResult(**out)
