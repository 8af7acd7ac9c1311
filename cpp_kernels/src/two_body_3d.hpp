// Copyright (C) 2026 tribofx contributors
// SPDX-License-Identifier: MIT
//
// Two-body (master-slave) contact in 3D: closest-point search on the current
// triangulated master surface, and the nodal augmented-Lagrangian residual with
// its exact tangent with respect to the slave and the master degrees of freedom.
// The 3D counterpart of two_body.hpp (same law, same packing idea).
//
// Master surface: flat triangles (x1, x2, x3) oriented so that the outward unit
// normal of the master body is n = t1 x t2 / |t1 x t2|, t1 = x2 - x1,
// t2 = x3 - x1.  On the triangle paired with a slave node x (the nearest one,
// a box tree refitted when the master moves), with the metric m = [t_a.t_b],
//
//   xi = m^{-1} [(x - x1).t1, (x - x1).t2],  xbar = x1 + xi^1 t1 + xi^2 t2,
//   g = (x - xbar).n                                                     (eq. 2)
//
// (the projection onto the plane of the triangle; xi outside the triangle is
// kept, the search decides the pairing).  Alart-Curnier tractions as in 2D,
//
//   T_N = min(lam_N + rho_N g, 0),
//   T_T = proj_{|.| <= -mu T_N}((I - n n) lam_T + rho_T (I - n n) s),
//   s   = xbar - z,  z = y1 + xi_old^1 (y2 - y1) + xi_old^2 (y3 - y1),
//         or, Eulerian (eq. 27), s = c^a t_a with c given in place of xi_old,
//
// and the virtual work w (T_N dg + T_a dxi^a), T_a = T_T.t_a (eq. 8), with the
// exact first variations of a flat facet, N = (1 - xi^1 - xi^2, xi^1, xi^2),
//
//   dg    = n.(dx - N_i dx_i),
//   dxi^a = m^{ab} [t_b.(dx - N_i dx_i) + g n.dt_b],  dt_b = dx_{b+1} - dx_1,
//
// so that, with F = T_N n + f^b t_b = T_N n + T_T and f^b = m^{ba} T_a, the rows
// are w F on x, w(-N_1 F - g n (f^1 + f^2)) on x1, w(-N_2 F + g n f^1) on x2,
// w(-N_3 F + g n f^2) on x3.  The tangent is the exact derivative by dual
// numbers over the 25 local unknowns
//   [x (3), x1, x2, x3 (9), y1, y2, y3 (9), lam_N, lam_T (3)].
// tribofx/two_body_ref.py is the NumPy twin of this file.

#pragma once

#include "bbox_tree.hpp"
#include "two_body.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <tuple>
#include <vector>

