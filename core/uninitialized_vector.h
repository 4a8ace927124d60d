#pragma once
// A std::vector whose resize leaves new elements of trivial types
// uninitialized: large arrays every entry of which is written next, in
// parallel, are first touched (and their pages mapped) by the threads that
// write them, instead of zeroed by one thread first.
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace kerf {

template <class T>
class DefaultInitAllocator : public std::allocator<T> {
 public:
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  /// Default-initialization: nothing for a trivial type.
  template <class U>
  void construct(U* at) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(at)) U;
  }
  template <class U, class... Args>
  void construct(U* at, Args&&... args) {
    ::new (static_cast<void*>(at)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using UninitializedVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace kerf
