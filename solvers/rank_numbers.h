#pragma once
// One number from every MPI rank, combined: their sum or their smallest,
// through a PETSc vector of one entry a rank (kerf passes no message of its
// own, and PETSc is the PETSc module's: solvers/petsc_module.h). Collective:
// every rank calls alike.
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

  /// What combines them (the PETSc module's).
  class Engine {
   public:
    virtual ~Engine() = default;
    virtual double sum(double x) const = 0;
    virtual double smallest(double x) const = 0;
  };

 private:
  std::unique_ptr<Engine> engine_;
};

}  // namespace kerf
