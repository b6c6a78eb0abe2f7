// app/image/image_io.cpp: PNG writing through Debian's stb_image_write (encoded in memory) and
// OpenEXR writing of our own (uncompressed scanlines: a header and the pixels), both written
// atomically and checked by core/atomic_file.h, and PNG reading through stb_image.
#include "app/image/image_io.h"

#include "core/atomic_file.h"
#include "core/error.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace wisp {

void checkOutputFolder(const std::filesystem::path& dir, const std::string& what)
{
    std::error_code ec;
    if (std::filesystem::is_directory(dir, ec))
        return;
    // The nearest part of the path that exists: a file there is why the folder cannot be.
    for (std::filesystem::path p = dir; !p.empty(); p = p.parent_path()) {
        std::filesystem::file_status status = std::filesystem::status(p, ec);
        if (std::filesystem::exists(status) && !std::filesystem::is_directory(status))
            throw UserError(what + ": '" + p.string() + "' is a file, not a folder");
        if (std::filesystem::exists(status) || p == p.parent_path())
            break;
    }
    throw UserError(what + ": folder '" + dir.string() + "' does not exist");
}

namespace {

// The output's folder exists and is writable, and the path is no folder.
void checkOutputPath(const std::filesystem::path& path)
{
    std::filesystem::path dir = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
    checkOutputFolder(dir, "--out " + path.string());
    std::error_code ec;
    if (access(dir.c_str(), W_OK) != 0)
        throw UserError("--out " + path.string() + ": folder '" + dir.string() + "' is not writable");
    if (std::filesystem::is_directory(path, ec))
        throw UserError("--out " + path.string() + ": is a directory");
}

} // namespace

void checkPngOutput(const std::filesystem::path& path)
{
    if (path.extension() != ".png")
        throw UserError("--out " + path.string() + ": the output must be a .png file");
    checkOutputPath(path);
}

void writePng(const std::filesystem::path& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba)
{
    checkPngOutput(path);
    int stride = static_cast<int>(width * 4);
    // Encoded in memory, then written by core/atomic_file.h's checked writes: stbi_write_png's own
    // file writing ignores fwrite's and fclose's results, so a full disk would pass unnoticed.
    std::string bytes;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    if (stbi_write_png_to_func(append, &bytes, static_cast<int>(width), static_cast<int>(height), 4, rgba.data(),
                               stride) == 0)
        throw UserError("cannot write " + path.string() + ": the PNG could not be encoded");
    writeFileAtomically(path, bytes);
}

bool isExrPath(const std::filesystem::path& path)
{
    return path.extension() == ".exr";
}

void checkImageOutput(const std::filesystem::path& path)
{
    if (path.extension() != ".png" && !isExrPath(path))
        throw UserError("--out " + path.string() + ": the output must be a .png or an .exr file");
    checkOutputPath(path);
}

namespace {

// Little-endian fields of the OpenEXR file layout.
void putU8(std::string& out, uint8_t v)
{
    out.push_back(char(v));
}
void putI32(std::string& out, int32_t v)
{
    auto u = uint32_t(v);
    for (int k = 0; k < 4; ++k)
        putU8(out, uint8_t(u >> (8 * k)));
}
void putU64(std::string& out, uint64_t v)
{
    for (int k = 0; k < 8; ++k)
        putU8(out, uint8_t(v >> (8 * k)));
}
void putF32(std::string& out, float v)
{
    uint32_t u = 0;
    std::memcpy(&u, &v, 4);
    putI32(out, int32_t(u));
}
// An attribute: its name, its type's name, its size, then its value (`value` appends it).
template <typename F> void putAttribute(std::string& out, const char* name, const char* type, F value)
{
    out += name;
    out.push_back('\0');
    out += type;
    out.push_back('\0');
    std::string v;
    value(v);
    putI32(out, int32_t(v.size()));
    out += v;
}

} // namespace

