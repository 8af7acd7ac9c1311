// Copyright (C) 2026 tribofx contributors
// SPDX-License-Identifier: MIT
//
// Film between two deformable bodies in 2D (and 3D, film_node_residual_3d: the
// master triangle in place of the segment): the nodal coupling of a slave node
// of the lubricated boundary to the current master polyline, with its exact
// tangent with respect to the slave, the master and the film's nodal unknowns.
//
// The lubrication surface is the slave's current boundary (S = gamma_l). Per
// slave node the film carries three nodal unknowns beside the displacements:
// the gap h, the velocity w of the master's surface at the projection point and
// the nominal fluid traction t of eq. (46) on the slave. On the master segment
// (x1, x2), tau = x2 - x1, l = |tau|, n = (tau_y, -tau_x)/l the master's
// outward normal (as in two_body.hpp):
//
//   xi  = (x - x1).tau / l^2,   xbar = x1 + xi tau,   g = (x - xbar).n
//   v_m = ((1 - xi) c1 + xi c2) tau + (1 - xi) xdot1 + xi xdot2,
//   xdot_k = k0 x_k + z_k
//
// c_k: the master's reference tangential velocity per reference length at the
// segment's nodes (V(X_k).T/|T|^2, T = X2 - X1: a master material point moving
// along its own surface, eq. 26); k0, z_k: the weights of a backward difference
// of the master's nodes (0 for a steady film). The residual of the node:
//
//   rows x:      -w t                 (the film on the slave: -int T.du dS, lumped)
//   rows x1, x2:  w (1 - xi) t, w xi t (the reaction on the master at xbar)
//   row h:       -c_h w_c g           (+ c_h w_c h from UFL: h = g nodally)
//   rows w:      -c_w w_c v_m         (+ c_w w_c w from UFL: w = v_m nodally)
//   rows t:       0                   (t = T(u, p, h, w) is collocated by UFL)
//
// so the film's forces on the two bodies balance exactly (action = reaction),
// and the tangent is the exact derivative of this residual (forward-mode dual
// numbers) over the local unknowns [x (2), x1 (2), x2 (2), h, w (2), t (2)].
// tribofx/two_body_film_ref.py is the NumPy twin of this file.

#pragma once

#include "two_body.hpp"

#include <array>

