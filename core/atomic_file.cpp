// core/atomic_file.cpp: write to "TARGET.partial-PID" (keeping the target's extension, which
// some writers read the format from), flush it to the disk, then rename. Every write, fsync and
// close is checked: a full disk (ENOSPC), a quota (EDQUOT) or an I/O error is reported naming the
// target, and the target keeps what it held.
#include "core/atomic_file.h"

#include "core/error.h"

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <mutex>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace wisp {

namespace {

std::filesystem::path temporaryBeside(const std::filesystem::path& path)
{
    std::filesystem::path temp = path;
    temp += ".partial-" + std::to_string(getpid()) + path.extension().string();
    return temp;
}

// WISP_INJECT_WRITE_FAILURE=N (test-only): the N-th file written through here, counted from when
// the variable took its value, fails as on a full disk: half its bytes reach the temporary file,
// then the write reports ENOSPC. Read at each file, so a test process may set it between writes.
bool injectFailureNow()
{
    static std::mutex mutex;
    static std::string counting; // the value the count runs under
    static uint64_t files = 0;
    std::lock_guard lock(mutex);
    const char* env = std::getenv("WISP_INJECT_WRITE_FAILURE");
    std::string value = env ? env : "";
    if (value != counting) {
        counting = value;
        files = 0;
    }
    if (value.empty())
        return false;
    uint64_t n = 0;
    auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
    if (ec != std::errc() || end != value.data() + value.size() || n == 0)
        throw UserError("WISP_INJECT_WRITE_FAILURE=" + value +
                        ": must be a file number, 1 or more (a test-only fault injection)");
    return ++files == n;
}

// Writes all of `bytes` to `fd`; false with errno set when a write fails.
bool writeAll(int fd, std::string_view bytes)
{
    while (!bytes.empty()) {
        ssize_t n = ::write(fd, bytes.data(), bytes.size());
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            if (n == 0)
                errno = ENOSPC;
            return false;
        }
        bytes.remove_prefix(size_t(n));
    }
    return true;
}

// Flushes a written file to the disk (a file system may report a full disk or an I/O error only
// here) and closes it; "" or why not.
std::string syncAndClose(int fd)
{
    std::string why;
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) // EINVAL: a file that cannot be synced
        why = std::strerror(errno);
    if (::close(fd) != 0 && why.empty())
        why = std::strerror(errno);
    return why;
}

// Fills `temp` through `write` (which returns "" or why it failed), then renames it over `path`.
void writeThrough(const std::filesystem::path& path, bool inject,
                  const std::function<std::string(const std::filesystem::path& temp)>& write)
{
    std::filesystem::path temp = temporaryBeside(path);
    auto removeTemp = [&] {
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
    };
    std::string why;
    try {
        why = write(temp);
        if (why.empty() && inject) {
            // As a full disk cuts a file short: half of it stays, and the writer learns ENOSPC.
            std::error_code ec;
            uintmax_t size = std::filesystem::file_size(temp, ec);
            if (!ec)
                std::filesystem::resize_file(temp, size / 2, ec);
            why = std::strerror(ENOSPC);
        }
    } catch (...) {
        removeTemp();
        throw;
    }
    if (!why.empty()) {
        removeTemp();
        throw UserError("cannot write " + path.string() + ": " + why);
    }
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        removeTemp();
        throw UserError("cannot write " + path.string() + ": " + ec.message());
    }
}

} // namespace

void writeAtomically(const std::filesystem::path& path,
                     const std::function<bool(const std::filesystem::path& temp)>& write)
{
    bool inject = injectFailureNow();
    writeThrough(path, inject, [&](const std::filesystem::path& temp) -> std::string {
        if (!write(temp))
            return "disk full or not writable?";
        // What the writer closed may still be in the page cache: flush it, to hear of a full disk.
        int fd = ::open(temp.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0)
            return std::strerror(errno);
        return syncAndClose(fd);
    });
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes)
{
    bool inject = injectFailureNow();
    writeThrough(path, false, [&](const std::filesystem::path& temp) -> std::string {
        int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (fd < 0)
            return std::strerror(errno);
        if (inject) {
            (void)writeAll(fd, bytes.substr(0, bytes.size() / 2));
            ::close(fd);
            return std::strerror(ENOSPC);
        }
        if (!writeAll(fd, bytes)) {
            std::string why = std::strerror(errno);
            ::close(fd);
            return why;
        }
        return syncAndClose(fd);
    });
}

} // namespace wisp
