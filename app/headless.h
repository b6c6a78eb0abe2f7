// app/headless.h: the headless front end: renders frames into the offscreen target and reads
// them back. Used by `wisp render` (and later `record` and `sweep`), and by the rendering tests.
#pragma once

#include "physics/head.h"
#include "renderer/camera.h"
#include "renderer/settings.h"
#include "renderer/vk/context.h"

#include <cstdint>
#include <vector>

namespace wisp {

struct Picture {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;  // tightly packed, top row first, sRGB
};

// Renders one frame of `head` as the default camera frames it. Deterministic for a device.
Picture renderPicture(const vk::Context& ctx, const Head& head, const RenderSettings& settings);

}  // namespace wisp
