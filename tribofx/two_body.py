"""Two-body contact kernels in 2D and 3D (C++): master search and the nodal contact law.

The work is done by :mod:`tribofx._cpp` (``cpp_kernels/src/two_body.hpp``);
:mod:`tribofx.two_body_ref` is its plain NumPy twin, used by the tests.

* :class:`MasterSurface` — the current master polyline: ``nodes`` (n_m, 2)
  float64 current positions, ``segments`` (m, 2) int32 node indices, oriented
  so that the outward unit normal of the master body is (τ_y, −τ_x)/l with
  τ = x₂ − x₁.  ``refit(nodes)`` moves the nodes (the box tree is refitted, not
  rebuilt); ``project(points)`` (n, 2) returns the nearest segment ``facet``
  (n,) int32, its clamped coordinate ``xi`` ∈ [0, 1] (n,) and the ``distance``
  (n,); ties go to the lowest segment index.
* :class:`MasterSurface3` — the same for a triangulated 3D master surface:
  ``nodes`` (n_m, 3), ``triangles`` (m, 3) int32 oriented so that the outward
  unit normal is t₁ × t₂/|t₁ × t₂| (t₁ = x₂ − x₁, t₂ = x₃ − x₁); ``project``
  returns ``facet`` (n,), ``xi`` (n, 2), the coordinates of the nearest point
  x₁ + ξ¹t₁ + ξ²t₂ of the triangle, and ``distance`` (n,)
  (``cpp_kernels/src/two_body_3d.hpp``).
* :func:`node_residuals` — per slave node the residual r (n, 13) and its exact
  tangent J (n, 13, 13) = ∂r/∂q of the Alart–Curnier law (see the header of
  ``two_body.hpp`` for the equations), packed over the local unknowns

      q = [x (2), x₁ (2), x₂ (2), y₁ (2), y₂ (2), λ_N, λ_T (2)]

  (slave node, current master segment, master segment of the last converged
  projection, multipliers).  Rows 0–5 are the virtual work on the positions
  (weight ``w``), rows 6–9 are zero, rows 10–12 the (1/ρ) T parts of the
  multiplier rows (weight ``w_c``).  In 3D (q with 25 columns, ``xi_old``
  (n, 2)) the packing is

      q = [x (3), x₁, x₂, x₃ (9), y₁, y₂, y₃ (9), λ_N, λ_T (3)]

  (rows 0–11 the virtual work, 12–20 zero, 21–24 the multiplier rows), r
  (n, 25) and J (n, 25, 25); the equations are in the header of
  ``two_body_3d.hpp``.
* :func:`film_node_residuals` — per slave node of a film between two deformable
  bodies (:class:`tribofx.interfaces.TwoBodyFilm`, 2D) the residual r (n, 11)
  and its exact tangent J (n, 11, 11) over

      q = [x (2), x₁ (2), x₂ (2), h, w (2), t (2)]

  (slave node, master segment, the film's nodal gap, master surface velocity and
  nominal traction), with ``data`` (n, 7) = [c₁, c₂, k₀, z₁ (2), z₂ (2)]: rows
  0–5 carry the traction t to the slave (−w t) and to the master at the
  projection (w(1 − ξ)t, wξt), row 6 is −c_h w_c g, rows 7–8 −c_w w_c v_m (the
  master's surface velocity at the projection), rows 9–10 zero; the equations
  are in the header of ``cpp_kernels/src/two_body_film.hpp``.  In 3D (q with 19
  columns) the packing is

      q = [x (3), x₁, x₂, x₃ (9), h, w (3), t (3)]

  with ``data`` (n, 16) = [c₁ (2), c₂ (2), c₃ (2), k₀, z₁ (3), z₂ (3), z₃ (3)]
  (c_k: the master's reference velocity at node k in the reference facet's basis
  T_a = X_{a+1} − X₁): rows 0–11 carry t (−w t on the slave, w N_k(ξ) t on the
  triangle's nodes), row 12 −c_h w_c g, rows 13–15 −c_w w_c v_m, rows 16–18 zero;
  r (n, 19), J (n, 19, 19) (``film_node_residual_3d`` in the same header).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from . import _cpp

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["NUM_LOCAL", "NUM_LOCAL_FILM", "MasterSurface", "MasterSurface3", "film_node_residuals",
           "node_residuals", "num_data_film", "num_local", "num_local_film"]

#: Local unknowns per slave node (2D).
NUM_LOCAL = 13

#: Local unknowns per slave node of the two-body film (2D).
NUM_LOCAL_FILM = 11

MasterSurface = _cpp.MasterSurface
MasterSurface3 = _cpp.MasterSurface3


def num_local_film(gdim: int) -> int:
    """Local unknowns per film node: x, the master facet's d nodes, h, w (d), t (d)."""
    return gdim + gdim * gdim + 1 + 2 * gdim


