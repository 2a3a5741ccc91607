// Error types thrown by libsol.
//
// Every public function of libsol validates its arguments: a NaN or infinite
// coordinate, a zero direction or an out-of-range option throws
// sol::InvalidArgument (a std::invalid_argument) whose message names the
// function and the offending argument. libsol never returns a silent NaN.
#pragma once

#include <stdexcept>
#include <string>

namespace sol {

/// A libsol message without the function it names ("sol::aim: the target
/// ..." -> "the target ..."): for a caller that names its own field or
/// option instead (a scene file's key, a program's option).
inline std::string without_function(const std::string& what) {
  const std::size_t cut = what.rfind("sol::", 0) == 0 ? what.find(": ") : std::string::npos;
  return cut == std::string::npos ? what : what.substr(cut + 2);
}

/// Thrown when an argument is NaN, infinite or otherwise invalid.
class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Thrown when a result does not fit in double (for example a geodesic so
/// long that e^{z} overflows).
class OutOfRange : public std::range_error {
 public:
  using std::range_error::range_error;
};

/// Thrown when a requested feature (for example a Method) is not available.
class NotImplemented : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// Thrown by a render that was asked to stop (sol::RenderOptions::cancel)
/// before it finished.
class Cancelled : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace sol
