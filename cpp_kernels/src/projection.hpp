// Copyright (C) 2025 tribofx contributors
// SPDX-License-Identifier: MIT
//
// Closest-point projection of points onto a surface mesh of Lagrange facets.
//
// Per (point, facet) pair the minimiser of 1/2 |x - x(xi)|^2 over the reference
// facet is found by
//  1. the interior problem: closed form for affine facets, otherwise Newton
//     (Hessian A = t.t - g.x_,ab, Gauss-Newton fallback if A is not SPD) with
//     each iterate projected onto the reference domain; accepted if it has
//     converged strictly inside the domain to a point with SPD Hessian;
//     abandoned after 3 consecutive iterates on the boundary;
//  2. otherwise (or, for curved facets, if a vertex is closer than that
//     interior minimum) the same 1D problem on every edge of the reference domain
//     (closed form / clamped Newton compared with the end points), keeping
//     the closest edge point.
// The facet search uses an axis-aligned bounding box tree with pruned
// nearest-first traversal. tribofx/projection_ref.py is a NumPy twin of this
// file: any change here must be mirrored there.

#pragma once

#include "bbox_tree.hpp"
#include "elements.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace tribofx::projection
{

using elements::evaluate;

inline constexpr int max_newton_iterations = 50;
inline constexpr double newton_tol = 1e-14;
/// Below this step size a step that does not decrease any more means the
/// round-off floor has been reached: also counted as convergence.
inline constexpr double newton_stall_tol = 1e-8;
/// The interior Newton iteration is abandoned (in favour of the edge search)
/// after this many consecutive iterates on the boundary of the reference facet.
inline constexpr int max_boundary_hits = 3;
inline constexpr double tie_rtol = 1e-12;
inline constexpr double tie_atol = 1e-300;

/// Location of the projection on the reference facet: interior, on edge
/// k >= 0 of the reference domain (strictly between its end points), or at a
/// vertex.
inline constexpr int state_interior = -1;
inline constexpr int state_vertex = -2;

template <std::size_t n>
double dot(const std::array<double, n>& a, const std::array<double, n>& b)
{
  double s = a[0] * b[0];
  for (std::size_t i = 1; i < n; ++i)
    s += a[i] * b[i];
  return s;
}

template <std::size_t n>
std::array<double, n> sub(const std::array<double, n>& a, const std::array<double, n>& b)
{
  std::array<double, n> c;
  for (std::size_t i = 0; i < n; ++i)
    c[i] = a[i] - b[i];
  return c;
}

/// Reference domain of a facet type: centroid, edges as (start, direction).
template <class E>
struct ReferenceDomain;

template <class E>
  requires(E::tdim == 1)
struct ReferenceDomain<E>
{
  static constexpr int num_edges = 0;
};

template <class E>
  requires(E::tdim == 2 && E::simplex)
struct ReferenceDomain<E>
{
  static constexpr int num_edges = 3;
  static constexpr std::array<double, 2> centroid = {1.0 / 3.0, 1.0 / 3.0};
  static constexpr std::array<std::array<double, 2>, 3> vertices = {
      {{0, 0}, {1, 0}, {0, 1}}};
  static constexpr std::array<std::array<double, 2>, 3> start = {
      {{1, 0}, {0, 0}, {0, 0}}};
  static constexpr std::array<std::array<double, 2>, 3> dir = {{{-1, 1}, {0, 1}, {1, 0}}};
  static bool strictly_inside(const std::array<double, 2>& p)
  {
    return p[0] > 0.0 and p[1] > 0.0 and p[0] + p[1] < 1.0;
  }
  /// Euclidean projection onto the reference triangle.
  static std::array<double, 2> project(const std::array<double, 2>& p)
  {
    if (p[0] >= 0.0 and p[1] >= 0.0 and p[0] + p[1] <= 1.0)
      return p;
    std::array<double, 2> best;
    double best_d2 = 0.0;
    for (int k = 0; k < num_edges; ++k)
    {
      const auto& a = start[k];
      const auto& e = dir[k];
      double t =
          ((p[0] - a[0]) * e[0] + (p[1] - a[1]) * e[1]) / (e[0] * e[0] + e[1] * e[1]);
      t = std::clamp(t, 0.0, 1.0);
      const std::array<double, 2> q = {a[0] + t * e[0], a[1] + t * e[1]};
      const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]);
      if (k == 0 or d2 < best_d2)
      {
        best_d2 = d2;
        best = q;
      }
    }
    return best;
  }
};

