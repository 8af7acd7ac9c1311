"""Sub-element positions of extremes and zero crossings of nodal profiles.

A P1 field takes its extreme at a node, so the *value* reported is the nodal one
(the discrete solution's own maximum); the *position* of the extreme of the
underlying smooth field lies between nodes.  It is estimated by the vertex of the
parabola through the extreme node and its two neighbours (non-uniform spacing):
for a smooth f with f'' ≠ 0 the error is O(h²) (|Δx| ≤ h² max|f'''| / (3|f''|)
plus the nodal error ε of f shifted by ≲ 2ε/(|f''| h)), against O(h) for the node.
"""

import numpy as np

__all__ = ["parabolic_vertex"]


def parabolic_vertex(x, f, kind="max"):
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
