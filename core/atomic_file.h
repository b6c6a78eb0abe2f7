// core/atomic_file.h: files that appear whole or not at all. Each is written under a temporary
// name beside its target (same folder, so same file system) and renamed over it; on any failure
// the temporary file is removed and the target is left as it was. PNGs, scene files, a sweep's
// CSV, a recording's video and the generated head all go through here.
#pragma once

#include <filesystem>
#include <functional>
#include <string_view>

namespace wisp {

// `write` fills the temporary path it is given and returns false when it could not (disk full, not
// writable); it may also throw its own error. Either way no temporary file stays behind, and a
// failure throws UserError naming `path`.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<bool(const std::filesystem::path& temp)>& write);
// The same for bytes already in memory.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

} // namespace wisp