namespace tribofx::two_body
{

/// Number of local unknowns per slave node of the two-body film (2D).
inline constexpr int num_local_film = 11;

/// Write the values (r, N) and the derivatives (J, N x N, row-major) of a node's residual.
template <int N>
inline void write_residual(const std::array<Dual<N>, N>& res, double* r, double* J)
{
  for (int i = 0; i < N; ++i)
  {
    r[i] = res[i].v;
    for (int k = 0; k < N; ++k)
      J[i * N + k] = res[i].d[k];
  }
}

/// Number of data per slave node: c1, c2, k0, z1 (2), z2 (2).
inline constexpr int num_data_film = 7;

/// Residual r (11) and tangent J (11 x 11, row-major) of one slave node of the
/// film; q = [x, x1, x2, h, w, t], data = [c1, c2, k0, z1, z2], w and w_c the
/// lumped weights, c_h and c_w the row scales of the gap and velocity rows.
inline void film_node_residual(const double* q, const double* data, double w, double w_c,
                               double c_h, double c_w, double* r, double* J)
{
  constexpr int N = num_local_film;
  using D = Dual<N>;
  std::array<D, N> v;
  for (int k = 0; k < N; ++k)
    v[k] = D::variable(q[k], k);
  const D x0 = v[0], x1 = v[1], a0 = v[2], a1 = v[3], b0 = v[4], b1 = v[5];
  const D tr0 = v[9], tr1 = v[10];
  const double c1 = data[0], c2 = data[1], k0 = data[2];
  const D t0 = b0 - a0, t1 = b1 - a1;
  const D l2 = t0 * t0 + t1 * t1;
  const D l = sqrt(l2);
  const D n0 = t1 / l, n1 = -t0 / l;
  const D xi = ((x0 - a0) * t0 + (x1 - a1) * t1) / l2;
  const D g = (x0 - a0 - xi * t0) * n0 + (x1 - a1 - xi * t1) * n1;
  const D s = (1.0 - xi) * c1 + xi * c2;
  const D vm0 = s * t0 + (1.0 - xi) * (k0 * a0 + data[3]) + xi * (k0 * b0 + data[5]);
  const D vm1 = s * t1 + (1.0 - xi) * (k0 * a1 + data[4]) + xi * (k0 * b1 + data[6]);
  const std::array<D, N> res = {-w * tr0,
                                -w * tr1,
                                w * (1.0 - xi) * tr0,
                                w * (1.0 - xi) * tr1,
                                w * xi * tr0,
                                w * xi * tr1,
                                -c_h * w_c * g,
                                -c_w * w_c * vm0,
                                -c_w * w_c * vm1,
                                D(0.0),
                                D(0.0)};
  write_residual<N>(res, r, J);
}

/// Number of local unknowns per slave node of the two-body film in 3D.
inline constexpr int num_local_film_3d = 19;

/// Number of data per slave node in 3D: c (3 nodes x 2), k0, z1, z2, z3 (3 each).
inline constexpr int num_data_film_3d = 16;

/// The 3D film node: residual r (19) and tangent J (19 x 19, row-major) over
/// q = [x (3), x1, x2, x3 (9), h, w (3), t (3)], data = [c_1 (2), c_2 (2), c_3 (2),
/// k0, z1 (3), z2 (3), z3 (3)].  On the master triangle (x1, x2, x3),
/// t_1 = x2 - x1, t_2 = x3 - x1, the metric m = [t_a.t_b], n = t_1 x t_2 / |t_1 x t_2|
/// (the master's outward normal, as in two_body_3d.hpp),
///
///   xi = m^{-1} [(x - x1).t_1, (x - x1).t_2],  N = (1 - xi^1 - xi^2, xi^1, xi^2),
///   g  = (x - x1).n,
///   v_m = (sum_k N_k c_k^a) t_a + sum_k N_k (k0 x_k + z_k)
///
/// (c_k^a: the master's reference velocity at node k in the reference facet's
/// basis T_a, its material moving along its own surface; k0, z_k the backward
/// difference of its nodes).  Rows: x -w t; x_k w N_k t; h -c_h w_c g;
/// w -c_w w_c v_m; t 0 — the 2D node's, with the triangle in place of the segment.
inline void film_node_residual_3d(const double* q, const double* data, double w, double w_c,
                                  double c_h, double c_w, double* r, double* J)
{
  constexpr int N = num_local_film_3d;
  using D = Dual<N>;
  std::array<D, N> v;
  for (int k = 0; k < N; ++k)
    v[k] = D::variable(q[k], k);
  auto at = [&](int k) { return std::array<D, 3>{v[k], v[k + 1], v[k + 2]}; };
  const auto x = at(0), a = at(3), b = at(6), c = at(9), tr = at(16);
  std::array<D, 3> t1, t2, d;
  for (int i = 0; i < 3; ++i)
  {
    t1[i] = b[i] - a[i];
    t2[i] = c[i] - a[i];
    d[i] = x[i] - a[i];
  }
  auto dot = [](const std::array<D, 3>& p, const std::array<D, 3>& q_)
  { return p[0] * q_[0] + p[1] * q_[1] + p[2] * q_[2]; };
  const D m11 = dot(t1, t1), m12 = dot(t1, t2), m22 = dot(t2, t2);
  const D det = m11 * m22 - m12 * m12;
  const D b1 = dot(d, t1), b2 = dot(d, t2);
  const D xi1 = (m22 * b1 - m12 * b2) / det, xi2 = (m11 * b2 - m12 * b1) / det;
  const std::array<D, 3> cr = {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2],
                               t1[0] * t2[1] - t1[1] * t2[0]};
  const D len = sqrt(dot(cr, cr));
  const D g = dot(d, cr) / len;
  const D N1 = 1.0 - xi1 - xi2;
  const D s1 = N1 * data[0] + xi1 * data[2] + xi2 * data[4];
  const D s2 = N1 * data[1] + xi1 * data[3] + xi2 * data[5];
  const double k0 = data[6];
  std::array<D, N> res;
  for (int i = 0; i < 3; ++i)
  {
    res[i] = -w * tr[i];
    res[3 + i] = w * N1 * tr[i];
    res[6 + i] = w * xi1 * tr[i];
    res[9 + i] = w * xi2 * tr[i];
    const D vm = s1 * t1[i] + s2 * t2[i] + N1 * (k0 * a[i] + data[7 + i])
                 + xi1 * (k0 * b[i] + data[10 + i]) + xi2 * (k0 * c[i] + data[13 + i]);
    res[13 + i] = -c_w * w_c * vm;
    res[16 + i] = D(0.0);
  }
  res[12] = -c_h * w_c * g;
  write_residual<N>(res, r, J);
}

} // namespace tribofx::two_body
