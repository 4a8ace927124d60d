// GhostExchange's engine: a PETSc ghosted vector (VecCreateGhost). Inside the PETSc module.
#include <petscvec.h>

#include <algorithm>

#include "core/check.h"
#include "solvers/petsc_internals.h"

namespace kerf {
namespace {

struct Gather {
  bool all = false;            // every entry, in order
  std::vector<Index> entries;  // else where the gathered values go
  std::vector<Index> own_places;  // which of this rank's own entries the scatter reads
  Vec gathered = nullptr;      // the asked entries on this rank
  VecScatter scatter = nullptr;
  ~Gather() {
    if (scatter) VecScatterDestroy(&scatter);
    if (gathered) VecDestroy(&gathered);
  }
};

/// `local` into the ghosted vector's local form (own entries, then the ghosts'), or back.
void copy_local_form(Vec ghosted, Vector& local, bool into_vector) {
  Vec form = nullptr;
  petsc_check(VecGhostGetLocalForm(ghosted, &form), "VecGhostGetLocalForm");
  PetscScalar* values = nullptr;
  petsc_check(VecGetArray(form, &values), "VecGetArray");
  if (into_vector)
    std::copy(local.data(), local.data() + local.size(), values);
  else
    std::copy(values, values + local.size(), local.data());
  petsc_check(VecRestoreArray(form, &values), "VecRestoreArray");
  petsc_check(VecGhostRestoreLocalForm(ghosted, &form), "VecGhostRestoreLocalForm");
}

class PetscGhostExchange final : public GhostExchange::Engine {
 public:
  PetscGhostExchange(Index global_size, Index own_count, std::span<const Index> ghosts)
      : global_size_(global_size), own_count_(own_count), local_size_(own_count + static_cast<Index>(ghosts.size())) {
    start_petsc();
    const std::vector<PetscInt> ghost_rows(ghosts.begin(), ghosts.end());
    petsc_check(VecCreateGhost(PETSC_COMM_WORLD, own_count, global_size, static_cast<PetscInt>(ghosts.size()),
                               ghost_rows.data(), &ghosted_),
                "VecCreateGhost");
  }
  ~PetscGhostExchange() override {
    if (ghosted_) VecDestroy(&ghosted_);
  }

  void sum_and_share(Vector& local) const override;
  void gather(const Vector& local, std::span<const Index> entries, Vector& whole) const override;
  void gather_all(const Vector& local, Vector& whole) const override;

 private:
  std::unique_ptr<Gather> make_gather(std::span<const Index> entries) const;
  std::unique_ptr<Gather> make_gather_all() const;
  void gather_with(const Gather& gather, const Vector& local, Vector& whole) const;

  Index global_size_, own_count_, local_size_;
  Vec ghosted_ = nullptr;  // own entries, then the ghosts' in the local form
  mutable std::unique_ptr<Gather> all_, listed_;  // built when first asked
};

void PetscGhostExchange::sum_and_share(Vector& local) const {
  KERF_CHECK(local.size() == local_size_, "internal: a ghosted vector of ", local.size(), " entries; expected ",
             local_size_);
  Vec ghosted = ghosted_;
  copy_local_form(ghosted, local, true);
  // The ghosts' parts added into their owners' entries, then the owners' sums copied to the ghosts.
  petsc_check(VecGhostUpdateBegin(ghosted, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateBegin");
  petsc_check(VecGhostUpdateEnd(ghosted, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateEnd");
  petsc_check(VecGhostUpdateBegin(ghosted, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateBegin");
  petsc_check(VecGhostUpdateEnd(ghosted, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateEnd");
  copy_local_form(ghosted, local, false);
}

std::unique_ptr<Gather> PetscGhostExchange::make_gather_all() const {
  auto gather = std::make_unique<Gather>();
  gather->all = true;
  petsc_check(VecScatterCreateToAll(ghosted_, &gather->scatter, &gather->gathered), "VecScatterCreateToAll");
  return gather;
}

std::unique_ptr<Gather> PetscGhostExchange::make_gather(std::span<const Index> entries) const {
  auto gather = std::make_unique<Gather>();
  gather->entries.assign(entries.begin(), entries.end());
  PetscInt first = 0, end = 0;
  petsc_check(VecGetOwnershipRange(ghosted_, &first, &end), "VecGetOwnershipRange");
  for (Index e : entries)
    if (e >= first && e < end) gather->own_places.push_back(e - first);
  const std::vector<PetscInt> rows(entries.begin(), entries.end());
  IS wanted = nullptr;
  petsc_check(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(rows.size()), rows.data(), PETSC_COPY_VALUES,
                              &wanted),
              "ISCreateGeneral");
  petsc_check(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(rows.size()), &gather->gathered), "VecCreateSeq");
  const PetscErrorCode code = VecScatterCreate(ghosted_, wanted, gather->gathered, nullptr, &gather->scatter);
  ISDestroy(&wanted);
  petsc_check(code, "VecScatterCreate");
  return gather;
}

void PetscGhostExchange::gather_with(const Gather& gather, const Vector& local, Vector& whole) const {
  KERF_CHECK(local.size() == local_size_, "internal: a ghosted vector of ", local.size(), " entries; expected ",
             local_size_);
  Vec ghosted = ghosted_;
  PetscScalar* own = nullptr;  // the global vector's array: this rank's own entries; the scatter reads the asked ones
  petsc_check(VecGetArray(ghosted, &own), "VecGetArray");
  if (gather.all)
    std::copy(local.data(), local.data() + own_count_, own);
  else
    for (Index k : gather.own_places) own[k] = local[k];
  petsc_check(VecRestoreArray(ghosted, &own), "VecRestoreArray");
  petsc_check(VecScatterBegin(gather.scatter, ghosted, gather.gathered, INSERT_VALUES, SCATTER_FORWARD),
              "VecScatterBegin");
  petsc_check(VecScatterEnd(gather.scatter, ghosted, gather.gathered, INSERT_VALUES, SCATTER_FORWARD),
              "VecScatterEnd");
  const PetscScalar* values = nullptr;
  petsc_check(VecGetArrayRead(gather.gathered, &values), "VecGetArrayRead");
  if (whole.size() != global_size_) whole = Vector::Zero(global_size_);
  if (gather.all) {
    std::copy(values, values + global_size_, whole.data());
  } else {
    for (std::size_t k = 0; k < gather.entries.size(); ++k) whole[gather.entries[k]] = values[k];
  }
  petsc_check(VecRestoreArrayRead(gather.gathered, &values), "VecRestoreArrayRead");
}

void PetscGhostExchange::gather(const Vector& local, std::span<const Index> entries, Vector& whole) const {
  if (!listed_ || !std::equal(entries.begin(), entries.end(), listed_->entries.begin(), listed_->entries.end()))
    listed_ = make_gather(entries);  // collective: every rank asks the same list at once
  gather_with(*listed_, local, whole);
}

void PetscGhostExchange::gather_all(const Vector& local, Vector& whole) const {
  if (!all_) all_ = make_gather_all();
  gather_with(*all_, local, whole);
}

}  // namespace

std::unique_ptr<GhostExchange::Engine> petsc_ghost_exchange(Index global_size, Index own_count,
                                                            std::span<const Index> ghosts) {
  return std::make_unique<PetscGhostExchange>(global_size, own_count, ghosts);
}

}  // namespace kerf
