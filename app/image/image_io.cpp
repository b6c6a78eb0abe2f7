// app/image/image_io.cpp: PNG writing through Debian's stb_image_write (encoded in memory), written
// atomically and checked by core/atomic_file.h,
// and PNG reading through its stb_image.
#include "app/image/image_io.h"

#include "core/atomic_file.h"
#include "core/error.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
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

void checkPngOutput(const std::filesystem::path& path)
{
    if (path.extension() != ".png")
        throw UserError("--out " + path.string() + ": the output must be a .png file");
    std::filesystem::path dir = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
    checkOutputFolder(dir, "--out " + path.string());
    std::error_code ec;
    if (access(dir.c_str(), W_OK) != 0)
        throw UserError("--out " + path.string() + ": folder '" + dir.string() + "' is not writable");
    if (std::filesystem::is_directory(path, ec))
        throw UserError("--out " + path.string() + ": is a directory");
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
