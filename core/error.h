// core/error.h: the kinds of failure Wisp reports, and the exit status of each. A UserError is
// something the person can fix (a bad file, option or value, no suitable GPU): main prints its
// one-line message and exits 2. A lost GPU device (vk::DeviceLost, gpu/check.h) exits 3.
// Anything else is an internal error: main prints it and exits 1.
#pragma once

#include <stdexcept>
#include <string>

namespace wisp {

class UserError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

inline constexpr int kExitInternalError = 1; // a bug, or validation messages with --validation
inline constexpr int kExitUserError = 2;     // bad input or environment: nothing was written
inline constexpr int kExitDeviceLost = 3;    // the GPU device was lost mid-run (VK_ERROR_DEVICE_LOST)

} // namespace wisp
