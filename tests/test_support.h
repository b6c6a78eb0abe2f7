// tests/test_support.h: helpers shared by the suites: a validated Vulkan context, the real wisp
// binary run as a subprocess, temporary folders, and paths to ../shared/data.
#pragma once

#include "gpu/context.h"

#include <filesystem>
#include <string>

namespace wisp::test {

// A context on the default device with validation on (the suites assert zero messages), and the
// synchronization checks too when the environment has WISP_TEST_SYNC_VALIDATION=1.
vk::ContextOptions validatedOptions();

struct RunResult {
    int status = -1;
    std::string out;
    std::string err;
};
// Runs the wisp binary with `args` (shell-quoted by the caller) and optional environment prefix.
RunResult runWisp(const std::string& args, const std::string& envPrefix = "");

// A fresh, empty folder under the system temp folder, removed when the object dies.
class TempDir {
public:
    TempDir();
    ~TempDir();
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

// A small file system of its own (tmpfs, `bytes` large) mounted on a fresh folder, to be filled:
// a real full disk. Mounting needs root (CAP_SYS_ADMIN); where it is refused, mounted() is false
// and whyNot() says why (WISP_REQUIRE_SMALL_DISK skips with it). Unmounted when the object dies.
class SmallDisk {
public:
    explicit SmallDisk(size_t bytes);
    ~SmallDisk();
    SmallDisk(const SmallDisk&) = delete;
    SmallDisk& operator=(const SmallDisk&) = delete;
    bool mounted() const { return mounted_; }
    const std::string& whyNot() const { return whyNot_; }
    const std::filesystem::path& path() const { return dir_.path(); }
    std::filesystem::path operator/(const std::string& name) const { return dir_ / name; }
    // Writes a file "filler" until the disk is full (a write fails); returns the bytes it holds.
    size_t fill() const;

private:
    TempDir dir_;
    bool mounted_ = false;
    std::string whyNot_;
};

void writeFile(const std::filesystem::path& path, const std::string& text);
// The whole file as bytes ("" when it cannot be read).
std::string readFile(const std::filesystem::path& path);
// ../shared/data/<relative>, or an empty path when the shared data is not beside the checkout.
std::filesystem::path sharedData(const std::string& relative);

// The largest single allocation through operator new since the last reset (the test binaries
// replace the global operator new to record it): a loader must not allocate what its input
// does not back.
void resetLargestAllocation();
size_t largestAllocation();

} // namespace wisp::test

// Skips the test, saying which file is missing, when shared data is absent.
#define WISP_REQUIRE_DATA(var, relative)                                                                               \
    std::filesystem::path var = ::wisp::test::sharedData(relative);                                                    \
    if (var.empty())                                                                                                   \
    GTEST_SKIP() << "../shared/data/" << (relative)                                                                    \
                 << " is absent: this test needs the shared "                                                          \
                    "third-party assets beside the checkout"

// A SmallDisk named `var`, or the test skipped saying why it could not be mounted (not root): the
// injected write failures (WISP_INJECT_WRITE_FAILURE) test the same paths everywhere.
#define WISP_REQUIRE_SMALL_DISK(var, bytes)                                                                            \
    ::wisp::test::SmallDisk var(bytes);                                                                                \
    if (!var.mounted())                                                                                                \
    GTEST_SKIP() << "cannot mount a " << (bytes) << "-byte tmpfs to fill (" << var.whyNot()                            \
                 << "): the injected write failures cover the same paths"
