#pragma once
// Errors carry their context (file, parameter, particle id) in the message, so that
// main() can print one clear line per problem and exit non-zero (docs/architecture.md).
#include <stdexcept>
#include <string>

namespace upgrain {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace upgrain