namespace tribofx::two_body
{

/// Number of local unknowns per slave node in 3D.
inline constexpr int num_local_3d = 25;

/// Closest point of x on triangle (a, b, c): squared distance and (v, w) with
/// p = a + v (b - a) + w (c - a)  (Voronoi regions of the vertices, edges, face).
inline std::tuple<double, double, double> triangle_closest(const double* x, const double* a,
                                                           const double* b, const double* c)
{
  auto dot3 = [](const double* p, const double* q)
  { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; };
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ap[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
  const double bp[3] = {x[0] - b[0], x[1] - b[1], x[2] - b[2]};
  const double cp[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
  const double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  const double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  double v = 0.0, w = 0.0;
  const double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
  if (d1 <= 0.0 and d2 <= 0.0)
  {
    v = 0.0, w = 0.0; // vertex a
  }
  else if (d3 >= 0.0 and d4 <= d3)
  {
    v = 1.0, w = 0.0; // vertex b
  }
  else if (vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0)
  {
    v = d1 / (d1 - d3), w = 0.0; // edge ab
  }
  else if (d6 >= 0.0 and d5 <= d6)
  {
    v = 0.0, w = 1.0; // vertex c
  }
  else if (vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0)
  {
    v = 0.0, w = d2 / (d2 - d6); // edge ac
  }
  else if (va <= 0.0 and (d4 - d3) >= 0.0 and (d5 - d6) >= 0.0)
  {
    w = (d4 - d3) / ((d4 - d3) + (d5 - d6)); // edge bc
    v = 1.0 - w;
  }
  else
  {
    const double denom = 1.0 / (va + vb + vc); // face
    v = vb * denom;
    w = vc * denom;
  }
  double d2s = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double e = x[k] - (a[k] + v * ab[k] + w * ac[k]);
    d2s += e * e;
  }
  return {d2s, v, w};
}

/// Current triangulated master surface with a box tree refitted when the nodes move.
class MasterSurface3
{
public:
  MasterSurface3(std::span<const double> nodes, std::span<const std::int32_t> triangles)
      : _tris(triangles.begin(), triangles.end()), _nodes(nodes.begin(), nodes.end()),
        _tree(boxes())
  {
  }

  /// The three vertices of triangle t, contiguous (9 doubles).
  const double* vertices(std::int32_t t) const { return &_xyz[9 * t]; }

  /// New current node positions (same number, same triangles): refit, not rebuild.
  void refit(std::span<const double> nodes)
  {
    if (nodes.size() != _nodes.size())
      throw std::invalid_argument("refit: the number of master nodes changed");
    std::copy(nodes.begin(), nodes.end(), _nodes.begin());
    _tree.refit(boxes());
  }

  std::size_t num_triangles() const { return _tris.size() / 3; }

  /// Nearest triangle of each point (ties: the lowest index): facet[i], the
  /// coordinates xi[2i], xi[2i+1] of the nearest point and distance[i].
  void project(std::span<const double> points, std::span<std::int32_t> facet,
               std::span<double> xi, std::span<double> distance) const
  {
    const std::size_t np = points.size() / 3;
    // visit the points in a spatially coherent order (cells of a 64^3 grid over
    // their bounding box, lexicographic), so that the previous point's triangle
    // is a close bound for the next one (warm start) and the tree stays in cache
    std::array<double, 3> lo, hi;
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
    for (std::size_t p = 0; p < np; ++p)
      for (int c = 0; c < 3; ++c)
      {
        lo[c] = std::min(lo[c], points[3 * p + c]);
        hi[c] = std::max(hi[c], points[3 * p + c]);
      }
    std::vector<std::uint32_t> key(np);
    for (std::size_t p = 0; p < np; ++p)
    {
      std::uint32_t k = 0;
      for (int c = 0; c < 3; ++c)
      {
        const double span = hi[c] - lo[c];
        const auto cell = static_cast<std::uint32_t>(
            span > 0 ? std::min(63.0, 64.0 * (points[3 * p + c] - lo[c]) / span) : 0.0);
        k = 64 * k + cell;
      }
      key[p] = k;
    }
    std::vector<std::size_t> order(np);
    for (std::size_t p = 0; p < np; ++p)
      order[p] = p;
    std::stable_sort(order.begin(), order.end(),
                     [&key](std::size_t a, std::size_t b) { return key[a] < key[b]; });
    std::int32_t prev = -1;
    for (const std::size_t p : order)
    {
      const double* x = points.data() + 3 * p;
      double dmin = std::numeric_limits<double>::infinity();
      std::int32_t best = -1;
      double bv = 0.0, bw = 0.0;
      // warm start: the previous point's triangle bounds the search; the tie rule
      // (lowest index) is unchanged, the pruning keeps ties
      if (prev >= 0)
      {
        const double* X = vertices(prev);
        const auto [d2, v, w] = triangle_closest(x, X, X + 3, X + 6);
        dmin = std::sqrt(d2);
        best = prev;
        bv = v;
        bw = w;
      }
      _tree.nearest_search(x, dmin,
                           [&](std::int32_t t)
                           {
                             const double* X = vertices(t);
                             const auto [d2, v, w] = triangle_closest(x, X, X + 3, X + 6);
                             const double d = std::sqrt(d2);
                             if (d < dmin or (d == dmin and t < best))
                             {
                               dmin = d;
                               best = t;
                               bv = v;
                               bw = w;
                             }
                           });
      facet[p] = best;
      xi[2 * p] = bv;
      xi[2 * p + 1] = bw;
      distance[p] = dmin;
      prev = best;
    }
  }

private:
  /// Boxes of the triangles; also refreshes the contiguous vertex copy _xyz.
  std::vector<double> boxes()
  {
    const std::size_t nt = num_triangles();
    _xyz.resize(9 * nt);
    for (std::size_t t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k)
        std::copy_n(&_nodes[3 * _tris[3 * t + k]], 3, &_xyz[9 * t + 3 * k]);
    std::vector<double> b(6 * nt);
    for (std::size_t t = 0; t < nt; ++t)
    {
      for (int c = 0; c < 3; ++c)
      {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (int k = 0; k < 3; ++k)
        {
          const double v = _nodes[3 * _tris[3 * t + k] + c];
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
        b[6 * t + c] = lo;
        b[6 * t + 3 + c] = hi;
      }
    }
    return b;
  }

  std::vector<std::int32_t> _tris;
  std::vector<double> _nodes;
  std::vector<double> _xyz; // per triangle its 3 vertices (search locality)
  geometry::BoxTree<3> _tree;
};

/// Residual r (25) and tangent J (25 x 25, row-major) of one slave node in 3D;
/// q = [x, x1, x2, x3, y1, y2, y3, lam_N, lam_T], xi_old (2) the old coordinates
/// on (y1, y2, y3), w and w_c the weights.
inline void node_residual_3d(const double* q, const double* xi_old, double w, double w_c,
                             const Law& law, double* r, double* J)
{
  constexpr int N = num_local_3d;
  using D = Dual<N>;
  using V3 = std::array<D, 3>;
  std::array<D, N> v;
  for (int k = 0; k < N; ++k)
    v[k] = D::variable(q[k], k);
  auto vec = [&v](int k) { return V3{v[k], v[k + 1], v[k + 2]}; };
  auto sub = [](const V3& p, const V3& s) { return V3{p[0] - s[0], p[1] - s[1], p[2] - s[2]}; };
  auto dot = [](const V3& p, const V3& s) { return p[0] * s[0] + p[1] * s[1] + p[2] * s[2]; };
  const V3 x = vec(0), a = vec(3), b = vec(6), c = vec(9);
  const V3 ya = vec(12), yb = vec(15), yc = vec(18), lt = vec(22);
  const D lam_n = v[21];
  const V3 t1 = sub(b, a), t2 = sub(c, a);
  const D m11 = dot(t1, t1), m12 = dot(t1, t2), m22 = dot(t2, t2);
  const D det = m11 * m22 - m12 * m12;
  const V3 nr{t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2],
              t1[0] * t2[1] - t1[1] * t2[0]};
  const D ln = sqrt(dot(nr, nr));
  const V3 n{nr[0] / ln, nr[1] / ln, nr[2] / ln};
  const V3 d = sub(x, a);
  const D r1 = dot(d, t1), r2 = dot(d, t2);
  const D xi1 = (m22 * r1 - m12 * r2) / det, xi2 = (m11 * r2 - m12 * r1) / det;
  V3 xb;
  for (int k = 0; k < 3; ++k)
    xb[k] = a[k] + xi1 * t1[k] + xi2 * t2[k];
  const D g = dot(sub(x, xb), n);
  const D lhat_n = lam_n + law.rho_n * g;
  const D T_n = lhat_n.v < 0.0 ? lhat_n : D(0.0);
  V3 Tt{D(0.0), D(0.0), D(0.0)};
  if (law.friction)
  {
    V3 s;
    for (int k = 0; k < 3; ++k)
      s[k] = law.eulerian
                 ? xi_old[0] * t1[k] + xi_old[1] * t2[k]
                 : xb[k] - (ya[k] + xi_old[0] * (yb[k] - ya[k]) + xi_old[1] * (yc[k] - ya[k]));
    const D sn = dot(s, n), lnn = dot(lt, n);
    V3 h;
    for (int k = 0; k < 3; ++k)
      h[k] = (lt[k] - lnn * n[k]) + law.rho_t * (s[k] - sn * n[k]);
    const D radius = -law.mu * T_n;
    const D norm = sqrt(dot(h, h) + D(1e-24));
    for (int k = 0; k < 3; ++k)
      Tt[k] = norm.v < radius.v ? h[k] : radius / norm * h[k];
  }
  const D T1 = dot(Tt, t1), T2 = dot(Tt, t2);
  const D f1 = (m22 * T1 - m12 * T2) / det, f2 = (m11 * T2 - m12 * T1) / det;
  const D N1 = 1.0 - xi1 - xi2;
  std::array<D, N> res;
  for (int k = 0; k < 3; ++k)
  {
    const D F = T_n * n[k] + f1 * t1[k] + f2 * t2[k];
    res[k] = w * F;
    res[3 + k] = w * (-N1 * F - g * n[k] * (f1 + f2));
    res[6 + k] = w * (-xi1 * F + g * n[k] * f1);
    res[9 + k] = w * (-xi2 * F + g * n[k] * f2);
  }
  for (int k = 12; k < 21; ++k)
    res[k] = D(0.0);
  res[21] = (w_c / law.rho_n) * T_n;
  for (int k = 0; k < 3; ++k)
    res[22 + k] = law.friction ? (w_c / law.rho_t) * Tt[k] : D(0.0);
  for (int i = 0; i < N; ++i)
  {
    r[i] = res[i].v;
    for (int k = 0; k < N; ++k)
      J[i * N + k] = res[i].d[k];
  }
}

} // namespace tribofx::two_body
