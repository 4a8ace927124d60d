// The collective calls of solvers/rank_messages.h over PETSc vectors: inside the PETSc module.
#include <petscvec.h>

#include <algorithm>
#include <numeric>

#include "core/check.h"
#include "solvers/petsc_internals.h"

namespace kerf {
namespace {

/// The entries of `v` this rank holds.
std::vector<double> local_values(Vec v) {
  PetscInt size = 0;
  petsc_check(VecGetLocalSize(v, &size), "VecGetLocalSize");
  const PetscScalar* values = nullptr;
  petsc_check(VecGetArrayRead(v, &values), "VecGetArrayRead");
  std::vector<double> out(values, values + size);
  petsc_check(VecRestoreArrayRead(v, &values), "VecRestoreArrayRead");
  return out;
}

PetscInt vector_length(std::size_t size) {
  KERF_CHECK(size < static_cast<std::size_t>(PETSC_MAX_INT), "internal: ", size,
             " values are too many to send in one PETSc vector");
  return static_cast<PetscInt>(size);
}

/// `from`'s entries scattered into `to` and this rank's of them read; the
/// scatter and both vectors destroyed.
std::vector<double> scatter_and_read(VecScatter scatter, Vec from, Vec to) {
  petsc_check(VecScatterBegin(scatter, from, to, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  petsc_check(VecScatterEnd(scatter, from, to, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  std::vector<double> out = local_values(to);
  petsc_check(VecScatterDestroy(&scatter), "VecScatterDestroy");
  petsc_check(VecDestroy(&to), "VecDestroy");
  petsc_check(VecDestroy(&from), "VecDestroy");
  return out;
}

/// Every rank's `mine` concatenated in rank order, on every rank.
std::vector<double> concatenated(std::vector<double>& mine) {
  Vec held = nullptr, all = nullptr;
  VecScatter to_all = nullptr;
  petsc_check(VecCreateMPIWithArray(PETSC_COMM_WORLD, 1, vector_length(mine.size()), PETSC_DETERMINE, mine.data(),
                                    &held),
              "VecCreateMPIWithArray");
  petsc_check(VecScatterCreateToAll(held, &to_all, &all), "VecScatterCreateToAll");
  return scatter_and_read(to_all, held, all);
}

}  // namespace

void petsc_scatter_into(VecScatter scatter, Vec from, Vec to, Index size, Vector& out) {
  petsc_check(VecScatterBegin(scatter, from, to, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  petsc_check(VecScatterEnd(scatter, from, to, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  const PetscScalar* values = nullptr;
  petsc_check(VecGetArrayRead(to, &values), "VecGetArrayRead");
  out = Eigen::Map<const Vector>(values, size);
  petsc_check(VecRestoreArrayRead(to, &values), "VecRestoreArrayRead");
}

std::vector<double> petsc_send_from_first_rank(std::vector<double> values) {
  start_petsc();
  PetscMPIInt rank = 0;
  petsc_check(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), "MPI_Comm_rank");
  if (rank != 0) values.clear();  // rank 0's alone, end to end, is rank 0's
  return concatenated(values);
}

std::vector<double> petsc_send_parts_from_first_rank(std::vector<std::vector<double>> parts) {
  start_petsc();
  PetscMPIInt rank = 0, size = 1;
  petsc_check(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), "MPI_Comm_rank");
  petsc_check(MPI_Comm_size(PETSC_COMM_WORLD, &size), "MPI_Comm_size");
  std::vector<double> lengths;  // rank 0's, then every rank's
  std::vector<double> held_values;
  if (rank == 0) {
    KERF_CHECK(static_cast<int>(parts.size()) == size, "internal: ", parts.size(), " parts for ", size, " ranks");
    for (const std::vector<double>& part : parts) {
      lengths.push_back(static_cast<double>(part.size()));
      held_values.insert(held_values.end(), part.begin(), part.end());
    }
    parts.clear();
  }
  lengths = petsc_send_from_first_rank(std::move(lengths));
  Vec held = nullptr, mine = nullptr;
  VecScatter to_owner = nullptr;
  petsc_check(VecCreateMPIWithArray(PETSC_COMM_WORLD, 1, vector_length(held_values.size()), PETSC_DETERMINE,
                                    held_values.data(), &held),
              "VecCreateMPIWithArray");
  petsc_check(VecCreateMPI(PETSC_COMM_WORLD, static_cast<PetscInt>(lengths[rank]), PETSC_DETERMINE, &mine),
              "VecCreateMPI");
  // Entry i of rank 0's vector to entry i of the other: both number the lists
  // end to end, and each rank asks for its own list's entries.
  PetscInt first = 0, end = 0;
  petsc_check(VecGetOwnershipRange(mine, &first, &end), "VecGetOwnershipRange");
  IS entries = nullptr;
  petsc_check(ISCreateStride(PETSC_COMM_WORLD, end - first, first, 1, &entries), "ISCreateStride");
  petsc_check(VecScatterCreate(held, entries, mine, entries, &to_owner), "VecScatterCreate");
  petsc_check(ISDestroy(&entries), "ISDestroy");
  return scatter_and_read(to_owner, held, mine);
}

std::vector<std::vector<double>> petsc_gather_from_every_rank(std::vector<double> mine) {
  start_petsc();
  std::vector<double> length{static_cast<double>(mine.size())};
  const std::vector<double> lengths = concatenated(length);
  const std::vector<double> all = concatenated(mine);
  std::vector<std::vector<double>> out;
  std::size_t at = 0;
  for (double n : lengths) {
    out.emplace_back(all.begin() + at, all.begin() + at + static_cast<std::size_t>(n));
    at += static_cast<std::size_t>(n);
  }
  return out;
}

void petsc_sum_on_every_rank(std::span<double> values) {
  start_petsc();
  std::vector<PetscInt> entries;  // a rank's part is zero away from its points: only the rest is sent
  std::vector<PetscScalar> nonzero;
  for (std::size_t k = 0; k < values.size(); ++k)
    if (values[k] != 0.0) entries.push_back(static_cast<PetscInt>(k)), nonzero.push_back(values[k]);
  Vec owned = nullptr, all = nullptr;
  VecScatter to_all = nullptr;
  petsc_check(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, vector_length(values.size()), &owned), "VecCreateMPI");
  petsc_check(VecSetValues(owned, static_cast<PetscInt>(entries.size()), entries.data(), nonzero.data(), ADD_VALUES),
              "VecSetValues");
  petsc_check(VecAssemblyBegin(owned), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(owned), "VecAssemblyEnd");
  petsc_check(VecScatterCreateToAll(owned, &to_all, &all), "VecScatterCreateToAll");
  const std::vector<double> sum = scatter_and_read(to_all, owned, all);
  std::copy(sum.begin(), sum.end(), values.begin());
}

}  // namespace kerf
