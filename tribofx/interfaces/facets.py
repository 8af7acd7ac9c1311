"""Geometry of oriented P1 contact facets (segments in 2D, triangles in 3D), in NumPy.

The conventions of the C++ two-body kernels (:mod:`tribofx.two_body`): a facet
is given by its d vertices (n, d, d); its outward unit normal is (τ_y, −τ_x)/l
in 2D and t₁ × t₂/|t₁ × t₂| in 3D; a point of it is Σ N_i(ξ) x_i with the P1
shape functions N = (1 − Σ ξ^a, ξ^1, ...).
"""

import numpy as np

__all__ = ["normals", "plane_coordinates", "shape_values"]


def shape_values(xi):
    """P1 facet shape functions at ξ: (n,) in 2D → (n, 2); (n, 2) in 3D → (n, 3)."""
    xi = np.asarray(xi)
    xi = xi.reshape(len(xi), 1 if xi.ndim == 1 else xi.shape[1])
    return np.c_[1 - xi.sum(axis=1), xi]


def plane_coordinates(x, facet):
    """Coordinates of points x (n, d) on their facets (n, d, d vertices), unclamped.

    Returns ξ (n, d − 1) of the projection onto the facet's line/plane, the
    distance to that line/plane (n,) and a facet size (n,): the length in 2D,
    the square root of twice the area in 3D.
    """
    a = facet[:, 0]
    t = facet[:, 1:] - a[:, None, :]                       # (n, d-1, d) edge vectors
    m = np.einsum("nad,nbd->nab", t, t)
    rhs = np.einsum("nad,nd->na", t, x - a)
    xi = np.linalg.solve(m, rhs[..., None])[..., 0]
    foot = a + np.einsum("na,nad->nd", xi, t)
    if t.shape[1] == 1:
        size = np.sqrt(m[:, 0, 0])                        # the segment's length
    else:
        size = np.abs(np.linalg.det(m)) ** 0.25           # √(2 area): det m = (2 area)²
    return xi, np.linalg.norm(x - foot, axis=1), size


def normals(facet):
    """Return the unit outward normals (n, d) of oriented facets (n, d, d), as the kernels."""
    if facet.shape[1] == 2:
        t = facet[:, 1] - facet[:, 0]
        n = np.c_[t[:, 1], -t[:, 0]]
    else:
        n = np.cross(facet[:, 1] - facet[:, 0], facet[:, 2] - facet[:, 0])
    return n / np.linalg.norm(n, axis=1)[:, None]
