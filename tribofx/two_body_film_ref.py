"""NumPy twin of the two-body film kernel (:func:`tribofx.two_body.film_node_residuals`).

The same nodal coupling written in NumPy (``cpp_kernels/src/two_body_film.hpp``
has the equations), its tangent by complex-step differentiation,
J[:, k] = Im r(q + i h e_k)/h: exact to round-off and independent of the
kernel's dual numbers.  Used by the tests.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["film_node_residual", "film_node_residual_3d", "film_node_residuals"]


def film_node_residual(q: npt.NDArray[np.float64 | np.complex128],
                       data: npt.NDArray[np.float64], w: float, w_c: float, c_h: float,
                       c_w: float) -> npt.NDArray[np.float64 | np.complex128]:
    """Residual (11,) of one film node; q may be complex (complex-step tangent)."""
    x, a, b, t = q[0:2], q[2:4], q[4:6], q[9:11]     # q[6:9] (h, w): rows from UFL
    c1, c2, k0, z1, z2 = data[0], data[1], data[2], data[3:5], data[5:7]
    tau = b - a
    l2 = tau @ tau
    n = np.array([tau[1], -tau[0]]) / np.sqrt(l2)
    xi = (x - a) @ tau / l2
    g = (x - a - xi * tau) @ n
    v_m = ((1 - xi) * c1 + xi * c2) * tau + (1 - xi) * (k0 * a + z1) + xi * (k0 * b + z2)
    r = np.zeros(11, dtype=q.dtype)
    r[0:2] = -w * t
    r[2:4] = w * (1 - xi) * t
    r[4:6] = w * xi * t
    r[6] = -c_h * w_c * g
    r[7:9] = -c_w * w_c * v_m
    return r


def film_node_residual_3d(q: npt.NDArray[np.float64 | np.complex128],
                          data: npt.NDArray[np.float64], w: float, w_c: float, c_h: float,
                          c_w: float) -> npt.NDArray[np.float64 | np.complex128]:
    """Residual (19,) of one 3D film node (master triangle); q may be complex."""
    x, a, b, c, t = q[0:3], q[3:6], q[6:9], q[9:12], q[16:19]   # q[12:16] (h, w): UFL's
    cn, k0, z = data[0:6].reshape(3, 2), data[6], data[7:16].reshape(3, 3)
    T = np.array([b - a, c - a])                   # t_1, t_2 (rows)
    m = T @ T.T
    xi = np.linalg.solve(m, T @ (x - a))
    Nk = np.array([1 - xi[0] - xi[1], xi[0], xi[1]])
    n = np.cross(T[0], T[1])
    n = n / np.sqrt(n @ n)
    g = (x - a) @ n
    s = Nk @ cn                                      # s^a = Σ_k N_k c_k^a
    v_m = s @ T + Nk @ (k0 * np.array([a, b, c]) + z)
    r = np.zeros(19, dtype=q.dtype)
    r[0:3] = -w * t
    for k in range(3):
        r[3 + 3 * k:6 + 3 * k] = w * Nk[k] * t
    r[12] = -c_h * w_c * g
    r[13:16] = -c_w * w_c * v_m
    return r


def film_node_residuals(q: npt.ArrayLike, data: npt.NDArray[np.float64],
                        w: npt.NDArray[np.float64], w_c: npt.NDArray[np.float64], c_h: float,
                        c_w: float, h: float = 1e-30
                        ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Residuals (n, N) and complex-step tangents (n, N, N), as the C++ kernel.

    N = 11 (2D, ``data`` (n, 7)) or 19 (3D: q with 19 columns, ``data`` (n, 16)).
    """
    q = np.asarray(q, float)
    N = 19 if q.ndim == 2 and q.shape[1] == 19 else 11
    node = film_node_residual_3d if N == 19 else film_node_residual
    q = q.reshape(-1, N)
    r = np.zeros_like(q)
    J = np.zeros((len(q), N, N))
    for i, qi in enumerate(q):
        args = (data[i], w[i], w_c[i], c_h, c_w)
        r[i] = node(qi.astype(complex), *args).real
        for k in range(N):
            qc = qi.astype(complex)
            qc[k] += 1j * h
            J[i, :, k] = node(qc, *args).imag / h
    return r, J
