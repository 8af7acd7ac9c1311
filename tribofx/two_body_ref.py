"""NumPy twin of the two-body contact kernels (:mod:`tribofx.two_body`), for the tests.

The search is brute force over all segments (the C++ kernel uses a box tree);
the residual is the same law written in NumPy, and the tangent is computed by
complex-step differentiation, J[:, k] = Im r(q + i h e_k)/h, exact to round-off
for a real-analytic branch and independent of the kernel's dual numbers.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, cast

import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

    #: a real node's unknowns, or complex ones (the complex-step tangent)
    Local = npt.NDArray[np.float64 | np.complex128]

__all__ = ["node_residual", "node_residual_3d", "node_residuals", "project", "project_3d"]


def project(nodes: npt.NDArray[np.float64], segments: npt.NDArray[np.int32],
            points: npt.ArrayLike) -> dict[str, np.ndarray]:
    """Nearest segment of each point: dict of ``facet``, clamped ``xi``, ``distance``."""
    a, b = nodes[segments[:, 0]], nodes[segments[:, 1]]
    t = b - a
    l2 = np.sum(t * t, axis=1)
    out: dict[str, list[Any]] = {"facet": [], "xi": [], "distance": []}
    for x in np.asarray(points, float):
        xi = np.clip(np.sum((x - a) * t, axis=1) / l2, 0.0, 1.0)
        d = np.linalg.norm(x - a - xi[:, None] * t, axis=1)
        s = int(np.argmin(d))          # first minimum: the lowest index on ties
        out["facet"].append(s)
        out["xi"].append(xi[s])
        out["distance"].append(d[s])
    return {"facet": np.array(out["facet"], np.int32), "xi": np.array(out["xi"]),
            "distance": np.array(out["distance"])}


def _closest_on_triangle(x: npt.NDArray[np.float64], a: npt.NDArray[np.float64],
                         b: npt.NDArray[np.float64],
                         c: npt.NDArray[np.float64]) -> tuple[float, float, float]:
    """Nearest point of x on triangle (a, b, c) as (distance, ξ¹, ξ²).

    The plane projection if inside, else the nearest of the three clamped edge points.
    """
    t1, t2 = b - a, c - a
    m = np.array([[t1 @ t1, t1 @ t2], [t1 @ t2, t2 @ t2]])
    xi = np.linalg.solve(m, [(x - a) @ t1, (x - a) @ t2])
    if xi[0] >= 0 and xi[1] >= 0 and xi.sum() <= 1:
        return np.linalg.norm(x - a - xi[0] * t1 - xi[1] * t2), xi[0], xi[1]
    best = None
    for p, q, to_xi in ((a, b, lambda s: (s, 0.0)), (a, c, lambda s: (0.0, s)),
                        (b, c, lambda s: (1 - s, s))):
        e = q - p
        s = float(np.clip((x - p) @ e / (e @ e), 0.0, 1.0))
        d = np.linalg.norm(x - p - s * e)
        if best is None or d < best[0]:
            best = (d, *to_xi(s))
    return cast("tuple[float, float, float]", best)   # set at the first edge


def project_3d(nodes: npt.NDArray[np.float64], triangles: npt.NDArray[np.int32],
               points: npt.ArrayLike) -> dict[str, np.ndarray]:
    """Nearest triangle of each point: dict of ``facet``, ``xi`` (n, 2), ``distance``."""
    out: dict[str, list[Any]] = {"facet": [], "xi": [], "distance": []}
    for x in np.asarray(points, float):
        cand = [_closest_on_triangle(x, *nodes[t]) for t in triangles]
        d = np.array([c[0] for c in cand])
        k = int(np.argmin(d))
        out["facet"].append(k)
        out["xi"].append(cand[k][1:])
        out["distance"].append(d[k])
    return {"facet": np.array(out["facet"], np.int32), "xi": np.array(out["xi"]),
            "distance": np.array(out["distance"])}


def node_residual_3d(q: Local, xi_old: npt.NDArray[np.float64], w: float, w_c: float,
                     rho_n: float, rho_t: float, mu: float, eulerian: bool = False) -> Local:
    """Residual (25,) of one 3D slave node; q may be complex (complex-step tangent)."""
    x, a, b, c = q[0:3], q[3:6], q[6:9], q[9:12]
    ya, yb, yc = q[12:15], q[15:18], q[18:21]
    lam_n, lam_t = q[21], q[22:25]
    t1, t2 = b - a, c - a
    m = np.array([[t1 @ t1, t1 @ t2], [t1 @ t2, t2 @ t2]])
    minv = np.array([[m[1, 1], -m[0, 1]], [-m[0, 1], m[0, 0]]]) / (m[0, 0] * m[1, 1]
                                                                    - m[0, 1] ** 2)
    nr = np.array([t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2],
                   t1[0] * t2[1] - t1[1] * t2[0]])
    n = nr / np.sqrt(nr @ nr)
    xi = minv @ np.array([(x - a) @ t1, (x - a) @ t2])
    xb = a + xi[0] * t1 + xi[1] * t2
    g = (x - xb) @ n
    lhat = lam_n + rho_n * g
    T_n = lhat if lhat.real < 0 else 0.0 * lhat
    T_t = np.zeros(3, dtype=q.dtype)
    if mu > 0:
        s = (xi_old[0] * t1 + xi_old[1] * t2 if eulerian
             else xb - (ya + xi_old[0] * (yb - ya) + xi_old[1] * (yc - ya)))
        h = (lam_t - (lam_t @ n) * n) + rho_t * (s - (s @ n) * n)
        radius = -mu * T_n
        norm = np.sqrt(h @ h + 1e-24)
        T_t = h if norm.real < radius.real else radius / norm * h
    f = minv @ np.array([T_t @ t1, T_t @ t2])
    F = T_n * n + f[0] * t1 + f[1] * t2
    r = np.zeros(25, dtype=q.dtype)
    r[0:3] = w * F
    r[3:6] = w * (-(1 - xi[0] - xi[1]) * F - g * n * (f[0] + f[1]))
    r[6:9] = w * (-xi[0] * F + g * n * f[0])
    r[9:12] = w * (-xi[1] * F + g * n * f[1])
    r[21] = w_c / rho_n * T_n
    if mu > 0:
        r[22:25] = w_c / rho_t * T_t
    return r


def node_residual(q: Local, xi_old: float, w: float, w_c: float, rho_n: float, rho_t: float,
                  mu: float, eulerian: bool = False) -> Local:
    """Residual (13,) of one slave node; q may be complex (complex-step tangent)."""
    x, a, b, c, e = q[0:2], q[2:4], q[4:6], q[6:8], q[8:10]
    lam_n, lam_t = q[10], q[11:13]
    t = b - a
    l2 = t @ t
    n = np.array([t[1], -t[0]]) / np.sqrt(l2)
    xi = (x - a) @ t / l2
    xb = a + xi * t
    g = (x - xb) @ n
    lhat = lam_n + rho_n * g
    T_n = lhat if lhat.real < 0 else 0.0 * lhat
    T_t: np.ndarray = np.zeros(2, dtype=q.dtype)
    if mu > 0:
        s = xi_old * t if eulerian else xb - (c + xi_old * (e - c))
        h = (lam_t - (lam_t @ n) * n) + rho_t * (s - (s @ n) * n)
        radius = -mu * T_n
        norm = np.sqrt(h @ h + 1e-24)
        T_t = h if norm.real < radius.real else radius / norm * h
    f = (T_t @ t) / l2
    r = np.zeros(13, dtype=q.dtype)
    r[0:2] = w * (T_n * n + f * t)
    r[2:4] = w * (-T_n * (1 - xi) * n + f * ((xi - 1) * t - g * n))
    r[4:6] = w * (-T_n * xi * n + f * (g * n - xi * t))
    r[10] = w_c / rho_n * T_n
    if mu > 0:
        r[11:13] = w_c / rho_t * T_t
    return r


def node_residuals(q: npt.ArrayLike, xi_old: npt.NDArray[np.float64],
                   w: npt.NDArray[np.float64], w_c: npt.NDArray[np.float64], rho_n: float,
                   rho_t: float | None = None, mu: float = 0.0, eulerian: bool = False,
                   h: float = 1e-30) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Residuals (n, L) and complex-step tangents (n, L, L), as the C++ kernel (L = 13 or 25)."""
    rho_t = rho_n if rho_t is None else rho_t
    q = np.asarray(q, float)
    L = q.shape[-1]
    q = q.reshape(-1, L)
    one = node_residual_3d if L == 25 else node_residual
    r = np.zeros_like(q)
    J = np.zeros((len(q), L, L))
    for i, qi in enumerate(q):
        args = (xi_old[i], w[i], w_c[i], rho_n, rho_t, mu, eulerian)
        r[i] = one(qi.astype(complex), *args).real
        for k in range(L):
            qc = qi.astype(complex)
            qc[k] += 1j * h
            J[i, :, k] = one(qc, *args).imag / h
    return r, J
