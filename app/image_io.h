// app/image_io.h: PNG output that is never half-written (a temporary file in the same folder,
// renamed into place), and checks that an output path can be written before any work is done.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace wisp {

// Throws UserError "WHAT: ..." when `dir` is not a folder: that it does not exist, or which part of
// its path is a file.
void checkOutputFolder(const std::filesystem::path& dir, const std::string& what);
// Throws UserError when `path`'s folder is missing or not writable, or the name is not a .png.
void checkPngOutput(const std::filesystem::path& path);
// Writes tightly packed RGBA8 pixels as a PNG; atomic.
void writePng(const std::filesystem::path& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba);

} // namespace wisp
