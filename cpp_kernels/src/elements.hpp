// Copyright (C) 2025 tribofx contributors
// SPDX-License-Identifier: MIT
//
// Lagrange surface elements (facets) used by the closest-point projection:
// shape functions with first and second reference derivatives, evaluation of
// the facet geometry x(xi), dx/dxi, d2x/dxi2, and a bounding box that provably
// encloses the (possibly curved) facet.
//
// Node ordering follows basix/DOLFINx. The arithmetic is written in a fixed
// order that tribofx/projection_ref.py mirrors operation by operation.

#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

namespace tribofx::elements
{

/// Shape function values and first/second derivatives at one reference point.
template <int tdim, int nn>
struct Tabulation
{
  std::array<double, nn> N{};
  std::array<std::array<double, nn>, tdim> dN{};
  std::array<std::array<std::array<double, nn>, tdim>, tdim> d2N{};
};

/// 1D Lagrange P1 on [0, 1], nodes (0, 1).
struct LagrangeLine1
{
  static constexpr int n = 2;
  static void eval(double t, std::array<double, n>& f, std::array<double, n>& df,
                   std::array<double, n>& d2f)
  {
    f = {1.0 - t, t};
    df = {-1.0, 1.0};
    d2f = {0.0, 0.0};
  }
};

/// 1D Lagrange P2 on [0, 1], nodes (0, 1, 1/2).
struct LagrangeLine2
{
  static constexpr int n = 3;
  static void eval(double t, std::array<double, n>& f, std::array<double, n>& df,
                   std::array<double, n>& d2f)
  {
    f = {(1.0 - t) * (1.0 - 2.0 * t), t * (2.0 * t - 1.0), 4.0 * t * (1.0 - t)};
    df = {4.0 * t - 3.0, 4.0 * t - 1.0, 4.0 - 8.0 * t};
    d2f = {4.0, 4.0, -8.0};
  }
};

/// Interval facets (curves in 2D): "interval" (P1) and "interval3" (P2).
template <class Line>
struct Interval
{
  static constexpr int tdim = 1;
  static constexpr int num_nodes = Line::n;
  static constexpr bool affine = (Line::n == 2);
  static constexpr bool simplex = true;

  static Tabulation<1, num_nodes> tabulate(const std::array<double, 1>& xi)
  {
    Tabulation<1, num_nodes> tab;
    std::array<double, num_nodes> d2f;
    Line::eval(xi[0], tab.N, tab.dN[0], d2f);
    tab.d2N[0][0] = d2f;
    return tab;
  }
};

/// Triangle facets: "triangle" (P1, k = 3).
struct Triangle3
{
  static constexpr int tdim = 2;
  static constexpr int num_nodes = 3;
  static constexpr bool affine = true;
  static constexpr bool simplex = true;

  static Tabulation<2, 3> tabulate(const std::array<double, 2>& xi)
  {
    const double s = xi[0];
    const double t = xi[1];
    Tabulation<2, 3> tab;
    tab.N = {1.0 - s - t, s, t};
    tab.dN[0] = {-1.0, 1.0, 0.0};
    tab.dN[1] = {-1.0, 0.0, 1.0};
    return tab;
  }
};

/// Triangle facets: "triangle6" (P2, k = 6). Edge nodes in basix order:
/// edge0 = (v1, v2), edge1 = (v0, v2), edge2 = (v0, v1).
struct Triangle6
{
  static constexpr int tdim = 2;
  static constexpr int num_nodes = 6;
  static constexpr bool affine = false;
  static constexpr bool simplex = true;