def num_data_film(gdim: int) -> int:
    """Return the data per film node: the tangential speeds c (d × (d − 1)), k₀, z (d × d)."""
    return gdim * (gdim - 1) + 1 + gdim * gdim


def num_local(gdim: int) -> int:
    """Local unknowns per slave node: x, the master facet's d nodes, the old facet's, λ."""
    return gdim + 2 * gdim * gdim + 1 + gdim


def node_residuals(q: npt.ArrayLike, xi_old: npt.ArrayLike, w: npt.ArrayLike,
                   w_c: npt.ArrayLike, rho_n: float, rho_t: float | None = None,
                   mu: float = 0.0, eulerian: bool = False
                   ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Residuals (n, 13) and tangents (n, 13, 13) of n slave nodes (see the module docstring).

    Args:
        q: (n, 13) local unknowns (3D: (n, 25)).
        xi_old: (n,) coordinate of the last converged projection on (y₁, y₂)
            (3D: (n, 2) on (y₁, y₂, y₃)).
        w: (n,) lumped reference weights of the virtual work.
        w_c: (n,) lumped reference weights of the constraint rows.
        rho_n: normal augmentation parameter (MPa/mm).
        rho_t: tangential augmentation parameter (MPa/mm); None: rho_n.
        mu: Coulomb coefficient (0: frictionless, rows 11–12 zero).
        eulerian: Eulerian slip (eq. 27): ``xi_old`` holds the constants c of the
            slip s = c τ (2D) or c^a t_a (3D) instead; the y unknowns are unused.
    """
    q = np.ascontiguousarray(q, dtype=np.float64)
    three = q.ndim == 2 and q.shape[1] == num_local(3)
    q = q.reshape(-1, num_local(3) if three else NUM_LOCAL)
    vec = [np.ascontiguousarray(a, dtype=np.float64).ravel() for a in (w, w_c)]
    rho_t = rho_n if rho_t is None else rho_t
    args = (float(rho_n), float(rho_t), float(mu), mu > 0, bool(eulerian))
    if three:
        xi: npt.NDArray[np.float64] = np.ascontiguousarray(xi_old, dtype=np.float64).reshape(-1, 2)
        return _cpp.two_body_nodes_3d(q, xi, *vec, *args)
    xi = np.ascontiguousarray(xi_old, dtype=np.float64).ravel()
    return _cpp.two_body_nodes(q, xi, *vec, *args)


def film_node_residuals(q: npt.ArrayLike, data: npt.ArrayLike, w: npt.ArrayLike,
                        w_c: npt.ArrayLike, c_h: float,
                        c_w: float) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Residuals (n, 11) and tangents (n, 11, 11) of n film nodes (see the module docstring).

    Args:
        q: (n, 11) local unknowns [x, x₁, x₂, h, w, t] (mm, mm/s, MPa); 3D: (n, 19)
            [x, x₁, x₂, x₃, h, w, t].
        data: (n, 7) [c₁, c₂, k₀, z₁, z₂]: the master's reference tangential velocity
            per reference length at x₁, x₂ (1/s), and the master nodes' velocities
            ẋ_k = k₀ x_k + z_k (k₀ in 1/s, z_k in mm/s; 0 for a steady film); 3D:
            (n, 16) [c₁, c₂, c₃ (2 each, in the reference facet's basis), k₀, z₁,
            z₂, z₃ (3 each)].
        w: (n,) lumped reference weights of the traction rows (mm; mm² in 3D and
            axisymmetric).
        w_c: (n,) lumped reference weights of the gap and velocity rows (mm; mm² in 3D).
        c_h: row scale of the gap rows (MPa/mm).
        c_w: row scale of the velocity rows (MPa·s/mm).
    """
    q = np.ascontiguousarray(q, dtype=np.float64)
    three = q.ndim == 2 and q.shape[1] == num_local_film(3)
    d = 3 if three else 2
    q = q.reshape(-1, num_local_film(d))
    data = np.ascontiguousarray(data, dtype=np.float64).reshape(-1, num_data_film(d))
    vec = [np.ascontiguousarray(a, dtype=np.float64).ravel() for a in (w, w_c)]
    kernel = _cpp.two_body_film_nodes_3d if three else _cpp.two_body_film_nodes
    return kernel(q, data, *vec, float(c_h), float(c_w))