std::string encodeExr(uint32_t width, uint32_t height, const std::vector<float>& rgba)
{
    if (rgba.size() != size_t(width) * height * 4)
        throw std::logic_error("encodeExr: the pixels are not width x height RGBA");
    std::string out;
    putI32(out, 20000630);                          // the magic number
    putI32(out, 2);                                 // version 2; no flags: one part of scanlines, short names
    const char* channels[4] = {"A", "B", "G", "R"}; // sorted by name, as the format requires
    const int source[4] = {3, 2, 1, 0};             // each channel's place in an RGBA pixel
    putAttribute(out, "channels", "chlist", [&](std::string& v) {
        for (const char* c : channels) {
            v += c;
            v.push_back('\0');
            putI32(v, 2); // FLOAT
            putU8(v, 0);  // pLinear
            putU8(v, 0), putU8(v, 0), putU8(v, 0);
            putI32(v, 1), putI32(v, 1); // x and y sampling
        }
        v.push_back('\0');
    });
    putAttribute(out, "compression", "compression", [](std::string& v) { putU8(v, 0); }); // none
    auto window = [&](std::string& v) {
        putI32(v, 0), putI32(v, 0), putI32(v, int32_t(width) - 1), putI32(v, int32_t(height) - 1);
    };
    putAttribute(out, "dataWindow", "box2i", window);
    putAttribute(out, "displayWindow", "box2i", window);
    putAttribute(out, "lineOrder", "lineOrder", [](std::string& v) { putU8(v, 0); }); // increasing y
    putAttribute(out, "pixelAspectRatio", "float", [](std::string& v) { putF32(v, 1.0f); });
    putAttribute(out, "screenWindowCenter", "v2f", [](std::string& v) { putF32(v, 0.0f), putF32(v, 0.0f); });
    putAttribute(out, "screenWindowWidth", "float", [](std::string& v) { putF32(v, 1.0f); });
    putU8(out, 0); // the header's end
    // The offset table (one chunk a scanline), then each chunk: y, its size, each channel's row.
    uint64_t rowBytes = uint64_t(width) * 4 * 4;
    uint64_t first = out.size() + uint64_t(height) * 8;
    for (uint32_t y = 0; y < height; ++y)
        putU64(out, first + y * (8 + rowBytes));
    std::vector<float> row(width);
    for (uint32_t y = 0; y < height; ++y) {
        putI32(out, int32_t(y));
        putI32(out, int32_t(rowBytes));
        for (int c = 0; c < 4; ++c) {
            for (uint32_t x = 0; x < width; ++x)
                row[x] = rgba[(size_t(y) * width + x) * 4 + size_t(source[c])];
            for (float f : row)
                putF32(out, f);
        }
    }
    return out;
}

void writeExr(const std::filesystem::path& path, uint32_t width, uint32_t height, const std::vector<float>& rgba)
{
    checkImageOutput(path);
    writeFileAtomically(path, encodeExr(width, height, rgba));
}

PngImage readPng(const std::filesystem::path& path, const std::string& what)
{
    std::string where = what + " " + path.string() + ": ";
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw UserError(where + "no such file");
    if (std::filesystem::is_directory(path, ec))
        throw UserError(where + "is a folder, not a PNG file");
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof())
        throw UserError(where + "cannot be read");
    // stb_image reads JPEG, BMP, ... too: only the signature (PNG spec 5.2) says it is a PNG.
    constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < 8 ||
        !std::equal(kSignature, kSignature + 8, reinterpret_cast<const unsigned char*>(bytes.data())))
        throw UserError(where + "not a PNG file (it does not start with the PNG signature)");
    if (bytes.size() > size_t(std::numeric_limits<int>::max()))
        throw UserError(where + "is larger than 2 GiB, more than the PNG reader takes");
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<stbi_us, void (*)(void*)> pixels(
        stbi_load_16_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &width, &height,
                                 &channels, 4),
        stbi_image_free);
    if (!pixels)
        throw UserError(where + "cannot decode the PNG (" + stbi_failure_reason() + ")");
    PngImage image{.width = uint32_t(width), .height = uint32_t(height), .rgba = {}};
    image.rgba.assign(pixels.get(), pixels.get() + size_t(width) * size_t(height) * 4);
    return image;
}

} // namespace wisp
