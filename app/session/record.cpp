// app/session/record.cpp: the recording loop (simulate a frame's worth of fixed steps, render, read back,
// write the PNG), the progress bar, the contact sheet (numbered thumbnails, filled as the frames
// come) and the ffmpeg subprocess; an earlier run's frames in the folder are refused or, asked to,
// deleted first. When the device is lost, the frames written stay (each complete) and the error
// says which; no contact sheet or video is made of the unfinished run.
#include "app/session/record.h"

#include "app/image/image_io.h"
#include "app/session/headless.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "gpu/check.h"
#include "gpu/frame.h"
#include "renderer/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <regex>
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

// 3 x 5 dot digits, row by row from the top, the left dot the highest of each row's three bits.
constexpr uint16_t kDigits[10] = {
    0b111'101'101'101'111, 0b010'110'010'010'111, 0b111'001'111'100'111, 0b111'001'111'001'111, 0b101'101'111'001'001,
    0b111'100'111'001'111, 0b111'100'111'101'111, 0b111'001'001'001'001, 0b111'101'111'101'111, 0b111'101'111'001'111};

// A contact sheet filled as the frames come: each shown frame shrunk into its cell and numbered.
class ContactSheet {
public:
    ContactSheet(uint32_t frames, uint32_t width, uint32_t height)
        : layout_(contactSheetLayout(frames, width, height)), rgba_(size_t(layout_.width) * layout_.height * 4, 0)
    {
        for (size_t i = 3; i < rgba_.size(); i += 4)
            rgba_[i] = 255; // opaque black gutters
    }

    void add(uint32_t frame, const Picture& p)
    {
        auto shown = std::find(layout_.frames.begin(), layout_.frames.end(), frame);
        if (shown == layout_.frames.end())
            return;
        size_t cell = size_t(shown - layout_.frames.begin());
        uint32_t ox = layout_.cellX(cell), oy = layout_.cellY(cell), k = layout_.shrink;
        for (uint32_t y = 0; y < layout_.thumbHeight; ++y)
            for (uint32_t x = 0; x < layout_.thumbWidth; ++x)
                for (size_t c = 0; c < 4; ++c) {
                    uint32_t sum = 0;
                    for (uint32_t dy = 0; dy < k; ++dy)
                        for (uint32_t dx = 0; dx < k; ++dx)
                            sum += p.rgba[(size_t(y * k + dy) * p.width + x * k + dx) * 4 + c];
                    at(ox + x, oy + y)[c] = uint8_t((sum + k * k / 2) / (k * k));
                }
        label(cell, frame);
    }

    void write(const std::filesystem::path& path) const { writePng(path, layout_.width, layout_.height, rgba_); }

private:
    uint8_t* at(uint32_t x, uint32_t y) { return &rgba_[(size_t(y) * layout_.width + x) * 4]; }

    // The frame's number, white dots on a black box, clipped to the thumbnail.
    void label(size_t cell, uint32_t frame)
    {
        std::string digits = std::to_string(frame);
        uint32_t s = layout_.digitScale, ox = layout_.cellX(cell), oy = layout_.cellY(cell);
        uint32_t w = std::min(layout_.labelWidth(frame), layout_.thumbWidth);
        uint32_t h = std::min(layout_.labelHeight(), layout_.thumbHeight);
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                bool dot = false;
                if (x >= s && y >= s && y < 6 * s) {
                    uint32_t slot = (x - s) / (4 * s), column = (x - s) % (4 * s) / s, row = (y - s) / s;
                    if (slot < digits.size() && column < 3)
                        dot = (kDigits[digits[slot] - '0'] >> (14 - (row * 3 + column))) & 1u;
                }
                uint8_t* px = at(ox + x, oy + y);
                px[0] = px[1] = px[2] = dot ? 255 : 0;
                px[3] = 255;
            }
    }

    ContactSheetLayout layout_;
    std::vector<uint8_t> rgba_;
};

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

