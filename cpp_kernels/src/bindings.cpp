// Copyright (C) 2025 tribofx contributors
// SPDX-License-Identifier: MIT
//
// nanobind module tribofx._cpp

#include "lubrication.hpp"
#include "petsc_insert.hpp"
#include "projection.hpp"
#include "two_body.hpp"
#include "two_body_3d.hpp"
#include "two_body_film.hpp"

#include <cstdint>
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace nb = nanobind;
using namespace nb::literals;

namespace
{

template <typename T>
using CArray2 = nb::ndarray<const T, nb::ndim<2>, nb::c_contig, nb::device::cpu>;

/// Hand a std::vector over to NumPy without copying.
template <typename T, typename S = T>
nb::ndarray<nb::numpy, T> to_numpy(std::vector<S>&& v,
                                   std::initializer_list<std::size_t> shape)
{
  static_assert(sizeof(T) == sizeof(S));
  auto* data = new std::vector<S>(std::move(v));
  nb::capsule owner(data,
                    [](void* p) noexcept { delete static_cast<std::vector<S>*>(p); });
  return nb::ndarray<nb::numpy, T>(reinterpret_cast<T*>(data->data()), shape.size(),
                                   shape.begin(), owner);
}

/// Validate shapes and node indices; returns the facet connectivity span.
template <class E, int gdim>
std::span<const std::int32_t> check_inputs(const CArray2<double>& points,
                                           const CArray2<double>& nodes,
                                           const CArray2<std::int32_t>& facets)
{
  const std::size_t nv = nodes.shape(0);
  const std::size_t nf = facets.shape(0);
  if (points.shape(1) != gdim or nodes.shape(1) != gdim)
    throw std::invalid_argument("points and nodes must have shape (., " +
                                std::to_string(gdim) + ") for this cell type");
  if (facets.shape(1) != static_cast<std::size_t>(E::num_nodes))
    throw std::invalid_argument("facets must have " + std::to_string(E::num_nodes) +
                                " nodes per facet for this cell type");
  if (nf == 0)
    throw std::invalid_argument("the surface mesh has no facets");
  std::span<const std::int32_t> f(facets.data(), nf * E::num_nodes);
  if (std::ranges::any_of(f, [nv](std::int32_t i)
                          { return i < 0 or static_cast<std::size_t>(i) >= nv; }))
    throw std::invalid_argument("facet node index out of range");
  return f;
}

template <class E, int gdim>
nb::dict project(const CArray2<double>& points, const CArray2<double>& nodes,
                 const CArray2<std::int32_t>& facets)
{
  constexpr int tdim = E::tdim;
  const std::size_t n = points.shape(0);
  const std::size_t nv = nodes.shape(0);
  const auto f = check_inputs<E, gdim>(points, nodes, facets);

  tribofx::projection::ProjectionOutput out;
  {
    nb::gil_scoped_release release;
    out = tribofx::projection::project_points<E, gdim>(
        std::span(points.data(), n * gdim), std::span(nodes.data(), nv * gdim), f);
  }

  nb::dict d;
  d["facet"] = to_numpy<std::int32_t>(std::move(out.facet), {n});
  d["xi"] = to_numpy<double>(std::move(out.xi), {n, tdim});
  d["x_bar"] = to_numpy<double>(std::move(out.x_bar), {n, gdim});
  d["gap"] = to_numpy<double>(std::move(out.gap), {n});
  d["normal"] = to_numpy<double>(std::move(out.normal), {n, gdim});
  d["tangents"] = to_numpy<double>(std::move(out.tangents), {n, tdim, gdim});
  d["dxi_dx"] = to_numpy<double>(std::move(out.dxi_dx), {n, tdim, gdim});
  d["dxbar_dx"] = to_numpy<double>(std::move(out.dxbar_dx), {n, gdim, gdim});
  d["dn_dx"] = to_numpy<double>(std::move(out.dn_dx), {n, gdim, gdim});
  d["curvature"] = to_numpy<double>(std::move(out.curvature), {n, tdim, tdim});
  d["inside"] = to_numpy<bool>(std::move(out.inside), {n});
  d["distance"] = to_numpy<double>(std::move(out.distance), {n});
  return d;
}

/// A facet type and the dimension of the space it lives in.
template <class E, int gdim>
struct Facet
{
  using element = E;
  static constexpr int dim = gdim;
};

/// The one cell-type dispatch of the bindings: calls f(Facet<E, gdim>{}) for the
/// named facet type (the names of tribofx.projection.CELL_TYPES).
template <class F>
nb::dict with_facet(const std::string& cell_type, F&& f)
{
  namespace el = tribofx::elements;
  if (cell_type == "interval")
    return f(Facet<el::Interval2, 2>{});
  if (cell_type == "interval3")
    return f(Facet<el::Interval3, 2>{});
  if (cell_type == "triangle")
    return f(Facet<el::Triangle3, 3>{});
  if (cell_type == "triangle6")
    return f(Facet<el::Triangle6, 3>{});
  if (cell_type == "quadrilateral")
    return f(Facet<el::Quadrilateral4, 3>{});
  if (cell_type == "quadrilateral9")
    return f(Facet<el::Quadrilateral9, 3>{});
  throw std::invalid_argument("unknown cell_type '" + cell_type + "'");
}

nb::dict closest_point_projection(const CArray2<double>& points,
                                  const CArray2<double>& nodes,
                                  const CArray2<std::int32_t>& facets,
                                  const std::string& cell_type)
{
  return with_facet(cell_type,
                    [&](auto t)
                    {
                      using T = decltype(t);
                      return project<typename T::element, T::dim>(points, nodes, facets);
                    });
}

template <class E, int gdim>
nb::dict lubricate(const CArray2<double>& points, const CArray2<double>& nodes,
                   const CArray2<std::int32_t>& facets)
{
  constexpr int tdim = E::tdim;
  const std::size_t n = points.shape(0);
  const std::size_t nv = nodes.shape(0);
  const auto f = check_inputs<E, gdim>(points, nodes, facets);

  tribofx::lubrication::LubricationOutput out;
  {
    nb::gil_scoped_release release;
    out = tribofx::lubrication::lubrication_points<E, gdim>(
        std::span(points.data(), n * gdim), std::span(nodes.data(), nv * gdim), f);
  }

  auto& pr = out.proj;
  nb::dict d;
  d["facet"] = to_numpy<std::int32_t>(std::move(pr.facet), {n});
  d["xi"] = to_numpy<double>(std::move(pr.xi), {n, tdim});
  d["y"] = to_numpy<double>(std::move(pr.x_bar), {n, gdim});
  d["nu"] = to_numpy<double>(std::move(pr.normal), {n, gdim});
  d["h"] = to_numpy<double>(std::move(pr.gap), {n});
  d["dy_dx"] = to_numpy<double>(std::move(pr.dxbar_dx), {n, gdim, gdim});
  d["dnu_dx"] = to_numpy<double>(std::move(pr.dn_dx), {n, gdim, gdim});
  d["dh_dx"] = to_numpy<double>(std::move(out.dh_dx), {n, gdim});
  d["d2h_dx2"] = to_numpy<double>(std::move(out.d2h_dx2), {n, gdim, gdim});
  d["d2y_dx2"] = to_numpy<double>(std::move(out.d2y_dx2), {n, gdim, gdim, gdim});
  d["inside"] = to_numpy<bool>(std::move(pr.inside), {n});
  d["distance"] = to_numpy<double>(std::move(pr.distance), {n});
  return d;
}

nb::dict lubrication_projection(const CArray2<double>& points, const CArray2<double>& nodes,
                                const CArray2<std::int32_t>& facets,
                                const std::string& cell_type)
{
  return with_facet(cell_type,
                    [&](auto t)
                    {
                      using T = decltype(t);
                      return lubricate<typename T::element, T::dim>(points, nodes, facets);
                    });
}

namespace tb = tribofx::two_body;

/// The 2D (segments) or 3D (triangles) master surface of the two-body kernels.
template <int d>
using Master = std::conditional_t<d == 2, tb::MasterSurface, tb::MasterSurface3>;

template <int d>
Master<d> make_master(const CArray2<double>& nodes, const CArray2<std::int32_t>& facets)
{
  const std::string dim = std::to_string(d);
  if (nodes.shape(1) != d or facets.shape(1) != d)
    throw std::invalid_argument("master nodes and facets must have shape (., " + dim + ")");
  if (facets.shape(0) == 0)
    throw std::invalid_argument("the master surface has no facets");
  const std::size_t nv = nodes.shape(0);
  std::span<const std::int32_t> fac(facets.data(), d * facets.shape(0));
  if (std::ranges::any_of(fac, [nv](std::int32_t i)
                          { return i < 0 or static_cast<std::size_t>(i) >= nv; }))
    throw std::invalid_argument("facet node index out of range");
  return Master<d>(std::span<const double>(nodes.data(), d * nv), fac);
}

template <int d>
nb::dict master_project(const Master<d>& master, const CArray2<double>& points)
{
  if (points.shape(1) != d)
    throw std::invalid_argument("points must have shape (., " + std::to_string(d) + ")");
  const std::size_t np = points.shape(0);
  std::vector<std::int32_t> facet(np);
  std::vector<double> xi((d - 1) * np), distance(np);
  {
    nb::gil_scoped_release release;
    master.project(std::span<const double>(points.data(), d * np), facet, xi, distance);
  }
  nb::dict out;
  out["facet"] = to_numpy<std::int32_t>(std::move(facet), {np});
  if constexpr (d == 2)
    out["xi"] = to_numpy<double>(std::move(xi), {np});
  else
    out["xi"] = to_numpy<double>(std::move(xi), {np, 2});
  out["distance"] = to_numpy<double>(std::move(distance), {np});
  return out;
}

template <int d>
void master_refit(Master<d>& master, const CArray2<double>& nodes)
{
  if (nodes.shape(1) != d)
    throw std::invalid_argument("nodes must have shape (., " + std::to_string(d) + ")");
  master.refit(std::span<const double>(nodes.data(), d * nodes.shape(0)));
}

using CArray1 = nb::ndarray<const double, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
using CArrayN = nb::ndarray<const double, nb::c_contig, nb::device::cpu>;

/// Nodal residuals and tangents of the 2D (13 unknowns) or 3D (25) kernel;
/// xi_old holds d - 1 values per node.
template <int d>
std::tuple<nb::ndarray<nb::numpy, double>, nb::ndarray<nb::numpy, double>>
two_body_nodes(const CArray2<double>& q, const CArrayN& xi_old, const CArray1& w,
               const CArray1& w_c, double rho_n, double rho_t, double mu, bool friction,
               bool eulerian)
{
  constexpr int N = d == 2 ? tb::num_local : tb::num_local_3d;
  const std::size_t n = q.shape(0);
  if (q.shape(1) != N)
    throw std::invalid_argument("q must have shape (., " + std::to_string(N) + ")");
  if (xi_old.size() != (d - 1) * n or w.shape(0) != n or w_c.shape(0) != n)
    throw std::invalid_argument("xi_old (d - 1 per node), w and w_c need one row per row of q");
  if (!(rho_n > 0) or (friction and !(rho_t > 0)) or mu < 0)
    throw std::invalid_argument("rho_n, rho_t must be > 0 and mu >= 0");
  std::vector<double> r(n * N), J(n * N * N);
  {
    nb::gil_scoped_release release;
    const tb::Law law{rho_n, rho_t, mu, friction, eulerian};
    for (std::size_t i = 0; i < n; ++i)
    {
      if constexpr (d == 2)
        tb::node_residual(q.data() + i * N, xi_old.data()[i], w.data()[i], w_c.data()[i], law,
                          r.data() + i * N, J.data() + i * N * N);
      else
        tb::node_residual_3d(q.data() + i * N, xi_old.data() + 2 * i, w.data()[i],
                             w_c.data()[i], law, r.data() + i * N, J.data() + i * N * N);
    }
  }
  return {to_numpy<double>(std::move(r), {n, static_cast<std::size_t>(N)}),
          to_numpy<double>(std::move(J),
                           {n, static_cast<std::size_t>(N), static_cast<std::size_t>(N)})};
}

/// Nodal residuals (n, N) and tangents (n, N, N) of the two-body film: 2D (N = 11,
/// data (., 7)) or 3D (N = 19, data (., 16)).
template <int dim>
std::tuple<nb::ndarray<nb::numpy, double>, nb::ndarray<nb::numpy, double>>
two_body_film_nodes(const CArray2<double>& q, const CArray2<double>& data, const CArray1& w,
                    const CArray1& w_c, double c_h, double c_w)
{
  constexpr int N = dim == 2 ? tb::num_local_film : tb::num_local_film_3d;
  constexpr int M = dim == 2 ? tb::num_data_film : tb::num_data_film_3d;
  const std::size_t n = q.shape(0);
  if (q.shape(1) != N or data.shape(1) != M)
    throw std::invalid_argument(dim == 2 ? "q must have shape (., 11) and data (., 7)"
                                         : "q must have shape (., 19) and data (., 16)");
  if (data.shape(0) != n or w.shape(0) != n or w_c.shape(0) != n)
    throw std::invalid_argument("data, w and w_c need one row per row of q");
  std::vector<double> r(n * N), J(n * N * N);
  {
    nb::gil_scoped_release release;
    for (std::size_t i = 0; i < n; ++i)
    {
      if constexpr (dim == 2)
        tb::film_node_residual(q.data() + i * N, data.data() + i * M, w.data()[i],
                               w_c.data()[i], c_h, c_w, r.data() + i * N,
                               J.data() + i * N * N);
      else
        tb::film_node_residual_3d(q.data() + i * N, data.data() + i * M, w.data()[i],
                                  w_c.data()[i], c_h, c_w, r.data() + i * N,
                                  J.data() + i * N * N);
    }
  }
  return {to_numpy<double>(std::move(r), {n, static_cast<std::size_t>(N)}),
          to_numpy<double>(std::move(J),
                           {n, static_cast<std::size_t>(N), static_cast<std::size_t>(N)})};
}

template <typename I>
void add_matrix_blocks(std::uintptr_t fn, std::uintptr_t mat, const CArray2<I>& rows,
                       const CArray2<I>& cols,
                       const nb::ndarray<const double, nb::ndim<3>, nb::c_contig,
                                         nb::device::cpu>& values)
{
  const std::size_t n = rows.shape(0), nr = rows.shape(1), nc = cols.shape(1);
  if (cols.shape(0) != n or values.shape(0) != n or values.shape(1) != nr
      or values.shape(2) != nc)
    throw std::invalid_argument("rows (n, nr), cols (n, nc) and values (n, nr, nc) disagree");
  nb::gil_scoped_release release;
  tribofx::petsc::add_matrix_blocks<I>(
      fn, mat, std::span<const I>(rows.data(), n * nr), std::span<const I>(cols.data(), n * nc),
      std::span<const double>(values.data(), n * nr * nc), n, static_cast<int>(nr),
      static_cast<int>(nc));
}

template <typename I>
void add_vector_blocks(std::uintptr_t fn, std::uintptr_t vec, const CArray2<I>& rows,
                       const CArray2<double>& values)
{
  const std::size_t n = rows.shape(0), nr = rows.shape(1);
  if (values.shape(0) != n or values.shape(1) != nr)
    throw std::invalid_argument("rows (n, nr) and values (n, nr) disagree");
  nb::gil_scoped_release release;
  tribofx::petsc::add_vector_blocks<I>(fn, vec, std::span<const I>(rows.data(), n * nr),
                                       std::span<const double>(values.data(), n * nr), n,
                                       static_cast<int>(nr));
}

} // namespace

