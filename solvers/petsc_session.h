#pragma once
// PETSc, and through it MPI, for the whole process: started by the first
// PETSc solver, or at once when an MPI launcher started the process, so that
// every rank knows how many there are before any work. kerf passes no message
// of its own: PETSc is the only message passing.

#include <functional>
#include <string>
#include <vector>

#include "core/rank_share.h"

namespace kerf {

/// Throws naming the PETSc (or MPI) call and PETSc's message when `code` is not 0.
void check_petsc(int code, const char* call);

/// Starts PETSc once (no signal handlers: kerf reports its own errors);
/// finalized at exit.
void ensure_petsc_initialized();

/// Ends every rank's process after an error on this one, so that no rank
/// waits forever for it in a collective call. Rank 0 prints `message` and
/// stops the job at once. Another rank, when every rank meets the failure
/// alike (`shared`: kerf::SharedFailure), says nothing and waits for rank 0
/// to stop the job (so it is printed once); should rank 0 not do so within
/// a minute, or when the failure is its own, it calls `if_alone` (its last
/// words: the summary rank 0 will not write), prints and stops the job. The
/// launcher's exit code is `code`.
[[noreturn]] void stop_every_rank(const RankShare& ranks, int code, const std::string& message, bool shared,
                                  const std::function<void()>& if_alone = {});

/// Returns when every rank has called it (files one rank writes that another
/// needs: the output folder, the pieces of a .pvtu).
void wait_for_every_rank();

/// This process's rank among those mpirun started (Open MPI or another PMIx
/// launcher: PETSc is then started here); 0 of 1 without a launcher, and
/// PETSc is left unstarted.
RankShare mpi_ranks();

}  // namespace kerf
