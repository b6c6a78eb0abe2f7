// gpu/check.h: VK_CHECK wraps every Vulkan call; a failure throws with the call's text,
// the VkResult's name, and the file and line. VK_ERROR_DEVICE_LOST throws DeviceLost, which the
// command line reports on its own. resultName() replaces vk_enum_string_helper.h, which Debian's
// Vulkan headers do not ship.
#pragma once

#include <stdexcept>
#include <vulkan/vulkan.h>

namespace wisp::vk {

// The device was lost (VK_ERROR_DEVICE_LOST: a driver reset, a hang, a removed GPU): nothing more
// runs on it. what() names the call and where it was made, and whatever the caller adds (what
// was written before the loss).
class DeviceLost : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

const char* resultName(VkResult result);
[[noreturn]] void failCheck(const char* call, VkResult result, const char* file, int line);

} // namespace wisp::vk

#define VK_CHECK(call)                                                                                                 \
    do {                                                                                                               \
        VkResult vkCheckResult_ = (call);                                                                              \
        if (vkCheckResult_ != VK_SUCCESS)                                                                              \
            ::wisp::vk::failCheck(#call, vkCheckResult_, __FILE__, __LINE__);                                          \
    } while (false)
