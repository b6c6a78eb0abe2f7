// app/window.h: the interactive front end: a GLFW window whose swapchain receives the renderer's
// result by a blit each frame. Orbit (left drag), zoom (wheel), pan (middle drag), Esc quits;
// resize and minimize are handled. Without a display it says so and points to `wisp render`.
#pragma once

#include "renderer/settings.h"
#include "renderer/vk/context.h"

#include <cstdint>
#include <string>

namespace wisp {

struct WindowOptions {
    vk::ContextOptions context;
    RenderSettings settings;
    std::string headFile;
    uint32_t maxFrames = 0;  // 0 = until the window is closed
    std::string screenshot;  // PNG of the last frame, written on exit when set
};

int runWindow(const WindowOptions& options);

}  // namespace wisp