NB_MODULE(_cpp, m)
{
  m.doc() = "tribofx C++ kernels";
  m.attr("__version__") = TRIBOFX_VERSION;
  m.def("version", []() { return 1; });
  m.def("closest_point_projection", &closest_point_projection, "points"_a.noconvert(),
        "nodes"_a.noconvert(), "facets"_a.noconvert(), "cell_type"_a,
        "Closest-point projection of points onto a surface mesh (see "
        "tribofx.projection.closest_point_projection). Returns a dict of arrays.");
  m.def("lubrication_projection", &lubrication_projection, "points"_a.noconvert(),
        "nodes"_a.noconvert(), "facets"_a.noconvert(), "cell_type"_a,
        "Lubrication-surface projection with film thickness and derivatives (see "
        "tribofx.lubrication_projection.lubrication_projection). Returns a dict of "
        "arrays.");
  nb::class_<tb::MasterSurface>(m, "MasterSurface",
                                "Current 2D master polyline with a refitted box tree (see "
                                "tribofx.two_body)")
      .def("__init__",
           [](tb::MasterSurface* self, const CArray2<double>& nodes,
              const CArray2<std::int32_t>& segments)
           { new (self) tb::MasterSurface(make_master<2>(nodes, segments)); },
           "nodes"_a.noconvert(), "segments"_a.noconvert())
      .def("refit", &master_refit<2>, "nodes"_a.noconvert())
      .def("project", &master_project<2>, "points"_a.noconvert())
      .def_prop_ro("num_segments", &tb::MasterSurface::num_segments);
  nb::class_<tb::MasterSurface3>(m, "MasterSurface3",
                                 "Current triangulated 3D master surface with a refitted box "
                                 "tree (see tribofx.two_body)")
      .def("__init__",
           [](tb::MasterSurface3* self, const CArray2<double>& nodes,
              const CArray2<std::int32_t>& triangles)
           { new (self) tb::MasterSurface3(make_master<3>(nodes, triangles)); },
           "nodes"_a.noconvert(), "triangles"_a.noconvert())
      .def("refit", &master_refit<3>, "nodes"_a.noconvert())
      .def("project", &master_project<3>, "points"_a.noconvert())
      .def_prop_ro("num_segments", &tb::MasterSurface3::num_triangles);
  m.def("two_body_nodes", &two_body_nodes<2>, "q"_a.noconvert(), "xi_old"_a.noconvert(),
        "w"_a.noconvert(), "w_c"_a.noconvert(), "rho_n"_a, "rho_t"_a, "mu"_a, "friction"_a,
        "eulerian"_a = false,
        "Nodal two-body contact residuals (n, 13) and tangents (n, 13, 13) (see "
        "tribofx.two_body.node_residuals).");
  m.def("two_body_nodes_3d", &two_body_nodes<3>, "q"_a.noconvert(), "xi_old"_a.noconvert(),
        "w"_a.noconvert(), "w_c"_a.noconvert(), "rho_n"_a, "rho_t"_a, "mu"_a, "friction"_a,
        "eulerian"_a = false,
        "Nodal 3D two-body contact residuals (n, 25) and tangents (n, 25, 25) (see "
        "tribofx.two_body.node_residuals).");
  m.def("two_body_film_nodes", &two_body_film_nodes<2>, "q"_a.noconvert(),
        "data"_a.noconvert(), "w"_a.noconvert(), "w_c"_a.noconvert(), "c_h"_a, "c_w"_a,
        "Nodal two-body film residuals (n, 11) and tangents (n, 11, 11) (see "
        "tribofx.two_body.film_node_residuals).");
  m.def("two_body_film_nodes_3d", &two_body_film_nodes<3>, "q"_a.noconvert(),
        "data"_a.noconvert(), "w"_a.noconvert(), "w_c"_a.noconvert(), "c_h"_a, "c_w"_a,
        "Nodal 3D two-body film residuals (n, 19) and tangents (n, 19, 19) (see "
        "tribofx.two_body.film_node_residuals).");
  m.def("add_matrix_blocks", &add_matrix_blocks<std::int32_t>, "fn"_a, "mat"_a,
        "rows"_a.noconvert(), "cols"_a.noconvert(), "values"_a.noconvert());
  m.def("add_matrix_blocks", &add_matrix_blocks<std::int64_t>, "fn"_a, "mat"_a,
        "rows"_a.noconvert(), "cols"_a.noconvert(), "values"_a.noconvert(),
        "Add dense blocks to a PETSc Mat through MatSetValues (see tribofx.petsc_insert).");
  m.def("add_vector_blocks", &add_vector_blocks<std::int32_t>, "fn"_a, "vec"_a,
        "rows"_a.noconvert(), "values"_a.noconvert());
  m.def("add_vector_blocks", &add_vector_blocks<std::int64_t>, "fn"_a, "vec"_a,
        "rows"_a.noconvert(), "values"_a.noconvert(),
        "Add dense blocks to a PETSc Vec through VecSetValues (see tribofx.petsc_insert).");
}