template <class E>
  requires(E::tdim == 2 && !E::simplex)
struct ReferenceDomain<E>
{
  static constexpr int num_edges = 4;
  static constexpr std::array<double, 2> centroid = {0.5, 0.5};
  static constexpr std::array<std::array<double, 2>, 4> vertices = {
      {{0, 0}, {1, 0}, {0, 1}, {1, 1}}};
  static constexpr std::array<std::array<double, 2>, 4> start = {
      {{0, 0}, {0, 0}, {1, 0}, {0, 1}}};
  static constexpr std::array<std::array<double, 2>, 4> dir = {
      {{1, 0}, {0, 1}, {0, 1}, {1, 0}}};
  static bool strictly_inside(const std::array<double, 2>& p)
  {
    return p[0] > 0.0 and p[0] < 1.0 and p[1] > 0.0 and p[1] < 1.0;
  }
  static std::array<double, 2> project(const std::array<double, 2>& p)
  {
    return {std::clamp(p[0], 0.0, 1.0), std::clamp(p[1], 0.0, 1.0)};
  }
};

/// Tangent along a reference direction e: sum_a e_a t_a.
template <int gdim, int tdim>
std::array<double, gdim> along(const std::array<double, tdim>& e,
                               const std::array<std::array<double, gdim>, tdim>& t)
{
  std::array<double, gdim> te;
  for (int c = 0; c < gdim; ++c)
  {
    te[c] = e[0] * t[0][c];
    for (int a = 1; a < tdim; ++a)
      te[c] += e[a] * t[a][c];
  }
  return te;
}

/// Second derivative along e: sum_a sum_b e_a e_b d_ab.
template <int gdim, int tdim>
std::array<double, gdim>
along2(const std::array<double, tdim>& e,
       const std::array<std::array<std::array<double, gdim>, tdim>, tdim>& d)
{
  std::array<double, gdim> de;
  for (int c = 0; c < gdim; ++c)
  {
    de[c] = (e[0] * e[0]) * d[0][0][c];
    for (int a = 0; a < tdim; ++a)
      for (int b = 0; b < tdim; ++b)
        if (a + b > 0)
          de[c] += (e[a] * e[b]) * d[a][b][c];
  }
  return de;
}

/// Minimise 1/2 |x - x(a + s e)|^2 over s in [0, 1]: closed form for affine
/// facets, clamped Newton from s = 1/2 otherwise (then compared with the end
/// points).
template <class E, int gdim>
double line_minimiser(const std::array<double, gdim>& x, const double* X,
                      const std::array<double, E::tdim>& a,
                      const std::array<double, E::tdim>& e)
{
  constexpr int tdim = E::tdim;
  if constexpr (E::affine)
  {
    const auto geo = evaluate<E, gdim>(X, a);
    const auto te = along<gdim, tdim>(e, geo.t);
    const double s = dot(te, sub(x, geo.x)) / dot(te, te);
    return std::clamp(s, 0.0, 1.0);
  }
  else
  {
    double s = 0.5;
    double prev_step = std::numeric_limits<double>::infinity();
    for (int it = 0; it < max_newton_iterations; ++it)
    {
      std::array<double, tdim> xi;
      for (int k = 0; k < tdim; ++k)
        xi[k] = a[k] + s * e[k];
      const auto geo = evaluate<E, gdim>(X, xi);
      const auto g = sub(x, geo.x);
      const auto te = along<gdim, tdim>(e, geo.t);
      const auto de = along2<gdim, tdim>(e, geo.d);
      const double r = -dot(te, g);
      const double tt = dot(te, te);
      double h = tt - dot(g, de);
      if (!(h > 0.0))
        h = tt;
      if (!(h > 0.0))
        break;
      const double sn = std::clamp(s - r / h, 0.0, 1.0);
      const double step = std::abs(sn - s);
      s = sn;
      if (step <= newton_tol or (step <= newton_stall_tol and step >= prev_step))
        break;
      prev_step = step;
    }
    // Newton may stop at a non-minimal stationary point: keep the best of s
    // and the two end points
    auto dist2 = [&](double sv)
    {
      std::array<double, tdim> xi;
      for (int k = 0; k < tdim; ++k)
        xi[k] = a[k] + sv * e[k];
      const auto g = sub(x, evaluate<E, gdim>(X, xi).x);
      return dot(g, g);
    };
    const double ds = dist2(s);
    const double d0 = dist2(0.0);
    const double d1 = dist2(1.0);
    if (d0 < ds and d0 <= d1)
      return 0.0;
    if (d1 < ds)
      return 1.0;
    return s;
  }
}

