// renderer/oit_stats.h: what the front ends see of the graphics path's per-pixel lists
// (renderer/graphics/oit.h) without knowing that path: the counts a frame reports, the advice
// when a frame dropped fragments, and the device memory the lists take (summed by the device-free
// workload check, app/settings/workload.cpp).
#pragma once

#include "gpu/resources.h"
#include "shaders/shared/shadows.h"

#include <cstdint>
#include <string>

namespace wisp {

struct OitStats {
    uint64_t fragments = 0; // fragments the hair produced last frame (stored + dropped)
    uint64_t overflow = 0;  // of those, dropped because the pool was full
    uint64_t capacity = 0;  // nodes in the pool
    uint64_t limit = 0;     // the most nodes the device allows the pool (one buffer, half its memory)
    bool automatic = true;  // sized by Wisp (oit_nodes_per_pixel=0), so it grows when a frame overflows
};

// What to tell a person whose frame dropped fragments: a pool of their own (oit_nodes_per_pixel)
// that the device could make large enough: the value that would hold them; one the device cannot
// make large enough (or the automatic pool at the device's limit): transparency=msaa or a
// smaller picture.
std::string oitOverflowAdvice(const OitStats& stats, uint32_t width, uint32_t height);

// The lists' resolved colour.
inline constexpr VkFormat kOitColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
// The device memory of the lists for a picture of `extent`: per pixel a list head, the resolved
// colour, and the node pool (`nodesPerPixel`; an automatic pool, 0, counts one node a pixel, the
// least it takes).
constexpr uint64_t oitDeviceBytes(VkExtent2D extent, uint32_t nodesPerPixel)
{
    uint64_t nodes = nodesPerPixel > 0 ? nodesPerPixel : 1;
    return uint64_t(extent.width) * extent.height *
           (sizeof(uint32_t) + vk::formatBytes(kOitColorFormat) + nodes * sizeof(gpu::OitNode));
}

} // namespace wisp
