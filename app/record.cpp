// app/record.cpp: the recording loop (simulate a frame's worth of fixed steps, render, read back,
// write the PNG), the progress bar, the contact sheet and the ffmpeg subprocess. When the device
// is lost, the frames written stay (each complete) and the error says which; no contact sheet or
// video is made of the unfinished run.
#include "app/record.h"

#include "app/headless.h"
#include "app/image_io.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "gpu/check.h"
#include "gpu/frame.h"
#include "renderer/renderer.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sys/wait.h>
#include <unistd.h>

namespace wisp {

namespace {

std::string framePath(const std::filesystem::path& dir, uint32_t index)
{
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%05u.png", index);
    return (dir / name).string();
}

void progress(uint32_t done, uint32_t total, double elapsed)
{
    bool tty = isatty(STDERR_FILENO) != 0;
    if (!tty && done != total && done % std::max(1u, total / 10) != 0)
        return; // logs get a line every 10%
    constexpr int kWidth = 30;
    int filled = int(double(kWidth) * done / std::max(total, 1u));
    double eta = done > 0 ? elapsed / done * (total - done) : 0.0;
    std::fprintf(stderr, "%srecord [%s%s] %u/%u frames, %.1f s, ETA %.1f s%s", tty ? "\r" : "",
                 std::string(size_t(filled), '#').c_str(), std::string(size_t(kWidth - filled), '.').c_str(), done,
                 total, elapsed, eta, tty && done != total ? "" : "\n");
    std::fflush(stderr);
}

// Up to 12 frames, evenly spaced, each shrunk 4x by box filtering, in a grid of 4 columns.
void writeContactSheet(const std::filesystem::path& path, const std::vector<Picture>& frames)
{
    if (frames.empty())
        return;
    constexpr uint32_t kShrink = 4, kColumns = 4;
    uint32_t w = std::max(1u, frames[0].width / kShrink), h = std::max(1u, frames[0].height / kShrink);
    uint32_t columns = std::min<uint32_t>(kColumns, uint32_t(frames.size()));
    uint32_t rows = (uint32_t(frames.size()) + columns - 1) / columns;
    std::vector<uint8_t> sheet(size_t(w) * columns * h * rows * 4, 255);
    for (size_t f = 0; f < frames.size(); ++f) {
        const Picture& p = frames[f];
        uint32_t ox = uint32_t(f % columns) * w, oy = uint32_t(f / columns) * h;
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x)
                for (int c = 0; c < 4; ++c) {
                    uint32_t sum = 0, n = 0;
                    for (uint32_t dy = 0; dy < kShrink; ++dy)
                        for (uint32_t dx = 0; dx < kShrink; ++dx) {
                            uint32_t sx = std::min(p.width - 1, x * kShrink + dx),
                                     sy = std::min(p.height - 1, y * kShrink + dy);
                            sum += p.rgba[(size_t(sy) * p.width + sx) * 4 + size_t(c)];
                            ++n;
                        }
                    sheet[((size_t(oy + y) * w * columns) + ox + x) * 4 + size_t(c)] = uint8_t(sum / n);
                }
    }
    writePng(path, w * columns, h * rows, sheet);
}

void encodeVideo(const std::filesystem::path& dir, const std::filesystem::path& video, float fps)
{
    writeAtomically(video, [&](const std::filesystem::path& temp) {
        std::string command =
            "ffmpeg -nostdin -hide_banner -loglevel error -y -framerate " + std::to_string(fps) + " -i '" +
            (dir / "frame_%05d.png").string() +
            "' -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' -c:v libx264 -pix_fmt yuv420p -movflags +faststart '" +
            temp.string() + "'";
        int status = std::system(command.c_str());
        if (status != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
            throw UserError("--video " + video.string() + ": ffmpeg failed (exit status " +
                            std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + "); the PNG frames are in " +
                            dir.string());
        return true;
    });
}

// What is left after the device was lost with `written` frames done: complete PNGs (each written
// under a temporary name and renamed), but no contact sheet and no video of an unfinished run.
std::string leftAfterLoss(const RecordOptions& o, uint32_t written)
{
    std::string last = std::filesystem::path(framePath(o.outDir, written == 0 ? 0 : written - 1)).filename().string();
    std::string left =
        written == 0 ? "no frame was written"
        : written == 1
            ? "1 of " + std::to_string(o.frames) + " frames is in " + o.outDir.string() + " (" + last + ", complete)"
            : std::to_string(written) + " of " + std::to_string(o.frames) + " frames are in " + o.outDir.string() +
                  " (frame_00000.png .. " + last + ", each complete)";
    left += "; no contact sheet";
    if (!o.video.empty())
        left += ", and no video (" + o.video.string() + " is not made from an unfinished run)";
    return left;
}

// Simulates, renders and writes the frames, counting in `written` those on disk; returns the
// contact sheet's pictures.
std::vector<Picture> recordFrames(const vk::Context& ctx, HairSession& session, const RecordOptions& o,
                                  uint32_t& written)
{
    Renderer renderer(ctx, o.settings, 1);
    renderer.setHead(session.scene().head);
    session.attachTo(renderer);
    Frame frame(ctx, 1);
    OrbitCamera framing =
        OrbitCamera::framing(renderer.sceneBounds(), float(o.settings.width) / float(o.settings.height));
    uint32_t stepsPerFrame = session.clock().stepsPerFrame(o.fps);
    std::vector<Picture> sheet;
    uint32_t sheetEvery = std::max(1u, (o.frames + 11) / 12);
    auto start = std::chrono::steady_clock::now();
    MemorySample memoryStart;
    for (uint32_t f = 0; f < o.frames; ++f) {
        renderer.setSteps(session.nextSteps(stepsPerFrame)); // without hair, time passes for the camera and light
        OrbitCamera camera = poseFrame(renderer, session.timeline(), session.clock().seconds(), framing);
        Picture picture = renderFrame(ctx, renderer, frame, camera);
        writePng(framePath(o.outDir, f), picture.width, picture.height, picture.rgba);
        written = f + 1;
        if (f % sheetEvery == 0)
            sheet.push_back(std::move(picture));
        if (f == 0)
            memoryStart = sampleMemory(); // after the first frame: every resource exists
        progress(f + 1, o.frames, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    // Before the contact sheet and the video, which the loop does not hold: a long recording's
    // memory stays flat (the soak test compares these).
    std::fprintf(stderr, "record: memory after frame 1 and frame %u: %s\n", o.frames,
                 describeMemory(memoryStart, sampleMemory()).c_str());
    return sheet;
}

} // namespace

void checkRecordOutputs(const RecordOptions& o)
{
    std::error_code ec;
    if (std::filesystem::exists(o.outDir, ec) && !std::filesystem::is_directory(o.outDir, ec))
        throw UserError("--out " + o.outDir.string() + ": exists and is not a folder");
    std::filesystem::path parent = o.outDir.parent_path().empty() ? "." : o.outDir.parent_path();
    if (!std::filesystem::is_directory(parent, ec))
        throw UserError("--out " + o.outDir.string() + ": folder '" + parent.string() + "' does not exist");
    if (!o.video.empty()) {
        std::filesystem::path dir = o.video.parent_path().empty() ? "." : o.video.parent_path();
        if (!std::filesystem::is_directory(dir, ec))
            throw UserError("--video " + o.video.string() + ": folder '" + dir.string() + "' does not exist");
        if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
            throw UserError("--video: ffmpeg is not installed (Debian package ffmpeg)");
    }
}

int runRecord(const vk::Context& ctx, HairSession& session, const RecordOptions& o)
{
    checkRecordOutputs(o);
    std::filesystem::create_directories(o.outDir);
    uint32_t written = 0;
    std::vector<Picture> sheet;
    try {
        sheet = recordFrames(ctx, session, o, written);
    } catch (const vk::DeviceLost& e) {
        if (written > 0 && isatty(STDERR_FILENO))
            std::fputc('\n', stderr); // ends the progress bar's line
        throw vk::DeviceLost(e.what() + std::string("; ") + leftAfterLoss(o, written));
    }
    writeContactSheet(o.outDir / "contact_sheet.png", sheet);
    if (!o.video.empty())
        encodeVideo(o.outDir, o.video, o.fps);
    std::printf("%s\n", o.outDir.string().c_str());
    if (!o.video.empty())
        std::printf("%s\n", o.video.string().c_str());
    if (ctx.validationMessages() > 0) {
        std::fprintf(stderr, "wisp: %u Vulkan validation messages (printed above)\n", ctx.validationMessages());
        return kExitInternalError;
    }
    return 0;
}

} // namespace wisp