/// Result of projecting one point onto one facet.
template <int tdim>
struct FacetPoint
{
  std::array<double, tdim> xi;
  int state;
  double dist2;
};

/// Closest point on one facet (node coordinates X) to x.
template <class E, int gdim>
FacetPoint<E::tdim> project_onto_facet(const std::array<double, gdim>& x, const double* X)
{
  constexpr int tdim = E::tdim;
  FacetPoint<tdim> fp;
  if constexpr (tdim == 1)
  {
    const double s = line_minimiser<E, gdim>(x, X, {0.0}, {1.0});
    fp.xi = {s};
    fp.state = (s > 0.0 and s < 1.0) ? state_interior : state_vertex;
  }
  else
  {
    using Ref = ReferenceDomain<E>;
    bool found = false;
    std::array<double, 2> xi;
    if constexpr (E::affine)
    {
      const auto geo = evaluate<E, gdim>(X, {0.0, 0.0});
      const auto r = sub(x, geo.x);
      const double b0 = dot(geo.t[0], r);
      const double b1 = dot(geo.t[1], r);
      const double G00 = dot(geo.t[0], geo.t[0]);
      const double G01 = dot(geo.t[0], geo.t[1]);
      const double G11 = dot(geo.t[1], geo.t[1]);
      const double det = G00 * G11 - G01 * G01;
      xi = {(G11 * b0 - G01 * b1) / det, (G00 * b1 - G01 * b0) / det};
      found = Ref::strictly_inside(xi);
    }
    else
    {
      xi = Ref::centroid;
      bool converged = false;
      int boundary_hits = 0;
      bool spd = false;
      double prev_step = std::numeric_limits<double>::infinity();
      for (int it = 0; it < max_newton_iterations; ++it)
      {
        const auto geo = evaluate<E, gdim>(X, xi);
        const auto g = sub(x, geo.x);
        const double r0 = -dot(geo.t[0], g);
        const double r1 = -dot(geo.t[1], g);
        const double G00 = dot(geo.t[0], geo.t[0]);
        const double G01 = dot(geo.t[0], geo.t[1]);
        const double G11 = dot(geo.t[1], geo.t[1]);
        double H00 = G00 - dot(g, geo.d[0][0]);
        double H01 = G01 - dot(g, geo.d[0][1]);
        double H11 = G11 - dot(g, geo.d[1][1]);
        double det = H00 * H11 - H01 * H01;
        spd = H00 > 0.0 and det > 0.0;
        if (!spd)
        {
          H00 = G00;
          H01 = G01;
          H11 = G11;
          det = H00 * H11 - H01 * H01;
          if (!(det > 0.0))
            break;
        }
        const double d0 = -(H11 * r0 - H01 * r1) / det;
        const double d1 = -(H00 * r1 - H01 * r0) / det;
        const auto xn = Ref::project({xi[0] + d0, xi[1] + d1});
        const double step = std::max(std::abs(xn[0] - xi[0]), std::abs(xn[1] - xi[1]));
        xi = xn;
        if (step <= newton_tol or (step <= newton_stall_tol and step >= prev_step))
        {
          converged = true;
          break;
        }
        prev_step = step;
        // The minimiser is on the boundary: leave it to the edge search
        boundary_hits = Ref::strictly_inside(xi) ? 0 : boundary_hits + 1;
        if (boundary_hits == max_boundary_hits)
          break;
      }
      // Only a local minimum (positive definite Hessian) is accepted
      found = converged and spd and Ref::strictly_inside(xi);
    }

    fp.state = state_interior;
    bool search_edges = !found;
    double best = 0.0;
    if constexpr (!E::affine)
    {
      // A curved facet may have several local minima: if a vertex is closer
      // than the interior minimum, search the edges as well
      if (found)
      {
        const auto g = sub(x, evaluate<E, gdim>(X, xi).x);
        best = dot(g, g);
        for (const auto& v : Ref::vertices)
        {
          const auto gv = sub(x, evaluate<E, gdim>(X, v).x);
          search_edges = search_edges or dot(gv, gv) < best;
        }
      }
    }
    if (search_edges)
    {
      for (int k = 0; k < Ref::num_edges; ++k)
      {
        const auto& a = Ref::start[k];
        const auto& e = Ref::dir[k];
        const double s = line_minimiser<E, gdim>(x, X, a, e);
        const std::array<double, 2> xe = {a[0] + s * e[0], a[1] + s * e[1]};
        const auto g = sub(x, evaluate<E, gdim>(X, xe).x);
        const double d2 = dot(g, g);
        if ((k == 0 and !found) or d2 < best)
        {
          best = d2;
          xi = xe;
          fp.state = (s > 0.0 and s < 1.0) ? k : state_vertex;
        }
      }
    }
    fp.xi = xi;
  }
  const auto g = sub(x, evaluate<E, gdim>(X, fp.xi).x);
  fp.dist2 = dot(g, g);
  return fp;
}