  static Tabulation<2, 6> tabulate(const std::array<double, 2>& xi)
  {
    const double s = xi[0];
    const double t = xi[1];
    const double l0 = 1.0 - s - t;
    Tabulation<2, 6> tab;
    tab.N = {l0 * (2.0 * l0 - 1.0), s * (2.0 * s - 1.0), t * (2.0 * t - 1.0),
             4.0 * s * t,           4.0 * t * l0,        4.0 * s * l0};
    tab.dN[0] = {1.0 - 4.0 * l0, 4.0 * s - 1.0, 0.0, 4.0 * t, -4.0 * t, 4.0 * (l0 - s)};
    tab.dN[1] = {1.0 - 4.0 * l0, 0.0, 4.0 * t - 1.0, 4.0 * s, 4.0 * (l0 - t), -4.0 * s};
    tab.d2N[0][0] = {4.0, 4.0, 0.0, 0.0, 0.0, -8.0};
    tab.d2N[0][1] = {4.0, 0.0, 0.0, 4.0, -4.0, -4.0};
    tab.d2N[1][0] = tab.d2N[0][1];
    tab.d2N[1][1] = {4.0, 0.0, 4.0, 0.0, -8.0, 0.0};
    return tab;
  }
};

/// Tensor-product quadrilateral facets: "quadrilateral" (Q1) and
/// "quadrilateral9" (Q2). Node i is the product of the 1D basis functions
/// (a_i in xi0) x (b_i in xi1), with 1D node indices 0 -> 0, 1 -> 1, 2 -> 1/2.
template <class Line>
struct Quadrilateral
{
  static constexpr int tdim = 2;
  static constexpr int num_nodes = Line::n * Line::n;
  static constexpr bool affine = false;
  static constexpr bool simplex = false;

  using line = Line;
  static constexpr std::array<std::array<int, 2>, 9> ab = {
      {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 0}, {0, 2}, {1, 2}, {2, 1}, {2, 2}}};

  static Tabulation<2, num_nodes> tabulate(const std::array<double, 2>& xi)
  {
    std::array<double, Line::n> f, df, d2f, g, dg, d2g;
    Line::eval(xi[0], f, df, d2f);
    Line::eval(xi[1], g, dg, d2g);
    Tabulation<2, num_nodes> tab;
    for (int i = 0; i < num_nodes; ++i)
    {
      const int a = ab[i][0];
      const int b = ab[i][1];
      tab.N[i] = f[a] * g[b];
      tab.dN[0][i] = df[a] * g[b];
      tab.dN[1][i] = f[a] * dg[b];
      tab.d2N[0][0][i] = d2f[a] * g[b];
      tab.d2N[0][1][i] = df[a] * dg[b];
      tab.d2N[1][0][i] = df[a] * dg[b];
      tab.d2N[1][1][i] = f[a] * d2g[b];
    }
    return tab;
  }
};

using Interval2 = Interval<LagrangeLine1>;
using Interval3 = Interval<LagrangeLine2>;
using Quadrilateral4 = Quadrilateral<LagrangeLine1>;
using Quadrilateral9 = Quadrilateral<LagrangeLine2>;

/// Facet geometry at one reference point: x, tangents t[a] = dx/dxi_a and
/// second derivatives d[a][b] = d2x/dxi_a dxi_b.
template <int gdim, int tdim>
struct Geometry
{
  std::array<double, gdim> x{};
  std::array<std::array<double, gdim>, tdim> t{};
  std::array<std::array<std::array<double, gdim>, tdim>, tdim> d{};
};

/// Evaluate the geometry of a facet with node coordinates X (row-major,
/// num_nodes x gdim) at the reference point xi. Sums run over nodes in order.
template <class E, int gdim>
Geometry<gdim, E::tdim> evaluate(const double* X, const std::array<double, E::tdim>& xi)
{
  constexpr int tdim = E::tdim;
  const auto tab = E::tabulate(xi);
  Geometry<gdim, tdim> geo;
  for (int i = 0; i < E::num_nodes; ++i)
  {
    const double* Xi = X + i * gdim;
    for (int c = 0; c < gdim; ++c)
      geo.x[c] += tab.N[i] * Xi[c];
    for (int a = 0; a < tdim; ++a)
      for (int c = 0; c < gdim; ++c)
        geo.t[a][c] += tab.dN[a][i] * Xi[c];
    for (int a = 0; a < tdim; ++a)
      for (int b = 0; b < tdim; ++b)
        for (int c = 0; c < gdim; ++c)
          geo.d[a][b][c] += tab.d2N[a][b][i] * Xi[c];
  }
  return geo;
}

