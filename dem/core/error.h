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

// An error that every rank of the run raised at the same point with the same message (a
// scene every rank read, a reduction every rank saw, dem/parallel/exchange.h: throw_if_any):
// the driver prints it once. Any other error may be one rank's alone.
class CollectiveError : public Error {
 public:
  using Error::Error;
};

}  // namespace upgrain