/// True if a facet at distance d ties with (or beats) the current minimum
/// dmin under the relative tolerance tie_rtol.
inline bool ties(double d, double dmin)
{
  return dmin >= d * (1.0 - tie_rtol) - tie_atol;
}

/// Output arrays, row-major, packed as documented in tribofx/projection.py.
struct ProjectionOutput
{
  std::vector<std::int32_t> facet;
  std::vector<double> xi, x_bar, gap, normal, tangents, dxi_dx, dxbar_dx, dn_dx,
      curvature;
  std::vector<std::uint8_t> inside;
  std::vector<double> distance;

  void resize(std::size_t n, int gdim, int tdim)
  {
    facet.resize(n);
    xi.resize(n * tdim);
    x_bar.resize(n * gdim);
    gap.resize(n);
    normal.resize(n * gdim);
    tangents.resize(n * tdim * gdim);
    dxi_dx.resize(n * tdim * gdim);
    dxbar_dx.resize(n * gdim * gdim);
    dn_dx.resize(n * gdim * gdim);
    curvature.resize(n * tdim * tdim);
    inside.resize(n);
    distance.resize(n);
  }
};

/// Fill row p of the output with NaN and facet -1 (no valid facet).
inline void write_undefined(std::size_t p, int gdim, int tdim, ProjectionOutput& out)
{
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  auto fill = [p, nan](std::vector<double>& v, std::size_t size)
  { std::fill_n(v.begin() + p * size, size, nan); };
  out.facet[p] = -1;
  out.inside[p] = 0;
  fill(out.xi, tdim);
  fill(out.x_bar, gdim);
  fill(out.gap, 1);
  fill(out.normal, gdim);
  fill(out.tangents, tdim * gdim);
  fill(out.dxi_dx, tdim * gdim);
  fill(out.dxbar_dx, gdim * gdim);
  fill(out.dn_dx, gdim * gdim);
  fill(out.curvature, tdim * tdim);
  fill(out.distance, 1);
}

