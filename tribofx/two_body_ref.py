"""NumPy twin of the two-body contact kernels (:mod:`tribofx.two_body`), for the tests.

The search is brute force over all segments (the C++ kernel uses a box tree);
the residual is the same law written in NumPy, and the tangent is computed by
complex-step differentiation, J[:, k] = Im r(q + i h e_k)/h, exact to round-off
for a real-analytic branch and independent of the kernel's dual numbers.
"""

import numpy as np

__all__ = ["node_residual", "node_residuals", "project"]


def project(nodes, segments, points):
    """Nearest segment of each point: dict of ``facet``, clamped ``xi``, ``distance``."""
    a, b = nodes[segments[:, 0]], nodes[segments[:, 1]]
    t = b - a
    l2 = np.sum(t * t, axis=1)
    out = {"facet": [], "xi": [], "distance": []}
    for x in np.asarray(points, float):
        xi = np.clip(np.sum((x - a) * t, axis=1) / l2, 0.0, 1.0)
        d = np.linalg.norm(x - a - xi[:, None] * t, axis=1)
        s = int(np.argmin(d))          # first minimum: the lowest index on ties
        out["facet"].append(s)
        out["xi"].append(xi[s])
        out["distance"].append(d[s])
    return {"facet": np.array(out["facet"], np.int32), "xi": np.array(out["xi"]),
            "distance": np.array(out["distance"])}


def node_residual(q, xi_old, w, w_c, rho_n, rho_t, mu):
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
    T_t = np.zeros(2, dtype=q.dtype)
    if mu > 0:
        s = xb - (c + xi_old * (e - c))
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


def node_residuals(q, xi_old, w, w_c, rho_n, rho_t=None, mu=0.0, h=1e-30):
    """Residuals (n, 13) and complex-step tangents (n, 13, 13), as the C++ kernel."""
    rho_t = rho_n if rho_t is None else rho_t
    q = np.asarray(q, float).reshape(-1, 13)
    r = np.zeros_like(q)
    J = np.zeros((len(q), 13, 13))
    for i, qi in enumerate(q):
        args = (xi_old[i], w[i], w_c[i], rho_n, rho_t, mu)
        r[i] = node_residual(qi.astype(complex), *args).real
        for k in range(13):
            qc = qi.astype(complex)
            qc[k] += 1j * h
            J[i, :, k] = node_residual(qc, *args).imag / h
    return r, J
