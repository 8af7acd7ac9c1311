"""Nodal profiles: sub-element positions of extremes, node-to-node oscillation.

A P1 field takes its extreme at a node, so the *value* reported is the nodal one
(the discrete solution's own maximum); the *position* of the extreme of the
underlying smooth field lies between nodes.  It is estimated by the vertex of the
parabola through the extreme node and its two neighbours (non-uniform spacing):
for a smooth f with f'' ≠ 0 the error is O(h²) (|Δx| ≤ h² max|f'''| / (3|f''|)
plus the nodal error ε of f shifted by ≲ 2ε/(|f''| h)), against O(h) for the node.

On a surface (a film map f(x, y) at scattered nodes) the same idea takes the
vertex of the quadratic f ≈ c₀ + g·ξ + ½ ξᵀHξ fitted by least squares to the
extreme node's ``k`` nearest nodes (:func:`paraboloid_vertex`): exact for a
quadratic field, O(h²) for a smooth one with a definite Hessian.

A film under-resolved by the mesh zig-zags from node to node (the discrete
solution of the Reynolds–elasticity coupling, not a solver failure): the
second difference of the nodal profile, :func:`oscillation_indicator`, measures
it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["oscillation_indicator", "parabolic_vertex", "paraboloid_vertex"]


def parabolic_vertex(x: npt.ArrayLike, f: npt.ArrayLike, kind: str = "max") -> float:
    """Position of the extreme of the nodal profile f at positions x (sorted here).

    Returns the vertex of the parabola through the extreme node i and nodes
    i ± 1, clamped to [x_{i−1}, x_{i+1}]; the node itself when it is an end node
    or the three values are not convex/concave in the sense of ``kind``
    ("max" or "min").
    """
    x, f = np.asarray(x, dtype=float), np.asarray(f, dtype=float)
    order = np.argsort(x, kind="stable")
    x, f = x[order], f[order]
    if kind not in ("max", "min"):
        raise ValueError(f"unknown kind {kind!r}")
    s = 1.0 if kind == "max" else -1.0
    i = int(np.argmax(s * f))
    if i == 0 or i == len(x) - 1:
        return float(x[i])
    x0, x1, x2 = x[i - 1:i + 2]
    f0, f1, f2 = s * f[i - 1:i + 2]
    d01, d12 = (f1 - f0) / (x1 - x0), (f2 - f1) / (x2 - x1)
    c = (d12 - d01) / (x2 - x0)          # half the second derivative of the parabola
    if c >= 0:                           # not a strict maximum of s·f
        return float(x1)
    # Newton form f ≈ f0 + d01 (ξ − x0) + c (ξ − x0)(ξ − x1): f'(ξ) = d01 + c (2ξ − x0 − x1)
    xv = 0.5 * (x0 + x1) - d01 / (2 * c)
    return float(np.clip(xv, x0, x2))


def paraboloid_vertex(xy: npt.ArrayLike, f: npt.ArrayLike, kind: str = "min",
                      k: int = 12) -> tuple[float, ...]:
    """Position (x, y) of the extreme of a field f given at scattered surface points xy.

    Fits f ≈ c₀ + g·ξ + ½ ξᵀHξ (ξ = x − x_i, six coefficients) by least squares
    to the ``k`` nodes nearest the extreme node i (i included) and returns the
    stationary point −H⁻¹g, kept within the fitted patch (the disc of its
    farthest node); the node itself when the patch has fewer than six nodes,
    the fit is rank deficient or H is not definite in the sense of ``kind``
    ("min": positive definite, "max": negative definite).
    """
    xy, f = np.asarray(xy, dtype=float)[:, :2], np.asarray(f, dtype=float)
    if kind not in ("max", "min"):
        raise ValueError(f"unknown kind {kind!r}")
    s = 1.0 if kind == "min" else -1.0
    i = int(np.argmin(s * f))
    d = np.linalg.norm(xy - xy[i], axis=1)
    near = np.argsort(d, kind="stable")[:k]
    if len(near) < 6:
        return tuple(float(c) for c in xy[i])
    xi = xy[near] - xy[i]
    A = np.column_stack([np.ones(len(near)), xi[:, 0], xi[:, 1], 0.5 * xi[:, 0] ** 2,
                         xi[:, 0] * xi[:, 1], 0.5 * xi[:, 1] ** 2])
    c, _, rank, _ = np.linalg.lstsq(A, s * f[near], rcond=None)
    H = np.array([[c[3], c[4]], [c[4], c[5]]])
    if rank < 6 or np.any(np.linalg.eigvalsh(H) <= 0):
        return tuple(float(v) for v in xy[i])
    step = -np.linalg.solve(H, c[1:3])
    r = float(d[near].max())
    if np.linalg.norm(step) > r:
        step *= r / np.linalg.norm(step)
    return tuple(float(v) for v in xy[i] + step)


def oscillation_indicator(h: npt.ArrayLike, p: npt.ArrayLike, threshold: float) -> float:
    """Zig-zag amplitude of a film profile in its loaded zone p > threshold.

    ``h``, ``p``: nodal film thickness and pressure along a line, sorted by
    position.  Returns mean |h_{i+1} − 2h_i + h_{i−1}| / (4 mean h) over the
    nodes of the zone: a nodal zig-zag ±δ h̄ gives δ (exactly on an even
    number of nodes; δ/(1 ± δ/n) on an odd number n), a smooth film
    O((Δx)² |h''| / h̄), which vanishes with refinement.
    """
    hz = np.asarray(h, dtype=float)[np.asarray(p) > threshold]
    if len(hz) < 3:
        return 0.0
    return float(np.mean(np.abs(np.diff(hz, 2))) / (4 * np.mean(hz)))
