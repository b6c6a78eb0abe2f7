// core/atomic_file.h: files that appear whole or not at all. Each is written under a temporary
// name beside its target (same folder, so same file system) and renamed over it; on any failure
// the temporary file is removed and the target is left as it was. PNGs, scene files, a sweep's
// CSV, a recording's video, groom exports and the generated head all go through here. Every write,
// the flush to the disk (fsync) and the close are checked: a full disk throws UserError "cannot
// write PATH: No space left on device". WISP_INJECT_WRITE_FAILURE=N (test-only) makes the N-th
// file the process writes through here fail that way, half written.
#pragma once

#include <filesystem>
#include <functional>
#include <string_view>

namespace wisp {

// `write` fills the temporary path it is given and returns false when it could not (disk full, not
// writable); it may also throw its own error. What it wrote is flushed to the disk before the
// rename. Either way no temporary file stays behind, and a failure throws UserError naming `path`.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<bool(const std::filesystem::path& temp)>& write);
// The same for bytes already in memory.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

} // namespace wisp
