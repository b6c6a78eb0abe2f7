// app/window/window.h: the interactive front end: a GLFW window whose swapchain receives the renderer's
// result by a blit each frame, with the hair simulated live by a hair session (real time is spent
// in fixed steps, at most 8 a frame; with --frames, exactly one 60 Hz frame's worth of steps per
// frame, so a scripted run is reproducible). The keys and drags are app/window/viewer.h's; the
// title bar shows the state and the help line. Resize and minimize are handled. Without a display
// it says so and points to `wisp render`.
#pragma once

#include "app/scene/scene_timeline.h"
#include "app/settings/hair_source.h"
#include "app/settings/settings_table.h"
#include "gpu/context.h"
#include "physics/groomed_head.h"
#include "physics/simulation.h"
#include "renderer/settings.h"

#include <cstdint>
#include <string>

namespace wisp {

struct WindowOptions {
    vk::ContextOptions context;
    Settings settings;            // every setting, edited live in the panel
    GroomedHead scene;            // the head and its hair (no strands: the head alone)
    glm::vec4 sphere{0.0f};       // the user's sphere (xyz, radius; 0 = none)
    uint32_t maxFrames = 0;       // 0 = until the window is closed
    std::string screenshot;       // PNG of the last frame, written on exit when set
    std::string script;           // timed input events (app/window/viewer.h), replayed by frame number
    bool screenshotPanel = false; // the screenshot includes the panel (else the scene alone)
    // A scene's keys, played from the start (T toggles playing; the keys and drags work while it
    // is stopped), and what F2 saves the window's state with.
    SceneTimeline timeline;
    double sceneLength = 0.0; // seconds; 0: nothing to play
    HairSource source;        // the head and hair as given (what F2 saves)
};

// Throws UserError, pointing to `wisp render`, when there is no display to open a window on.
void requireDisplay();
int runWindow(WindowOptions options);

} // namespace wisp
