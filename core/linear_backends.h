#pragma once
// Every linear solver backend, described once: its scene spelling
// (solve.linear_solver), whether it factors the matrix (the resource estimate
// counts the factor's fill), whether one solve spans MPI ranks (the command
// line refuses the others under mpirun) and the stage it records in the
// summary. A new backend is a row here and a case in
// solvers/linear_solver_factory.cpp beside its own file.
#include <array>

#include "core/enum_table.h"

namespace kerf {

enum class LinearSolverKind { cholmod, petsc, cg, ldlt, p_multigrid };

struct LinearBackend {
  LinearSolverKind kind;
  const char* name;
  bool direct;       // factors the matrix: memory for the factor's fill
  bool spans_ranks;  // one solve shared by every MPI rank
  const char* stage;  // the summary's stage it starts ("" for none)
};

inline constexpr std::array<LinearBackend, 5> linear_backends{{
    {LinearSolverKind::cholmod, "cholmod", true, false, ""},
    {LinearSolverKind::petsc, "petsc", false, true, "petsc"},
    {LinearSolverKind::cg, "cg", false, false, ""},
    {LinearSolverKind::ldlt, "ldlt", true, false, ""},
    {LinearSolverKind::p_multigrid, "p_multigrid", false, false, ""},
}};

static_assert(rows_follow_enum(linear_backends, &LinearBackend::kind),
              "linear_backends: one row per LinearSolverKind, in its order");

constexpr const LinearBackend& linear_backend(LinearSolverKind kind) { return row_of(linear_backends, kind); }

}  // namespace kerf
