#pragma once
// The floor under a cut update: the least work a new piece costs is
// recomputing the MLS shape functions (values and gradients, linear basis) of
// the rows whose weights it changed, by kerf's own linear row (mls_linear.h,
// the kernel every update calls; BM_MlsRowLinear times it alone) from the
// neighbours' quartic weights times their cut factors (read from the table,
// not looked up), rows in parallel. No Enrichment Grid, no search for the
// rows, no stabilisation pairs, no table bookkeeping.
#include <span>
#include <vector>

#include "core/types.h"

namespace kerf::bench {

struct MlsRowsFloorData {
  std::span<const Index> start, index;  // neighbour lists of the rows (CSR over all points)
  std::span<const Vec3> node, point;    // node positions; the points the rows are at
  std::span<const double> support;      // per node
  std::span<const double> factor;       // per slot: the cut factor g_I
};

/// Values and gradients of rows `rows` into value (per slot) and gradient (3 per slot).
void mls_rows_floor(const MlsRowsFloorData& data, std::span<const Index> rows, std::vector<double>& value,
                    std::vector<double>& gradient);

}  // namespace kerf::bench
