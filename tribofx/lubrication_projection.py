"""Lubrication-surface projection y = P(x) onto a meshed countersurface (C++ kernel).

The work is done by :func:`tribofx._cpp.lubrication_projection`, a serial kernel
(one call per MPI rank with its own points, GIL released) built on the
closest-point projection of :mod:`tribofx.projection`.
:mod:`tribofx.lubrication_projection_ref` is a NumPy twin running the identical
algorithm, used for testing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from tribofx.projection import CELL_TYPES, _validate

__all__ = ["CELL_TYPES", "LubricationResult", "lubrication_projection"]


@dataclass(frozen=True)
class LubricationResult:
    """Lubrication projection of ``n`` points; see :func:`lubrication_projection`."""

    facet: npt.NDArray[np.int32]
    xi: npt.NDArray[np.float64]
    y: npt.NDArray[np.float64]
    nu: npt.NDArray[np.float64]
    h: npt.NDArray[np.float64]
    dy_dx: npt.NDArray[np.float64]
    dnu_dx: npt.NDArray[np.float64]
    dh_dx: npt.NDArray[np.float64]
    d2h_dx2: npt.NDArray[np.float64]
    d2y_dx2: npt.NDArray[np.float64]
    inside: npt.NDArray[np.bool_]
    distance: npt.NDArray[np.float64]


def lubrication_projection(
    points: npt.ArrayLike, nodes: npt.ArrayLike, facets: npt.ArrayLike, cell_type: str
) -> LubricationResult:
    """Project points of the lubricated boundary onto a meshed countersurface.

    For each point ``x`` (quadrature or nodal point of Γ_l, current position)
    the closest point ``y = P(x)`` on the surface mesh is found by
    :func:`tribofx.projection.closest_point_projection` (same search, same
    Newton, same tie-breaking), and the film data of the lubrication surface
    are derived from it (mm throughout):

    * ``h = (x − y)·ν`` with ``ν`` the facet normal at ``y``; 2D
      ``(t_y, −t_x)/|t|``, 3D ``t_0 × t_1/|t_0 × t_1|``. The facets must be
      oriented so that ``ν`` points from the countersurface into the film.
    * ``∂h/∂x_j = ν_j + g_i ∂ν_i/∂x_j − ν_i ∂y_i/∂x_j`` with ``g = x − y``
      (``= ν`` for an interior projection);
    * ``∂²h/∂x² = ∂ν/∂x`` (exact for interior and vertex projections; for a
      projection on an edge of a 2D facet it omits the edge terms);
    * ``∂²y_i/∂x_j∂x_k`` from differentiating ``∂y/∂x = t_a Ξ_a``,
      ``Ξ = A⁻¹ t``, ``A_ab = t_a·t_b − g·x_,ab`` once more. Third derivatives
      of the facet map are neglected: exact for ``interval``, ``interval3``,
      ``triangle``, ``triangle6``, ``quadrilateral``, not for
      ``quadrilateral9``. Zero for projections that are not interior.

    Args:
        points: ``(n, gdim)`` float64 point coordinates.
        nodes: ``(nv, gdim)`` float64 surface-mesh node coordinates.
        facets: ``(nf, k)`` int32 connectivity, node ordering as in
            :func:`tribofx.projection.closest_point_projection`.
        cell_type: One of :data:`CELL_TYPES`.

    Returns:
        LubricationResult with C-contiguous arrays, ``tdim = gdim − 1``, last
        axes packed row-major in the index order given:

        * ``facet`` ``(n,)`` int32: facet of the projection (−1: none).
        * ``xi`` ``(n, tdim)``: reference coordinates of ``y`` on the facet.
        * ``y`` ``(n, gdim)``: projection point ``P(x)``.
        * ``nu`` ``(n, gdim)``: unit normal ``ν(y)``.
        * ``h`` ``(n,)``: film thickness ``(x − y)·ν``.
        * ``dy_dx`` ``(n, gdim, gdim)``: ``[p, i, j] = ∂y_i/∂x_j`` (``∂P/∂x``).
        * ``dnu_dx`` ``(n, gdim, gdim)``: ``[p, i, j] = ∂ν_i/∂x_j``.
        * ``dh_dx`` ``(n, gdim)``: ``[p, j] = ∂h/∂x_j``.
        * ``d2h_dx2`` ``(n, gdim, gdim)``: ``[p, i, j] = ∂²h/∂x_i∂x_j``.
        * ``d2y_dx2`` ``(n, gdim, gdim, gdim)``: ``[p, i, j, k] = ∂²y_i/∂x_j∂x_k``.
        * ``inside`` ``(n,)`` bool: ``y`` interior to its facet.
        * ``distance`` ``(n,)``: ``|x − y|``.

    Raises:
        ValueError: if shapes, dtypes, ``cell_type`` or node indices are
            inconsistent.

    """
    from tribofx import _cpp

    points, nodes, facets = _validate(points, nodes, facets, cell_type)
    return LubricationResult(**_cpp.lubrication_projection(points, nodes, facets, cell_type))