/// Fill row p of the output for point x projected onto the facet with node
/// coordinates X at reference point xi with location state.
template <class E, int gdim>
void write_result(std::size_t p, const std::array<double, gdim>& x, const double* X,
                  std::int32_t facet, const std::array<double, E::tdim>& xi, int state,
                  ProjectionOutput& out)
{
  constexpr int tdim = E::tdim;
  const auto geo = evaluate<E, gdim>(X, xi);
  const auto g = sub(x, geo.x);
  const auto& t = geo.t;
  const auto& d = geo.d;

  // Unnormalised normal m, n = m / |m|, and dm/dxi_a
  std::array<double, gdim> m;
  std::array<std::array<double, gdim>, tdim> dm;
  if constexpr (gdim == 2)
  {
    m = {t[0][1], -t[0][0]};
    dm[0] = {d[0][0][1], -d[0][0][0]};
  }
  else
  {
    auto cross = [](const std::array<double, 3>& u, const std::array<double, 3>& v)
    {
      return std::array<double, 3>{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                   u[0] * v[1] - u[1] * v[0]};
    };
    for (int a = 0; a < tdim; ++a)
    {
      const auto c0 = cross(d[0][a], t[1]);
      const auto c1 = cross(t[0], d[1][a]);
      for (int c = 0; c < gdim; ++c)
        dm[a][c] = c0[c] + c1[c];
    }
    m = cross(t[0], t[1]);
  }
  const double mnorm = std::sqrt(dot(m, m));
  std::array<double, gdim> n;
  for (int c = 0; c < gdim; ++c)
    n[c] = m[c] / mnorm;
  // dn/dxi_a = (I - n n^T) dm_a / |m|
  std::array<std::array<double, gdim>, tdim> dn;
  for (int a = 0; a < tdim; ++a)
  {
    const double nd = dot(n, dm[a]);
    for (int c = 0; c < gdim; ++c)
      dn[a][c] = (dm[a][c] - n[c] * nd) / mnorm;
  }

  // dxi/dx (rows a): interior, restricted to an edge, or zero at a vertex
  std::array<std::array<double, gdim>, tdim> dxi{};
  if (state == state_interior)
  {
    if constexpr (tdim == 1)
    {
      const double A = dot(t[0], t[0]) - dot(g, d[0][0]);
      for (int c = 0; c < gdim; ++c)
        dxi[0][c] = t[0][c] / A;
    }
    else
    {
      const double A00 = dot(t[0], t[0]) - dot(g, d[0][0]);
      const double A01 = dot(t[0], t[1]) - dot(g, d[0][1]);
      const double A11 = dot(t[1], t[1]) - dot(g, d[1][1]);
      const double det = A00 * A11 - A01 * A01;
      const double i00 = A11 / det;
      const double i01 = -A01 / det;
      const double i11 = A00 / det;
      for (int c = 0; c < gdim; ++c)
      {
        dxi[0][c] = i00 * t[0][c] + i01 * t[1][c];
        dxi[1][c] = i01 * t[0][c] + i11 * t[1][c];
      }
    }
  }
  else if (state >= 0)
  {
    if constexpr (tdim == 2)
    {
      const auto& e = ReferenceDomain<E>::dir[state];
      const auto te = along<gdim, tdim>(e, t);
      const auto de = along2<gdim, tdim>(e, d);
      const double A = dot(te, te) - dot(g, de);
      for (int c = 0; c < gdim; ++c)
      {
        const double ds = te[c] / A;
        dxi[0][c] = e[0] * ds;
        dxi[1][c] = e[1] * ds;
      }
    }
  }

  out.facet[p] = facet;
  out.inside[p] = (state == state_interior) ? 1 : 0;
  out.gap[p] = dot(g, n);
  out.distance[p] = std::sqrt(dot(g, g));
  for (int a = 0; a < tdim; ++a)
    out.xi[p * tdim + a] = xi[a];
  for (int c = 0; c < gdim; ++c)
  {
    out.x_bar[p * gdim + c] = geo.x[c];
    out.normal[p * gdim + c] = n[c];
  }
  for (int a = 0; a < tdim; ++a)
  {
    for (int c = 0; c < gdim; ++c)
    {
      out.tangents[(p * tdim + a) * gdim + c] = t[a][c];
      out.dxi_dx[(p * tdim + a) * gdim + c] = dxi[a][c];
    }
    for (int b = 0; b < tdim; ++b)
      out.curvature[(p * tdim + a) * tdim + b] = dot(n, d[a][b]);
  }
  for (int i = 0; i < gdim; ++i)
  {
    for (int j = 0; j < gdim; ++j)
    {
      double sx = t[0][i] * dxi[0][j];
      double sn = dn[0][i] * dxi[0][j];
      for (int a = 1; a < tdim; ++a)
      {
        sx += t[a][i] * dxi[a][j];
        sn += dn[a][i] * dxi[a][j];
      }
      out.dxbar_dx[(p * gdim + i) * gdim + j] = sx;
      out.dn_dx[(p * gdim + i) * gdim + j] = sn;
    }
  }
}

