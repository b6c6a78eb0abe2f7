// core/error.h: the two kinds of failure Wisp reports. A UserError is something the person can fix
// (a bad file, option or value, no suitable GPU): main prints its one-line message and exits 2.
// Anything else is an internal error: main prints it and exits 1.
#pragma once

#include <stdexcept>
#include <string>

namespace wisp {

class UserError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

inline constexpr int kExitUserError = 2;
inline constexpr int kExitInternalError = 1;

}  // namespace wisp
