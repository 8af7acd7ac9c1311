"""Two-body contact kernels in 2D (C++): master search and the nodal contact law.

The work is done by :mod:`tribofx._cpp` (``cpp_kernels/src/two_body.hpp``);
:mod:`tribofx.two_body_ref` is its plain NumPy twin, used by the tests.

* :class:`MasterSurface` — the current master polyline: ``nodes`` (n_m, 2)
  float64 current positions, ``segments`` (m, 2) int32 node indices, oriented
  so that the outward unit normal of the master body is (τ_y, −τ_x)/l with
  τ = x₂ − x₁.  ``refit(nodes)`` moves the nodes (the box tree is refitted, not
  rebuilt); ``project(points)`` (n, 2) returns the nearest segment ``facet``
  (n,) int32, its clamped coordinate ``xi`` ∈ [0, 1] (n,) and the ``distance``
  (n,); ties go to the lowest segment index.
* :func:`node_residuals` — per slave node the residual r (n, 13) and its exact
  tangent J (n, 13, 13) = ∂r/∂q of the Alart–Curnier law (see the header of
  ``two_body.hpp`` for the equations), packed over the local unknowns

      q = [x (2), x₁ (2), x₂ (2), y₁ (2), y₂ (2), λ_N, λ_T (2)]

  (slave node, current master segment, master segment of the last converged
  projection, multipliers).  Rows 0–5 are the virtual work on the positions
  (weight ``w``), rows 6–9 are zero, rows 10–12 the (1/ρ) T parts of the
  multiplier rows (weight ``w_c``).
"""

import numpy as np

from . import _cpp

__all__ = ["NUM_LOCAL", "MasterSurface", "node_residuals"]

#: Local unknowns per slave node.
NUM_LOCAL = 13

MasterSurface = _cpp.MasterSurface


def node_residuals(q, xi_old, w, w_c, rho_n, rho_t=None, mu=0.0):
    """Residuals (n, 13) and tangents (n, 13, 13) of n slave nodes (see the module docstring).

    Args:
        q: (n, 13) local unknowns.
        xi_old: (n,) coordinate of the last converged projection on (y₁, y₂).
        w: (n,) lumped reference weights of the virtual work.
        w_c: (n,) lumped reference weights of the constraint rows.
        rho_n: normal augmentation parameter (MPa/mm).
        rho_t: tangential augmentation parameter (MPa/mm); None: rho_n.
        mu: Coulomb coefficient (0: frictionless, rows 11–12 zero).
    """
    q = np.ascontiguousarray(q, dtype=np.float64).reshape(-1, NUM_LOCAL)
    vec = [np.ascontiguousarray(a, dtype=np.float64).ravel() for a in (xi_old, w, w_c)]
    rho_t = rho_n if rho_t is None else rho_t
    return _cpp.two_body_nodes(q, *vec, float(rho_n), float(rho_t), float(mu), mu > 0)
