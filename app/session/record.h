// app/session/record.h: `wisp record`: a run rendered frame by frame offscreen into a folder of PNGs, with
// a video through an ffmpeg subprocess and a contact sheet. Fixed steps only (exactly
// round(step_hz / fps) per frame) and the fixed-point hair grid: the same command gives the same
// frames, byte for byte, on the same device. A scene's timeline poses every step and frame.
#pragma once

#include "app/session/hair_session.h"
#include "gpu/context.h"
#include "renderer/settings.h"

#include <filesystem>
#include <string>
#include <vector>

namespace wisp {

struct RecordOptions {
    std::filesystem::path outDir; // frame_00000.png ... and contact_sheet.png
    std::filesystem::path video;  // empty: no video
    uint32_t frames = 120;
    float fps = 30.0f;
    bool overwrite = false; // delete an earlier run's frames and sheet in outDir first (else refused)
    RenderSettings settings;
};

// The contact sheet: every frame up to kSheetMostFrames, else that many chosen evenly (the first
// and the last among them); each shrunk by a whole factor (box filter) to at least
// kSheetThumbnailWidth pixels wide (a narrower frame stays whole), kSheetColumns to a row,
// kSheetGutter pixels apart, with its frame number in white on black in its top-left corner.
inline constexpr uint32_t kSheetMostFrames = 48;
inline constexpr uint32_t kSheetThumbnailWidth = 240;
inline constexpr uint32_t kSheetColumns = 6;
inline constexpr uint32_t kSheetGutter = 4;
struct ContactSheetLayout {
    std::vector<uint32_t> frames; // the frames shown, in order
    uint32_t shrink = 1;          // each thumbnail pixel is the mean of shrink x shrink frame pixels
    uint32_t thumbWidth = 0, thumbHeight = 0;
    uint32_t columns = 0, rows = 0;
    uint32_t width = 0, height = 0; // the sheet's
    uint32_t digitScale = 1;        // pixels per dot of the 3 x 5 digits
    uint32_t cellX(size_t cell) const { return uint32_t(cell % columns) * (thumbWidth + kSheetGutter); }
    uint32_t cellY(size_t cell) const { return uint32_t(cell / columns) * (thumbHeight + kSheetGutter); }
    // The label's box at the cell's top-left corner (clipped to the thumbnail).
    uint32_t labelWidth(uint32_t frame) const;
    uint32_t labelHeight() const;
};
ContactSheetLayout contactSheetLayout(uint32_t frames, uint32_t width, uint32_t height);

// Fails (UserError) before any work when the folder or the video cannot be written, or when the
// folder holds an earlier run's frames and `overwrite` is off (runs are never mixed).
void checkRecordOutputs(const RecordOptions& options);
// Records `session`'s run: its timeline poses every step (at the step's end) and frame (frame f,
// drawn after its steps, shows the moment (f + 1) x steps per frame / step_hz). With `overwrite`, an
// earlier run's frames and sheet in the folder are deleted before the first frame. When the device is
// lost, throws vk::DeviceLost saying which frames were written (each a complete PNG); no contact
// sheet or video is made.
int runRecord(const vk::Context& ctx, HairSession& session, const RecordOptions& options);

} // namespace wisp