/// Project every point (row-major, n x gdim) onto the surface mesh given by
/// nodes (nv x gdim) and facets (nf x num_nodes). Inputs must be validated.
template <class E, int gdim>
ProjectionOutput project_points(std::span<const double> points,
                                std::span<const double> nodes,
                                std::span<const std::int32_t> facets)
{
  constexpr int nn = E::num_nodes;
  constexpr int tdim = E::tdim;
  const std::size_t n = points.size() / gdim;
  const std::size_t nf = facets.size() / nn;

  // Gather facet coordinates once
  std::vector<double> coords(nf * nn * gdim);
  for (std::size_t f = 0; f < nf; ++f)
    for (int i = 0; i < nn; ++i)
      for (int c = 0; c < gdim; ++c)
        coords[(f * nn + i) * gdim + c] = nodes[facets[f * nn + i] * gdim + c];

  std::vector<double> boxes(nf * 2 * gdim);
  for (std::size_t f = 0; f < nf; ++f)
  {
    const auto b = elements::facet_box<E, gdim>(coords.data() + f * nn * gdim);
    std::copy(b.begin(), b.end(), boxes.begin() + f * 2 * gdim);
  }
  const geometry::BoxTree<gdim> tree(boxes);

  struct Candidate
  {
    double d;
    std::int32_t facet;
    FacetPoint<tdim> fp;
  };
  std::vector<Candidate> candidates;

  ProjectionOutput out;
  out.resize(n, gdim, tdim);
  for (std::size_t p = 0; p < n; ++p)
  {
    std::array<double, gdim> x;
    std::copy_n(points.data() + p * gdim, gdim, x.begin());

    double dmin = std::numeric_limits<double>::infinity();
    candidates.clear();
    tree.nearest_search(
        x.data(), dmin,
        [&](std::int32_t f)
        {
          const auto fp = project_onto_facet<E, gdim>(x, coords.data() + f * nn * gdim);
          const double d = std::sqrt(fp.dist2);
          if (d < dmin)
          {
            dmin = d;
            std::erase_if(candidates,
                          [dmin](const Candidate& c) { return !ties(c.d, dmin); });
          }
          if (ties(d, dmin))
            candidates.push_back({d, f, fp});
        });

    if (candidates.empty())
    {
      // Only possible for degenerate facets (all distances NaN)
      write_undefined(p, gdim, tdim, out);
      continue;
    }
    // Lowest facet index among those tying with the minimum distance
    const auto best = std::ranges::min_element(candidates, {}, &Candidate::facet);
    write_result<E, gdim>(p, x, coords.data() + best->facet * nn * gdim, best->facet,
                          best->fp.xi, best->fp.state, out);
  }
  return out;
}

} // namespace tribofx::projection
