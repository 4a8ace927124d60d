#include "solvers/ghost_exchange.h"

#include <petscvec.h>

#include <algorithm>

#include "core/check.h"
#include "solvers/petsc_session.h"

namespace kerf {

struct GhostExchange::Petsc {
  Vec ghosted = nullptr;  // own entries, then the ghosts' in the local form
  ~Petsc() {
    if (ghosted) VecDestroy(&ghosted);
  }
};

struct GhostExchange::Gather {
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

GhostExchange::GhostExchange(Index global_size, Index own_count, std::span<const Index> ghosts)
    : global_size_(global_size), own_count_(own_count), ghost_count_(static_cast<Index>(ghosts.size())),
      petsc_(std::make_unique<Petsc>()) {
  ensure_petsc_initialized();
  const std::vector<PetscInt> ghost_rows(ghosts.begin(), ghosts.end());
  check_petsc(VecCreateGhost(PETSC_COMM_WORLD, own_count, global_size, ghost_count_, ghost_rows.data(),
                             &petsc_->ghosted),
              "VecCreateGhost");
}

GhostExchange::~GhostExchange() = default;

namespace {

/// `local` into the ghosted vector's local form (own entries, then the ghosts'), or back.
void copy_local_form(Vec ghosted, Vector& local, bool into_vector) {
  Vec form = nullptr;
  check_petsc(VecGhostGetLocalForm(ghosted, &form), "VecGhostGetLocalForm");
  PetscScalar* values = nullptr;
  check_petsc(VecGetArray(form, &values), "VecGetArray");
  if (into_vector)
    std::copy(local.data(), local.data() + local.size(), values);
  else
    std::copy(values, values + local.size(), local.data());
  check_petsc(VecRestoreArray(form, &values), "VecRestoreArray");
  check_petsc(VecGhostRestoreLocalForm(ghosted, &form), "VecGhostRestoreLocalForm");
}

}  // namespace

void GhostExchange::sum_and_share(Vector& local) const {
  KERF_CHECK(local.size() == local_size(), "internal: a ghosted vector of ", local.size(), " entries; expected ",
             local_size());
  Vec ghosted = petsc_->ghosted;
  copy_local_form(ghosted, local, true);
  // The ghosts' parts added into their owners' entries, then the owners' sums copied to the ghosts.
  check_petsc(VecGhostUpdateBegin(ghosted, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateBegin");
  check_petsc(VecGhostUpdateEnd(ghosted, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateEnd");
  check_petsc(VecGhostUpdateBegin(ghosted, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateBegin");
  check_petsc(VecGhostUpdateEnd(ghosted, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateEnd");
  copy_local_form(ghosted, local, false);
}

std::unique_ptr<GhostExchange::Gather> GhostExchange::make_gather_all() const {
  auto gather = std::make_unique<Gather>();
  gather->all = true;
  check_petsc(VecScatterCreateToAll(petsc_->ghosted, &gather->scatter, &gather->gathered), "VecScatterCreateToAll");
  return gather;
}

std::unique_ptr<GhostExchange::Gather> GhostExchange::make_gather(std::span<const Index> entries) const {
  auto gather = std::make_unique<Gather>();
  gather->entries.assign(entries.begin(), entries.end());
  PetscInt first = 0, end = 0;
  check_petsc(VecGetOwnershipRange(petsc_->ghosted, &first, &end), "VecGetOwnershipRange");
  for (Index e : entries)
    if (e >= first && e < end) gather->own_places.push_back(e - first);
  const std::vector<PetscInt> rows(entries.begin(), entries.end());
  IS wanted = nullptr;
  check_petsc(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(rows.size()), rows.data(), PETSC_COPY_VALUES,
                              &wanted),
              "ISCreateGeneral");
  check_petsc(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(rows.size()), &gather->gathered), "VecCreateSeq");
  const PetscErrorCode code = VecScatterCreate(petsc_->ghosted, wanted, gather->gathered, nullptr, &gather->scatter);
  ISDestroy(&wanted);
  check_petsc(code, "VecScatterCreate");
  return gather;
}

void GhostExchange::gather_with(const Gather& gather, const Vector& local, Vector& whole) const {
  KERF_CHECK(local.size() == local_size(), "internal: a ghosted vector of ", local.size(), " entries; expected ",
             local_size());
  Vec ghosted = petsc_->ghosted;
  PetscScalar* own = nullptr;  // the global vector's array: this rank's own entries; the scatter reads the asked ones
  check_petsc(VecGetArray(ghosted, &own), "VecGetArray");
  if (gather.all)
    std::copy(local.data(), local.data() + own_count_, own);
  else
    for (Index k : gather.own_places) own[k] = local[k];
  check_petsc(VecRestoreArray(ghosted, &own), "VecRestoreArray");
  check_petsc(VecScatterBegin(gather.scatter, ghosted, gather.gathered, INSERT_VALUES, SCATTER_FORWARD),
              "VecScatterBegin");
  check_petsc(VecScatterEnd(gather.scatter, ghosted, gather.gathered, INSERT_VALUES, SCATTER_FORWARD),
              "VecScatterEnd");
  const PetscScalar* values = nullptr;
  check_petsc(VecGetArrayRead(gather.gathered, &values), "VecGetArrayRead");
  if (whole.size() != global_size_) whole = Vector::Zero(global_size_);
  if (gather.all) {
    std::copy(values, values + global_size_, whole.data());
  } else {
    for (std::size_t k = 0; k < gather.entries.size(); ++k) whole[gather.entries[k]] = values[k];
  }
  check_petsc(VecRestoreArrayRead(gather.gathered, &values), "VecRestoreArrayRead");
}

void GhostExchange::gather(const Vector& local, std::span<const Index> entries, Vector& whole) const {
  if (!listed_ || !std::equal(entries.begin(), entries.end(), listed_->entries.begin(), listed_->entries.end()))
    listed_ = make_gather(entries);  // collective: every rank asks the same list at once
  gather_with(*listed_, local, whole);
}

void GhostExchange::gather_all(const Vector& local, Vector& whole) const {
  if (!all_) all_ = make_gather_all();
  gather_with(*all_, local, whole);
}

}  // namespace kerf
