// core/atomic_file.cpp: write to "TARGET.partial-PID" (keeping the target's extension, which
// some writers read the format from), then rename.
#include "core/atomic_file.h"

#include "core/error.h"

#include <fstream>
#include <string>
#include <unistd.h>

namespace wisp {

namespace {

std::filesystem::path temporaryBeside(const std::filesystem::path& path)
{
    std::filesystem::path temp = path;
    temp += ".partial-" + std::to_string(getpid()) + path.extension().string();
    return temp;
}

} // namespace

void writeAtomically(const std::filesystem::path& path,
                     const std::function<bool(const std::filesystem::path& temp)>& write)
{
    std::filesystem::path temp = temporaryBeside(path);
    auto removeTemp = [&] {
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
    };
    bool written = false;
    try {
        written = write(temp);
    } catch (...) {
        removeTemp();
        throw;
    }
    if (!written) {
        removeTemp();
        throw UserError("cannot write " + path.string() + " (disk full or not writable?)");
    }
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        removeTemp();
        throw UserError("cannot write " + path.string() + ": " + ec.message());
    }
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes)
{
    writeAtomically(path, [&](const std::filesystem::path& temp) {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), std::streamsize(bytes.size()));
        out.close();
        return bool(out);
    });
}

} // namespace wisp
