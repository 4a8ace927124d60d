#pragma once
// The two check macros of the house: KERF_CHECK is always on (input, library
// return codes) and throws kerf::Error; KERF_DCHECK guards invariants in debug builds.
#include <cassert>
#include <sstream>
#include <stdexcept>
#include <string>

namespace kerf {

/// Every error kerf reports to a user; the message says where and why.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An error every MPI rank meets alike, decided from values each rank holds
/// the same (a solve's verdict from global norms, the replicated state gone
/// NaN): under mpirun rank 0 alone reports it, the others say nothing.
class SharedFailure : public Error {
 public:
  using Error::Error;
};

/// A solution that diverged (NaN or infinity in the state): summary.json says
/// `"diverged": true` beside `"status": "error"`, so a study probing stability
/// tells it from any other failure.
class Diverged : public SharedFailure {
 public:
  using SharedFailure::SharedFailure;
};

namespace detail {
template <class... Parts>
std::string concat(const Parts&... parts) {
  std::ostringstream out;
  (out << ... << parts);
  return out.str();
}
}  // namespace detail

}  // namespace kerf

#define KERF_CHECK_THROWING(error_type, condition, ...)             \
  do {                                                              \
    if (!(condition)) throw error_type(::kerf::detail::concat(__VA_ARGS__)); \
  } while (0)

#define KERF_CHECK(condition, ...) KERF_CHECK_THROWING(::kerf::Error, condition, __VA_ARGS__)

/// KERF_CHECK for a condition every rank evaluates alike (kerf::SharedFailure).
#define KERF_CHECK_SHARED(condition, ...) KERF_CHECK_THROWING(::kerf::SharedFailure, condition, __VA_ARGS__)

#define KERF_DCHECK(condition) assert(condition)
