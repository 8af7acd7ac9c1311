// Copyright (C) 2025 tribofx contributors
// SPDX-License-Identifier: MIT
//
// Lubrication-surface projection y = P(x) onto a meshed countersurface, with
// the data an exact Newton tangent of the film thickness h = (x - y).nu and of
// the surface map needs.
//
// The closest point, its normal nu, dP/dx (= dxbar/dx) and dnu/dx come from
// projection::project_points (closest-point machinery, not duplicated here).
// This file adds, per point:
//   dh/dx_j = nu_j + g_i dnu_i/dx_j - nu_i dy_i/dx_j        (g = x - y)
//           (= nu for an interior projection),
//   d2h/dx2 = dnu/dx (exact for interior and vertex projections),
//   d2y_i/dx_j dx_k by differentiating dy/dx = t_a Xi_a, Xi = A^-1 t,
//           A_ab = t_a.t_b - g.x_,ab, whose derivative carries the third
//           derivatives of the facet map (nonzero for quadrilateral9 only).
// tribofx/lubrication_projection_ref.py is a NumPy twin of this file: any
// change here must be mirrored there.

#pragma once

#include "projection.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace tribofx::lubrication
{

/// Output arrays, row-major, packed as documented in
/// tribofx/lubrication_projection.py.
struct LubricationOutput
{
  projection::ProjectionOutput proj;
  std::vector<double> dh_dx, d2h_dx2, d2y_dx2;
};

/// Second derivative d2y_i/dx_j dx_k (row-major [i][j][k]) of the projection
/// onto the facet with node coordinates X, interior point xi.
template <class E, int gdim>
std::array<double, gdim * gdim * gdim>
second_derivative(const std::array<double, gdim>& x, const double* X,
                  const std::array<double, E::tdim>& xi)
{
  constexpr int tdim = E::tdim;
  const auto geo = elements::evaluate<E, gdim>(X, xi);
  const auto g = projection::sub(x, geo.x);
  const auto& t = geo.t;
  const auto& d = geo.d;
  const auto d3 = elements::third_derivatives<E, gdim>(X, xi);

  // A^-1
  std::array<std::array<double, tdim>, tdim> Ai;
  if constexpr (tdim == 1)
    Ai[0][0] = 1.0 / (projection::dot(t[0], t[0]) - projection::dot(g, d[0][0]));
  else
  {
    const double A00 = projection::dot(t[0], t[0]) - projection::dot(g, d[0][0]);
    const double A01 = projection::dot(t[0], t[1]) - projection::dot(g, d[0][1]);
    const double A11 = projection::dot(t[1], t[1]) - projection::dot(g, d[1][1]);
    const double det = A00 * A11 - A01 * A01;
    Ai = {{{A11 / det, -A01 / det}, {-A01 / det, A00 / det}}};
  }
  // Xi[a][j] = dxi_a/dx_j
  std::array<std::array<double, gdim>, tdim> Xi{};
  for (int a = 0; a < tdim; ++a)
    for (int b = 0; b < tdim; ++b)
      for (int j = 0; j < gdim; ++j)
        Xi[a][j] += Ai[a][b] * t[b][j];
  // dt[b][m][k] = dt_b,m/dx_k = x_,bd,m Xi_dk
  std::array<std::array<std::array<double, gdim>, gdim>, tdim> dt{};
  for (int b = 0; b < tdim; ++b)
    for (int m = 0; m < gdim; ++m)
      for (int k = 0; k < gdim; ++k)
        for (int e = 0; e < tdim; ++e)
          dt[b][m][k] += d[b][e][m] * Xi[e][k];
  // dA[b][c][k] = dt_b.t_c + t_b.dt_c - dg.x_,bc - g.x_,bce Xi_ek
  // (dg_m/dx_k = delta_mk - t_em Xi_ek)
  std::array<std::array<std::array<double, gdim>, tdim>, tdim> dA{};
  for (int b = 0; b < tdim; ++b)
    for (int c = 0; c < tdim; ++c)
      for (int k = 0; k < gdim; ++k)
        for (int m = 0; m < gdim; ++m)
        {
          double dg = (m == k) ? 1.0 : 0.0;
          for (int e = 0; e < tdim; ++e)
            dg -= t[e][m] * Xi[e][k];
          dA[b][c][k] += dt[b][m][k] * t[c][m] + t[b][m] * dt[c][m][k] - dg * d[b][c][m];
          for (int e = 0; e < tdim; ++e)
            dA[b][c][k] -= g[m] * d3[b][c][e][m] * Xi[e][k];
        }
  // dAi = -A^-1 dA A^-1
  std::array<std::array<std::array<double, gdim>, tdim>, tdim> dAi{};
  for (int a = 0; a < tdim; ++a)
    for (int b = 0; b < tdim; ++b)
      for (int k = 0; k < gdim; ++k)
        for (int c = 0; c < tdim; ++c)
          for (int e = 0; e < tdim; ++e)
            dAi[a][b][k] -= Ai[a][c] * dA[c][e][k] * Ai[e][b];
  // dXi[a][j][k] = dAi_ab,k t_bj + Ai_ab dt_bj,k
  std::array<std::array<std::array<double, gdim>, gdim>, tdim> dXi{};
  for (int a = 0; a < tdim; ++a)
    for (int j = 0; j < gdim; ++j)
      for (int k = 0; k < gdim; ++k)
        for (int b = 0; b < tdim; ++b)
          dXi[a][j][k] += dAi[a][b][k] * t[b][j] + Ai[a][b] * dt[b][j][k];
  // d2y[i][j][k] = dt_a,i/dx_k Xi_aj + t_ai dXi_aj,k
  std::array<double, gdim * gdim * gdim> out{};
  for (int i = 0; i < gdim; ++i)
    for (int j = 0; j < gdim; ++j)
      for (int k = 0; k < gdim; ++k)
      {
        double s = 0.0;
        for (int a = 0; a < tdim; ++a)
          s += dt[a][i][k] * Xi[a][j] + t[a][i] * dXi[a][j][k];
        out[(i * gdim + j) * gdim + k] = s;
      }
  return out;
}

/// Project every point (n x gdim) onto the surface mesh (nodes, facets) and
/// add the film-thickness data. Inputs must be validated.
template <class E, int gdim>
LubricationOutput lubrication_points(std::span<const double> points,
                                     std::span<const double> nodes,
                                     std::span<const std::int32_t> facets)
{
  constexpr int nn = E::num_nodes;
  constexpr int tdim = E::tdim;
  constexpr int g2 = gdim * gdim;
  constexpr int g3 = gdim * gdim * gdim;
  const std::size_t n = points.size() / gdim;

  LubricationOutput out;
  out.proj = projection::project_points<E, gdim>(points, nodes, facets);
  const auto& pr = out.proj;
  out.dh_dx.assign(n * gdim, 0.0);
  out.d2h_dx2.assign(n * g2, 0.0);
  out.d2y_dx2.assign(n * g3, 0.0);
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t p = 0; p < n; ++p)
  {
    const std::int32_t f = pr.facet[p];
    if (f < 0)
    {
      std::fill_n(out.dh_dx.begin() + p * gdim, gdim, nan);
      std::fill_n(out.d2h_dx2.begin() + p * g2, g2, nan);
      std::fill_n(out.d2y_dx2.begin() + p * g3, g3, nan);
      continue;
    }
    std::array<double, gdim> x;
    std::copy_n(points.data() + p * gdim, gdim, x.begin());
    const double* nu = pr.normal.data() + p * gdim;
    const double* y = pr.x_bar.data() + p * gdim;
    const double* dy = pr.dxbar_dx.data() + p * g2;
    const double* dnu = pr.dn_dx.data() + p * g2;
    for (int j = 0; j < gdim; ++j)
    {
      double s = nu[j];
      for (int i = 0; i < gdim; ++i)
        s += (x[i] - y[i]) * dnu[i * gdim + j] - nu[i] * dy[i * gdim + j];
      out.dh_dx[p * gdim + j] = s;
    }
    std::copy_n(dnu, g2, out.d2h_dx2.begin() + p * g2);
    if (pr.inside[p])
    {
      std::array<double, nn * gdim> X;
      for (int i = 0; i < nn; ++i)
        for (int c = 0; c < gdim; ++c)
          X[i * gdim + c] = nodes[facets[f * nn + i] * gdim + c];
      std::array<double, tdim> xi;
      std::copy_n(pr.xi.data() + p * tdim, tdim, xi.begin());
      const auto d2y = second_derivative<E, gdim>(x, X.data(), xi);
      std::copy(d2y.begin(), d2y.end(), out.d2y_dx2.begin() + p * g3);
    }
  }
  return out;
}

} // namespace tribofx::lubrication
