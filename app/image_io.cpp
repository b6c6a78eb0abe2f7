// app/image_io.cpp: PNG writing through Debian's stb_image_write, made atomic by core/atomic_file.h.
#include "app/image_io.h"

#include "core/atomic_file.h"
#include "core/error.h"

#include <stb_image_write.h>

#include <unistd.h>

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
    writeAtomically(path, [&](const std::filesystem::path& temp) {
        return stbi_write_png(temp.c_str(), static_cast<int>(width), static_cast<int>(height), 4, rgba.data(),
                              stride) != 0;
    });
}

} // namespace wisp
