// Copyright (C) 2026 tribofx contributors
// SPDX-License-Identifier: MIT
//
// Insertion of dense element blocks into a PETSc matrix or vector from C++.
//
// The PETSc of the dolfinx-solver wheel ships its shared library but no
// headers, so the two entry points used here are declared by their C ABI
// (stable across PETSc releases):
//
//   PetscErrorCode MatSetValues(Mat, PetscInt m, const PetscInt rows[], PetscInt n,
//                               const PetscInt cols[], const PetscScalar v[], InsertMode);
//   PetscErrorCode VecSetValues(Vec, PetscInt n, const PetscInt ix[],
//                               const PetscScalar v[], InsertMode);
//
// with PetscScalar = double (real build) and PetscInt the index type of the
// build (int32 or int64, the template parameter).  Their addresses and the
// object handles come from Python (tribofx/petsc_insert.py).  A block may hold
// unused slots (-1): MatSetValues skips negative indices itself, the vector
// entries are filtered here.

#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace tribofx::petsc
{

/// PETSc's ADD_VALUES.
inline constexpr int add_values = 2;

template <typename I>
using MatSetValuesFn = int (*)(void*, I, const I*, I, const I*, const double*, int);
template <typename I>
using VecSetValuesFn = int (*)(void*, I, const I*, const double*, int);

/// Add n dense blocks values[k] (nr x nc, row-major) at rows[k] x cols[k] of a Mat.
template <typename I>
void add_matrix_blocks(std::uintptr_t fn, std::uintptr_t mat, std::span<const I> rows,
                       std::span<const I> cols, std::span<const double> values,
                       std::size_t n, int nr, int nc)
{
  auto set = reinterpret_cast<MatSetValuesFn<I>>(fn);
  for (std::size_t k = 0; k < n; ++k)
  {
    const int err = set(reinterpret_cast<void*>(mat), static_cast<I>(nr),
                        rows.data() + k * nr, static_cast<I>(nc), cols.data() + k * nc,
                        values.data() + k * nr * nc, add_values);
    if (err != 0)
      throw std::runtime_error("MatSetValues failed with PETSc error " + std::to_string(err));
  }
}

/// Add n dense blocks values[k] (nr) at rows[k] of a Vec.  VecSetValues does not
/// skip negative indices by default: the valid entries are gathered and added
/// in one call.
template <typename I>
void add_vector_blocks(std::uintptr_t fn, std::uintptr_t vec, std::span<const I> rows,
                       std::span<const double> values, std::size_t n, int nr)
{
  auto set = reinterpret_cast<VecSetValuesFn<I>>(fn);
  std::vector<I> ix;
  std::vector<double> y;
  ix.reserve(n * nr);
  y.reserve(n * nr);
  for (std::size_t k = 0; k < n * nr; ++k)
  {
    if (rows[k] >= 0)
    {
      ix.push_back(rows[k]);
      y.push_back(values[k]);
    }
  }
  const int err = set(reinterpret_cast<void*>(vec), static_cast<I>(ix.size()), ix.data(),
                      y.data(), add_values);
  if (err != 0)
    throw std::runtime_error("VecSetValues failed with PETSc error " + std::to_string(err));
}

} // namespace tribofx::petsc
