// app/image/image_io.h: PNG output that is never half-written (a temporary file in the same folder,
// renamed into place), checks that an output path can be written before any work is done, and PNG
// input (8 or 16 bits, refused with one line naming the file when it is missing or not a PNG).
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

// Is `path` named .exr (linear output)?
bool isExrPath(const std::filesystem::path& path);
// As checkPngOutput, for a .png or an .exr.
void checkImageOutput(const std::filesystem::path& path);
// The bytes of an OpenEXR file (the format's public file layout: version 2, one part, scanlines,
// no compression, FLOAT channels A, B, G, R, one scanline a chunk) of tightly packed linear RGBA
// floats, top row first (the data window's y = 0), RGB premultiplied by A as OpenEXR's are.
std::string encodeExr(uint32_t width, uint32_t height, const std::vector<float>& rgba);
// The same written to `path`; atomic.
void writeExr(const std::filesystem::path& path, uint32_t width, uint32_t height, const std::vector<float>& rgba);

// A PNG as read: RGBA, 16 bits a channel (an 8-bit file's value v reads as v * 257), top row first.
struct PngImage {
    uint32_t width = 0, height = 0;
    std::vector<uint16_t> rgba;
};
// Reads a PNG file (grey, grey + alpha, RGB or RGBA; 8 or 16 bits). Throws UserError "WHAT PATH: WHY"
// when the file is missing, a folder, not a PNG (its first bytes are not PNG's signature: a JPEG is
// refused too) or cannot be decoded.
PngImage readPng(const std::filesystem::path& path, const std::string& what);

} // namespace wisp
