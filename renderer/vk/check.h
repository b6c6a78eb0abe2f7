// renderer/vk/check.h: VK_CHECK wraps every Vulkan call; a failure throws with the call's text,
// the VkResult's name, and the file and line. resultName() replaces vk_enum_string_helper.h,
// which Debian's Vulkan headers do not ship.
#pragma once

#include <vulkan/vulkan.h>

namespace wisp::vk {

const char* resultName(VkResult result);
[[noreturn]] void failCheck(const char* call, VkResult result, const char* file, int line);

}  // namespace wisp::vk

#define VK_CHECK(call)                                                        \
    do {                                                                      \
        VkResult vkCheckResult_ = (call);                                     \
        if (vkCheckResult_ != VK_SUCCESS)                                     \
            ::wisp::vk::failCheck(#call, vkCheckResult_, __FILE__, __LINE__); \
    } while (false)