/// Third derivatives d3[a][b][c] = d3x/dxi_a dxi_b dxi_c of a facet map at xi.
/// Zero for intervals and triangles (at most quadratic); a tensor-product
/// quadrilateral is at most quadratic in each coordinate, so only the mixed
/// x_,001 (and permutations) and x_,011 remain (nonzero for quadrilateral9).
template <class E, int gdim>
std::array<std::array<std::array<std::array<double, gdim>, E::tdim>, E::tdim>, E::tdim>
third_derivatives(const double* X, const std::array<double, E::tdim>& xi)
{
  std::array<std::array<std::array<std::array<double, gdim>, E::tdim>, E::tdim>, E::tdim> d3{};
  if constexpr (E::tdim == 2 && !E::simplex)
  {
    using Line = typename E::line;
    std::array<double, Line::n> f, df, d2f, g, dg, d2g;
    Line::eval(xi[0], f, df, d2f);
    Line::eval(xi[1], g, dg, d2g);
    std::array<double, gdim> x001{}, x011{};
    for (int i = 0; i < E::num_nodes; ++i)
    {
      const int a = E::ab[i][0];
      const int b = E::ab[i][1];
      for (int c = 0; c < gdim; ++c)
      {
        x001[c] += d2f[a] * dg[b] * X[i * gdim + c];
        x011[c] += df[a] * d2g[b] * X[i * gdim + c];
      }
    }
    d3[0][0][1] = d3[0][1][0] = d3[1][0][0] = x001;
    d3[0][1][1] = d3[1][0][1] = d3[1][1][0] = x011;
  }
  return d3;
}

/// Bounding box [lo_0..lo_{g-1}, hi_0..hi_{g-1}] of a facet. For quadratic
/// facets the box of the Bernstein control points is used (convex-hull
/// property), so the curved facet is enclosed exactly; the box is padded by
/// 1e-10 of its diagonal to absorb round-off.
template <class E, int gdim>
std::array<double, 2 * gdim> facet_box(const double* X)
{
  constexpr int nn = E::num_nodes;
  std::array<std::array<double, gdim>, nn> cp;
  for (int i = 0; i < nn; ++i)
    for (int c = 0; c < gdim; ++c)
      cp[i][c] = X[i * gdim + c];

  // Bernstein control point of a P2 edge with end nodes a, b, midside node m
  auto edge_cp = [X](int a, int b, int m, int c)
  { return 2.0 * X[m * gdim + c] - 0.5 * (X[a * gdim + c] + X[b * gdim + c]); };
  if constexpr (std::is_same_v<E, Interval3>)
  {
    for (int c = 0; c < gdim; ++c)
      cp[2][c] = edge_cp(0, 1, 2, c);
  }
  else if constexpr (std::is_same_v<E, Triangle6>)
  {
    for (int c = 0; c < gdim; ++c)
    {
      cp[3][c] = edge_cp(1, 2, 3, c);
      cp[4][c] = edge_cp(0, 2, 4, c);
      cp[5][c] = edge_cp(0, 1, 5, c);
    }
  }
  else if constexpr (std::is_same_v<E, Quadrilateral9>)
  {
    for (int c = 0; c < gdim; ++c)
    {
      auto x = [X, c](int i) { return X[i * gdim + c]; };
      cp[4][c] = edge_cp(0, 1, 4, c);
      cp[5][c] = edge_cp(0, 2, 5, c);
      cp[6][c] = edge_cp(1, 3, 6, c);
      cp[7][c] = edge_cp(2, 3, 7, c);
      cp[8][c] =
          4.0 * x(8) - (x(4) + x(5) + x(6) + x(7)) + 0.25 * (x(0) + x(1) + x(2) + x(3));
    }
  }

  std::array<double, 2 * gdim> box;
  for (int c = 0; c < gdim; ++c)
  {
    box[c] = cp[0][c];
    box[gdim + c] = cp[0][c];
    for (int i = 1; i < nn; ++i)
    {
      box[c] = std::min(box[c], cp[i][c]);
      box[gdim + c] = std::max(box[gdim + c], cp[i][c]);
    }
  }
  double diag2 = 0.0;
  for (int c = 0; c < gdim; ++c)
    diag2 += (box[gdim + c] - box[c]) * (box[gdim + c] - box[c]);
  const double pad = 1e-10 * std::sqrt(diag2);
  for (int c = 0; c < gdim; ++c)
  {
    box[c] -= pad;
    box[gdim + c] += pad;
  }
  return box;
}

} // namespace tribofx::elements
