// RAII guard: Eigen heap allocations abort inside its scope (EIGEN_RUNTIME_NO_MALLOC; see
// eigen_guard.hpp for why this holds in Release too). Wrap every init / start / step with it.
#pragma once

#include <Eigen/Core>

namespace ntn_test {

class EigenNoMalloc {
 public:
  EigenNoMalloc() : was_(Eigen::internal::is_malloc_allowed()) {
    Eigen::internal::set_is_malloc_allowed(false);
  }
  ~EigenNoMalloc() { Eigen::internal::set_is_malloc_allowed(was_); }
  EigenNoMalloc(const EigenNoMalloc&) = delete;
  EigenNoMalloc& operator=(const EigenNoMalloc&) = delete;

 private:
  bool was_;
};

}  // namespace ntn_test
