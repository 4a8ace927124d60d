#pragma once
// A BlockSink adding blocks into a CSR matrix's arrays (sorted columns a row).
#include "discretization/body_capabilities.h"

namespace kerf {

/// A sink adding scale * block into `matrix` (whose pattern holds the block's
/// nonzero entries; entries outside it must be zero and are skipped);
/// thread-safe for blocks that share no row. With `dofs_per_node` 2 or 3, a
/// block of whole nodes is written a node pair at a time (one search each).
BlockSink add_into(const CsrView& matrix, double scale = 1.0, int dofs_per_node = 1);

}  // namespace kerf
