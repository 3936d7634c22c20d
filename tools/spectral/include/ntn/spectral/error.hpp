// The one exception type of the spectral tools: bad input (NaN, too short a record, non-uniform
// time, bad options), with a message a person can act on.
#pragma once

#include <stdexcept>

namespace ntn::spectral {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ntn::spectral
