"""NumPy twin of the C++ lubrication-surface projection (``cpp_kernels/src/lubrication.hpp``).

:func:`lubrication_projection_ref` has the signature and result of
:func:`tribofx.lubrication_projection.lubrication_projection`: the closest point
comes from :func:`tribofx.projection_ref.closest_point_projection_ref`, the film
data are computed with the same formulas as the C++ kernel, vectorised over points.
For testing only (brute-force facet search).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from tribofx.facet_elements_ref import ELEMENTS, QUAD_AB, line1, line2
from tribofx.lubrication_projection import LubricationResult
from tribofx.projection import _validate
from tribofx.projection_ref import _evaluate, closest_point_projection_ref

if TYPE_CHECKING:
    from tribofx.facet_elements_ref import FacetElement

__all__ = ["lubrication_projection_ref"]


def _third_derivatives(el: FacetElement, X: np.ndarray, xi: np.ndarray) -> np.ndarray:
    """x_,abc (m, tdim, tdim, tdim, g) of the facet map.

    Zero for intervals and triangles (at most quadratic); a tensor-product
    quadrilateral is at most quadratic in each coordinate, so only the mixed
    x_,001 (and its permutations) and x_,011 remain — nonzero for quadrilateral9.
    """
    m, nn, gdim = X.shape
    d3 = np.zeros((m, el.tdim, el.tdim, el.tdim, gdim))
    if el.simplex:
        return d3
    line = line2 if nn == 9 else line1
    f, df, d2f = line(xi[:, 0])
    g, dg, d2g = line(xi[:, 1])
    x001 = sum((d2f[a] * dg[b])[:, None] * X[:, i] for i, (a, b) in enumerate(QUAD_AB[:nn]))
    x011 = sum((df[a] * d2g[b])[:, None] * X[:, i] for i, (a, b) in enumerate(QUAD_AB[:nn]))
    for a, b, c in ((0, 0, 1), (0, 1, 0), (1, 0, 0)):
        d3[:, a, b, c] = x001
    for a, b, c in ((0, 1, 1), (1, 0, 1), (1, 1, 0)):
        d3[:, a, b, c] = x011
    return d3


def _second_derivative(el: FacetElement, x: np.ndarray, X: np.ndarray,
                       xi: np.ndarray) -> np.ndarray:
    """d2y_i/dx_j dx_k (m, g, g, g) of interior projections."""
    xs, t, d = _evaluate(el, X, xi)
    d3 = _third_derivatives(el, X, xi)
    g = x - xs
    gdim = x.shape[1]
    A = np.einsum("mai,mbi->mab", t, t) - np.einsum("mi,mabi->mab", g, d)
    Ai = np.linalg.inv(A)
    Xi = np.einsum("mab,mbj->maj", Ai, t)
    dt = np.einsum("mben,mek->mbnk", d, Xi)
    dg = np.eye(gdim)[None] - np.einsum("men,mek->mnk", t, Xi)
    dA = (np.einsum("mbnk,mcn->mbck", dt, t) + np.einsum("mbn,mcnk->mbck", t, dt)
          - np.einsum("mnk,mbcn->mbck", dg, d)
          - np.einsum("mn,mbcen,mek->mbck", g, d3, Xi))
    dAi = -np.einsum("mac,mcek,meb->mabk", Ai, dA, Ai)
    dXi = np.einsum("mabk,mbj->majk", dAi, t) + np.einsum("mab,mbjk->majk", Ai, dt)
    return np.einsum("maik,maj->mijk", dt, Xi) + np.einsum("mai,majk->mijk", t, dXi)


def lubrication_projection_ref(
    points: npt.ArrayLike, nodes: npt.ArrayLike, facets: npt.ArrayLike, cell_type: str
) -> LubricationResult:
    """NumPy version of :func:`tribofx.lubrication_projection.lubrication_projection`."""
    points, nodes, facets = _validate(points, nodes, facets, cell_type)
    el = ELEMENTS[cell_type]
    n, gdim = points.shape
    pr = closest_point_projection_ref(points, nodes, facets, cell_type)
    g = points - pr.x_bar
    dh = (pr.normal + np.einsum("pi,pij->pj", g, pr.dn_dx)
          - np.einsum("pi,pij->pj", pr.normal, pr.dxbar_dx))
    d2y = np.zeros((n, gdim, gdim, gdim))
    d2y[pr.facet < 0] = np.nan
    ins = pr.inside & (pr.facet >= 0)
    if ins.any():
        X = nodes[facets[pr.facet[ins]]]
        d2y[ins] = _second_derivative(el, points[ins], X, pr.xi[ins])
    return LubricationResult(
        facet=pr.facet, xi=pr.xi, y=pr.x_bar, nu=pr.normal, h=pr.gap, dy_dx=pr.dxbar_dx,
        dnu_dx=pr.dn_dx, dh_dx=dh, d2h_dx2=pr.dn_dx.copy(), d2y_dx2=d2y, inside=pr.inside,
        distance=pr.distance)
