// Copyright (C) 2026 tribofx contributors
// SPDX-License-Identifier: MIT
//
// Two-body (master-slave) contact in 2D: closest-point search on the current
// master polyline, and the nodal augmented-Lagrangian contact residual with its
// exact tangent with respect to the slave AND the master degrees of freedom.
//
// Master surface: straight segments (x1, x2) oriented so that the outward unit
// normal of the master body is n = (tau_y, -tau_x)/l, tau = x2 - x1, l = |tau|.
// A slave node x is paired with the segment nearest to it (a box tree over the
// segments, refitted when the master moves); on it
//
//   xi = (x - x1).tau / l^2,   xbar = x1 + xi tau,   g = (x - xbar).n      (eq. 2)
//
// Per slave node (vertex quadrature: lumped reference weight w of the
// virtual work, w_c of the constraint rows) with the Alart-Curnier tractions
//
//   T_N = min(lam_N + rho_N g, 0),
//   T_T = proj_{|.| <= -mu T_N}((I - n n) lam_T + rho_T (I - n n) s),
//   s   = xbar - z,  z = y1 + xi_old (y2 - y1)  (the master material point of
//         the last converged projection, now at z; Lagrangian slip), or in
//         Eulerian mode (eq. 27) s = c tau with the constant c given in place of
//         xi_old (c tau = -dtau F V of a master moving along its own surface),
//
// the residual is  w (T_N dg + (T_T.tau) dxi)  on the positions (eq. 8) and
// w_c (1/rho) T  on the multiplier rows (the -(1/rho) lam part is linear and
// assembled by UFL). dg and dxi are the exact first variations
//
//   dg   = n.(dx - (1 - xi) dx1 - xi dx2),
//   dxi  = [tau.dx + ((xi - 1) tau - g n).dx1 + (g n - xi tau).dx2] / l^2,
//
// and the tangent is the exact derivative of this residual, by forward-mode
// automatic differentiation (Dual numbers) over the local unknowns
//   [x (2), x1 (2), x2 (2), y1 (2), y2 (2), lam_N, lam_T (2)].
// tribofx/two_body_ref.py is the NumPy twin of this file.

#pragma once

#include "bbox_tree.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

namespace tribofx::two_body
{

/// Number of local unknowns per slave node (2D, friction).
inline constexpr int num_local = 13;

/// Forward-mode dual number with N derivative directions.
template <int N>
struct Dual
{
  double v = 0.0;
  std::array<double, N> d{};

  Dual() = default;
  Dual(double value) : v(value) {}
  static Dual variable(double value, int k)
  {
    Dual x(value);
    x.d[k] = 1.0;
    return x;
  }
};

template <int N>
Dual<N> operator+(const Dual<N>& a, const Dual<N>& b)
{
  Dual<N> c(a.v + b.v);
  for (int k = 0; k < N; ++k)
    c.d[k] = a.d[k] + b.d[k];
  return c;
}
template <int N>
Dual<N> operator-(const Dual<N>& a, const Dual<N>& b)
{
  Dual<N> c(a.v - b.v);
  for (int k = 0; k < N; ++k)
    c.d[k] = a.d[k] - b.d[k];
  return c;
}
template <int N>
Dual<N> operator-(const Dual<N>& a)
{
  Dual<N> c(-a.v);
  for (int k = 0; k < N; ++k)
    c.d[k] = -a.d[k];
  return c;
}
template <int N>
Dual<N> operator*(const Dual<N>& a, const Dual<N>& b)
{
  Dual<N> c(a.v * b.v);
  for (int k = 0; k < N; ++k)
    c.d[k] = a.d[k] * b.v + a.v * b.d[k];
  return c;
}
template <int N>
Dual<N> operator/(const Dual<N>& a, const Dual<N>& b)
{
  Dual<N> c(a.v / b.v);
  const double ib2 = 1.0 / (b.v * b.v);
  for (int k = 0; k < N; ++k)
    c.d[k] = (a.d[k] * b.v - a.v * b.d[k]) * ib2;
  return c;
}
template <int N>
Dual<N> sqrt(const Dual<N>& a)
{
  Dual<N> c(std::sqrt(a.v));
  const double f = c.v > 0.0 ? 0.5 / c.v : 0.0;
  for (int k = 0; k < N; ++k)
    c.d[k] = f * a.d[k];
  return c;
}

template <int N>
Dual<N> operator+(double a, const Dual<N>& b)
{
  return Dual<N>(a) + b;
}
template <int N>
Dual<N> operator+(const Dual<N>& a, double b)
{
  return a + Dual<N>(b);
}
template <int N>
Dual<N> operator-(double a, const Dual<N>& b)
{
  return Dual<N>(a) - b;
}
template <int N>
Dual<N> operator-(const Dual<N>& a, double b)
{
  return a - Dual<N>(b);
}
template <int N>
Dual<N> operator*(double a, const Dual<N>& b)
{
  Dual<N> c(a * b.v);
  for (int k = 0; k < N; ++k)
    c.d[k] = a * b.d[k];
  return c;
}
template <int N>
Dual<N> operator*(const Dual<N>& a, double b)
{
  return b * a;
}

/// Current master polyline with a box tree refitted when the nodes move.
class MasterSurface
{
public:
  MasterSurface(std::span<const double> nodes, std::span<const std::int32_t> segments)
      : _segments(segments.begin(), segments.end()),
        _nodes(nodes.begin(), nodes.end()), _tree(boxes())
  {
  }

