// gpu/check.cpp: names for VkResult values and the failure path of VK_CHECK (DeviceLost
// for a lost device, std::runtime_error for anything else).
#include "gpu/check.h"

#include <string>

namespace wisp::vk {

const char* resultName(VkResult result)
{
    switch (result) {
#define WISP_RESULT(name)                                                                                              \
    case name:                                                                                                         \
        return #name;
        WISP_RESULT(VK_SUCCESS)
        WISP_RESULT(VK_NOT_READY)
        WISP_RESULT(VK_TIMEOUT)
        WISP_RESULT(VK_EVENT_SET)
        WISP_RESULT(VK_EVENT_RESET)
        WISP_RESULT(VK_INCOMPLETE)
        WISP_RESULT(VK_SUBOPTIMAL_KHR)
        WISP_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
        WISP_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        WISP_RESULT(VK_ERROR_INITIALIZATION_FAILED)
        WISP_RESULT(VK_ERROR_DEVICE_LOST)
        WISP_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
        WISP_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
        WISP_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
        WISP_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
        WISP_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
        WISP_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
        WISP_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
        WISP_RESULT(VK_ERROR_FRAGMENTED_POOL)
        WISP_RESULT(VK_ERROR_UNKNOWN)
        WISP_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
        WISP_RESULT(VK_ERROR_SURFACE_LOST_KHR)
        WISP_RESULT(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        WISP_RESULT(VK_ERROR_OUT_OF_DATE_KHR)
#undef WISP_RESULT
    default:
        return "VkResult (unnamed)";
    }
}

void failCheck(const char* call, VkResult result, const char* file, int line)
{
    std::string where = std::string(file) + ":" + std::to_string(line);
    if (result == VK_ERROR_DEVICE_LOST)
        throw DeviceLost(std::string(call) + " at " + where);
    throw std::runtime_error(std::string(call) + " failed with " + resultName(result) + " (" +
                             std::to_string(static_cast<int>(result)) + ") at " + where);
}

} // namespace wisp::vk
