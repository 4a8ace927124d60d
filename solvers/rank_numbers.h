#pragma once
// One number from every MPI rank, combined: their sum or their smallest,
// through a PETSc vector of one entry a rank (kerf passes no message of its
// own). Collective: every rank calls alike.
#include <memory>

namespace kerf {

class RankNumbers {
 public:
  RankNumbers();
  ~RankNumbers();
  RankNumbers(const RankNumbers&) = delete;
  RankNumbers& operator=(const RankNumbers&) = delete;

  /// The sum of every rank's x.
  double sum(double x) const;
  /// The smallest of every rank's x.
  double smallest(double x) const;

 private:
  void set_mine(double x) const;  // this rank's entry
  struct Petsc;
  std::unique_ptr<Petsc> petsc_;
};

}  // namespace kerf
