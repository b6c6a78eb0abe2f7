// app/record.h: `wisp record`: a run rendered frame by frame offscreen into a folder of PNGs, with
// a video through an ffmpeg subprocess and a contact sheet. Fixed steps only (exactly
// round(step_hz / fps) per frame) and the fixed-point hair grid: the same command gives the same
// frames, byte for byte, on the same device. A scene's timeline poses every step and frame.
#pragma once

#include "app/hair_session.h"
#include "gpu/context.h"
#include "renderer/settings.h"

#include <filesystem>
#include <string>

namespace wisp {

struct RecordOptions {
    std::filesystem::path outDir; // frame_00000.png ... and contact_sheet.png
    std::filesystem::path video;  // empty: no video
    uint32_t frames = 120;
    float fps = 30.0f;
    RenderSettings settings;
};

// Fails (UserError) before any work when the folder or the video cannot be written.
void checkRecordOutputs(const RecordOptions& options);
// Records `session`'s run: its timeline poses every step (at the step's end) and frame (frame f,
// drawn after its steps, shows the moment (f + 1) x steps per frame / step_hz). When the device is
// lost, throws vk::DeviceLost saying which frames were written (each a complete PNG); no contact
// sheet or video is made.
int runRecord(const vk::Context& ctx, HairSession& session, const RecordOptions& options);

} // namespace wisp