// Simulates, renders and writes the frames, counting in `written` those on disk; fills the sheet.
void recordFrames(const vk::Context& ctx, HairSession& session, const RecordOptions& o, ContactSheet& sheet,
                  uint32_t& written)
{
    Renderer renderer(ctx, o.settings, 1);
    renderer.setHead(session.scene().head);
    session.attachTo(renderer);
    Frame frame(ctx, 1);
    OrbitCamera framing =
        OrbitCamera::framing(renderer.sceneBounds(), float(o.settings.width) / float(o.settings.height));
    uint32_t stepsPerFrame = session.clock().stepsPerFrame(o.fps);
    auto start = std::chrono::steady_clock::now();
    MemorySample memoryStart;
    for (uint32_t f = 0; f < o.frames; ++f) {
        renderer.setSteps(session.nextSteps(stepsPerFrame)); // without hair, time passes for the camera and light
        OrbitCamera camera = poseFrame(renderer, session.timeline(), session.clock().seconds(), framing);
        Picture picture = renderFrame(ctx, renderer, frame, camera);
        writePng(framePath(o.outDir, f), picture.width, picture.height, picture.rgba);
        written = f + 1;
        sheet.add(f, picture);
        if (f == 0)
            memoryStart = sampleMemory(); // after the first frame: every resource exists
        progress(f + 1, o.frames, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    // Before the contact sheet and the video, which the loop does not hold: a long recording's
    // memory stays flat (the soak test compares these).
    std::fprintf(stderr, "record: memory after frame 1 and frame %u: %s\n", o.frames,
                 describeMemory(memoryStart, sampleMemory()).c_str());
}

bool isEarlierRunFile(const std::filesystem::path& name)
{
    static const std::regex frame(R"(frame_\d{5,}\.png)");
    std::string n = name.filename().string();
    return n == "contact_sheet.png" || std::regex_match(n, frame);
}

// The frames and contact sheet of an earlier run in `dir`, in name order.
std::vector<std::filesystem::path> earlierRun(const std::filesystem::path& dir)
{
    std::vector<std::filesystem::path> found;
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
        return found;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
        if (isEarlierRunFile(entry.path()))
            found.push_back(entry.path());
    std::sort(found.begin(), found.end());
    return found;
}

} // namespace

uint32_t ContactSheetLayout::labelWidth(uint32_t frame) const
{
    uint32_t digits = uint32_t(std::to_string(frame).size());
    return digitScale * (4 * digits + 1); // a dot of margin, then 3 dots and a gap per digit
}

uint32_t ContactSheetLayout::labelHeight() const
{
    return digitScale * 7;
}

ContactSheetLayout contactSheetLayout(uint32_t frames, uint32_t width, uint32_t height)
{
    ContactSheetLayout l;
    uint32_t shown = std::min(frames, kSheetMostFrames);
    for (uint32_t i = 0; i < shown; ++i)
        l.frames.push_back(shown == frames ? i
                                           : uint32_t((uint64_t(i) * (frames - 1) + (shown - 1) / 2) / (shown - 1)));
    l.shrink = std::max(1u, width / kSheetThumbnailWidth);
    l.thumbWidth = width / l.shrink;
    l.thumbHeight = std::max(1u, height / l.shrink);
    l.columns = std::max(1u, std::min(kSheetColumns, shown));
    l.rows = (shown + l.columns - 1) / l.columns;
    l.width = l.columns * l.thumbWidth + (l.columns - 1) * kSheetGutter;
    l.height = l.rows * l.thumbHeight + (l.rows > 0 ? l.rows - 1 : 0) * kSheetGutter;
    l.digitScale = std::max(2u, l.thumbWidth / 80);
    return l;
}

void checkRecordOutputs(const RecordOptions& o)
{
    std::error_code ec;
    if (std::filesystem::exists(o.outDir, ec) && !std::filesystem::is_directory(o.outDir, ec))
        throw UserError("--out " + o.outDir.string() + ": exists and is not a folder");
    std::filesystem::path parent = o.outDir.parent_path().empty() ? "." : o.outDir.parent_path();
    checkOutputFolder(parent, "--out " + o.outDir.string());
    if (!o.overwrite) {
        std::vector<std::string> frames;
        bool sheet = false;
        for (const std::filesystem::path& p : earlierRun(o.outDir))
            if (p.filename() == "contact_sheet.png")
                sheet = true;
            else
                frames.push_back(p.filename().string());
        std::string held = frames.empty()       ? std::string()
                           : frames.size() == 1 ? "1 frame (" + frames[0] + ")"
                                                : std::to_string(frames.size()) + " frames (" + frames.front() +
                                                      " .. " + frames.back() + ")";
        if (sheet)
            held += std::string(held.empty() ? "" : " and ") + "a contact sheet";
        if (!held.empty())
            throw UserError("--out " + o.outDir.string() + ": holds " + held +
                            " of an earlier run; record into an empty folder, or add --overwrite to delete them first");
    }
    if (!o.video.empty()) {
        std::filesystem::path dir = o.video.parent_path().empty() ? "." : o.video.parent_path();
        checkOutputFolder(dir, "--video " + o.video.string());
        if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
            throw UserError("--video: ffmpeg is not installed (Debian package ffmpeg)");
    }
}

int runRecord(const vk::Context& ctx, HairSession& session, const RecordOptions& o)
{
    checkRecordOutputs(o);
    std::filesystem::create_directories(o.outDir);
    for (const std::filesystem::path& old : earlierRun(o.outDir)) // only with --overwrite (else refused above)
        std::filesystem::remove(old);
    uint32_t written = 0;
    ContactSheet sheet(o.frames, o.settings.width, o.settings.height);
    try {
        recordFrames(ctx, session, o, sheet, written);
    } catch (const vk::DeviceLost& e) {
        if (written > 0 && isatty(STDERR_FILENO))
            std::fputc('\n', stderr); // ends the progress bar's line
        throw vk::DeviceLost(e.what() + std::string("; ") + leftAfterLoss(o, written));
    }
    sheet.write(o.outDir / "contact_sheet.png");
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
