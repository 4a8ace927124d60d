#pragma once
// Runs a library call on one OpenMP thread and restores the thread count after:
// gmsh's meshers are not deterministic on several threads; CHOLMOD's analysis
// and triangular solves stay on one thread (threads were not shown to help
// them; its numeric factorization does gain and runs threaded).
#include <dlfcn.h>
#include <omp.h>

namespace kerf {

class SingleThreadScope {
 public:
  SingleThreadScope() : threads_(omp_get_max_threads()) {
    omp_set_num_threads(1);
    // OpenBLAS opens parallel regions with its own thread count, whatever
    // OpenMP's is; it is found at run time so that any BLAS still links.
    if (auto* set = openblas_setter()) {
      blas_threads_ = openblas_getter() ? openblas_getter()() : threads_;
      set(1);
    }
  }
  ~SingleThreadScope() {
    omp_set_num_threads(threads_);
    if (auto* set = openblas_setter()) set(blas_threads_);
  }
  SingleThreadScope(const SingleThreadScope&) = delete;
  SingleThreadScope& operator=(const SingleThreadScope&) = delete;

 private:
  using Setter = void (*)(int);
  using Getter = int (*)();
  static Setter openblas_setter() {
    static Setter setter = reinterpret_cast<Setter>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    return setter;
  }
  static Getter openblas_getter() {
    static Getter getter = reinterpret_cast<Getter>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    return getter;
  }
  int threads_;
  int blas_threads_ = 1;
};

}  // namespace kerf