  /// New current node positions (same number, same segments): the box tree is
  /// refitted bottom-up, its topology kept.
  void refit(std::span<const double> nodes)
  {
    if (nodes.size() != _nodes.size())
      throw std::invalid_argument("refit: the number of master nodes changed");
    std::copy(nodes.begin(), nodes.end(), _nodes.begin());
    _tree.refit(boxes());
  }

  std::size_t num_segments() const { return _segments.size() / 2; }
  std::size_t num_nodes() const { return _nodes.size() / 2; }
  const std::vector<std::int32_t>& segments() const { return _segments; }
  const std::vector<double>& nodes() const { return _nodes; }

  /// Squared distance from x to segment s and the clamped coordinate of its
  /// nearest point.
  std::pair<double, double> segment_distance2(const double* x, std::int32_t s) const
  {
    const double* a = &_nodes[2 * _segments[2 * s]];
    const double* b = &_nodes[2 * _segments[2 * s + 1]];
    const double tx = b[0] - a[0], ty = b[1] - a[1];
    const double l2 = tx * tx + ty * ty;
    double xi = ((x[0] - a[0]) * tx + (x[1] - a[1]) * ty) / l2;
    xi = std::clamp(xi, 0.0, 1.0);
    const double dx = x[0] - a[0] - xi * tx, dy = x[1] - a[1] - xi * ty;
    return {dx * dx + dy * dy, xi};
  }

  /// Nearest segment of each point (ties: the lowest index); facet[i], xi[i]
  /// (clamped to [0, 1]) and distance[i].
  void project(std::span<const double> points, std::span<std::int32_t> facet,
               std::span<double> xi, std::span<double> distance) const
  {
    const std::size_t np = points.size() / 2;
    for (std::size_t p = 0; p < np; ++p)
    {
      const double* x = points.data() + 2 * p;
      double dmin = std::numeric_limits<double>::infinity();
      std::int32_t best = -1;
      double best_xi = 0.0;
      _tree.nearest_search(x, dmin,
                           [&](std::int32_t s)
                           {
                             const auto [d2, t] = segment_distance2(x, s);
                             const double d = std::sqrt(d2);
                             if (d < dmin or (d == dmin and s < best))
                             {
                               dmin = d;
                               best = s;
                               best_xi = t;
                             }
                           });
      facet[p] = best;
      xi[p] = best_xi;
      distance[p] = dmin;
    }
  }

private:
  std::vector<double> boxes() const
  {
    const std::size_t ns = num_segments();
    std::vector<double> b(4 * ns);
    for (std::size_t s = 0; s < ns; ++s)
    {
      const double* p = &_nodes[2 * _segments[2 * s]];
      const double* q = &_nodes[2 * _segments[2 * s + 1]];
      b[4 * s + 0] = std::min(p[0], q[0]);
      b[4 * s + 1] = std::min(p[1], q[1]);
      b[4 * s + 2] = std::max(p[0], q[0]);
      b[4 * s + 3] = std::max(p[1], q[1]);
    }
    return b;
  }

  std::vector<std::int32_t> _segments;
  std::vector<double> _nodes;
  geometry::BoxTree<2> _tree;
};

/// Parameters of the nodal law.
struct Law
{
  double rho_n, rho_t, mu;
  bool friction;
  /// Eulerian slip (eq. 27, master moving along its own surface): the slip is
  /// s = c^a t_a with the per-node constants c passed in place of xi_old (the
  /// surface deformation gradient of the current facet applied to -V dtau),
  /// and the old-facet unknowns y are not used.
  bool eulerian = false;
};

/// Residual r (num_local) and tangent J (num_local x num_local, row-major) of
/// one slave node; q = [x, x1, x2, y1, y2, lam_N, lam_T], xi_old the old
/// coordinate on the segment (y1, y2), w and w_c the weights.
inline void node_residual(const double* q, double xi_old, double w, double w_c,
                          const Law& law, double* r, double* J)
{
  constexpr int N = num_local;
  using D = Dual<N>;
  std::array<D, N> v;
  for (int k = 0; k < N; ++k)
    v[k] = D::variable(q[k], k);
  const D x0 = v[0], x1 = v[1], a0 = v[2], a1 = v[3], b0 = v[4], b1 = v[5];
  const D c0 = v[6], c1 = v[7], e0 = v[8], e1 = v[9];
  const D lam_n = v[10], lt0 = v[11], lt1 = v[12];
  const D t0 = b0 - a0, t1 = b1 - a1;
  const D l2 = t0 * t0 + t1 * t1;
  const D l = sqrt(l2);
  const D n0 = t1 / l, n1 = -t0 / l;
  const D xi = ((x0 - a0) * t0 + (x1 - a1) * t1) / l2;
  const D xb0 = a0 + xi * t0, xb1 = a1 + xi * t1;
  const D g = (x0 - xb0) * n0 + (x1 - xb1) * n1;
  const D lhat_n = lam_n + law.rho_n * g;
  const D T_n = lhat_n.v < 0.0 ? lhat_n : D(0.0);
  D Tt0(0.0), Tt1(0.0);
  if (law.friction)
  {
    const D z0 = c0 + xi_old * (e0 - c0), z1 = c1 + xi_old * (e1 - c1);
    const D s0 = law.eulerian ? xi_old * t0 : xb0 - z0;
    const D s1 = law.eulerian ? xi_old * t1 : xb1 - z1;
    const D sn = s0 * n0 + s1 * n1;
    const D ln = lt0 * n0 + lt1 * n1;
    const D h0 = (lt0 - ln * n0) + law.rho_t * (s0 - sn * n0);
    const D h1 = (lt1 - ln * n1) + law.rho_t * (s1 - sn * n1);
    const D radius = -law.mu * T_n;
    const D norm = sqrt(h0 * h0 + h1 * h1 + D(1e-24));
    if (norm.v < radius.v)
    {
      Tt0 = h0;
      Tt1 = h1;
    }
    else
    {
      Tt0 = radius / norm * h0;
      Tt1 = radius / norm * h1;
    }
  }
  const D tt = Tt0 * t0 + Tt1 * t1; // T_T . tau
  const D f = tt / l2;
  std::array<D, N> res;
  // slave position: T_N n + (T_T.tau) tau / l^2
  res[0] = w * (T_n * n0 + f * t0);
  res[1] = w * (T_n * n1 + f * t1);
  // master node 1: -T_N (1 - xi) n + (T_T.tau) ((xi - 1) tau - g n) / l^2
  res[2] = w * (-T_n * (1.0 - xi) * n0 + f * ((xi - 1.0) * t0 - g * n0));
  res[3] = w * (-T_n * (1.0 - xi) * n1 + f * ((xi - 1.0) * t1 - g * n1));
  // master node 2: -T_N xi n + (T_T.tau) (g n - xi tau) / l^2
  res[4] = w * (-T_n * xi * n0 + f * (g * n0 - xi * t0));
  res[5] = w * (-T_n * xi * n1 + f * (g * n1 - xi * t1));
  for (int k = 6; k < 10; ++k)
    res[k] = D(0.0);
  res[10] = (w_c / law.rho_n) * T_n;
  res[11] = law.friction ? (w_c / law.rho_t) * Tt0 : D(0.0);
  res[12] = law.friction ? (w_c / law.rho_t) * Tt1 : D(0.0);
  for (int i = 0; i < N; ++i)
  {
    r[i] = res[i].v;
    for (int k = 0; k < N; ++k)
      J[i * N + k] = res[i].d[k];
  }
}

} // namespace tribofx::two_body
