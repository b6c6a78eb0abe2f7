// tests/cli_support.h: what the suites that run the real wisp binary share: a bad-input run's
// checks (one line, exit status 2, no internal error), a lost device's (injected through
// WISP_INJECT_DEVICE_LOST=N: the N-th queue submission reports VK_ERROR_DEVICE_LOST, and from there
// the code runs as after a real loss; `timeout` turns a hang in the teardown into a failure), files
// left under a temporary name, and skipping window tests without Xvfb.
#pragma once

#include "core/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

// Skips a window test, saying why, where Xvfb is not installed.
#define WISP_REQUIRE_XVFB()                                                                                            \
    if (std::system("command -v Xvfb >/dev/null 2>&1") != 0)                                                           \
    GTEST_SKIP() << "Xvfb is not installed (Debian package xvfb): cannot test the window here"

// The prefix that runs a command under an Xvfb of its own (tests/with_xvfb.sh: the server picks a
// free display, so window tests side by side never race for one).
#define WISP_XVFB "'" WISP_SOURCE_DIR "/tests/with_xvfb.sh'"

namespace wisp::test {

inline size_t lineCount(const std::string& s)
{
    return size_t(std::count(s.begin(), s.end(), '\n'));
}

// Bad input: exit status 2 and one line on stderr that mentions `mention`.
inline void expectUserError(const RunResult& r, const std::string& mention)
{
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal"), std::string::npos) << r.err;
}

inline const std::string kLostMessage = "wisp: the GPU device was lost (VK_ERROR_DEVICE_LOST) during wisp ";

// The one line a lost device gives: its own exit status, no validation message, no internal error.
inline void expectDeviceLost(const RunResult& r, const std::string& command)
{
    EXPECT_EQ(r.status, kExitDeviceLost) << r.err;
    EXPECT_NE(r.err.find(kLostMessage + command + ": "), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal"), std::string::npos) << r.err;
    size_t lines = 0;
    for (size_t at = r.err.find("wisp: "); at != std::string::npos; at = r.err.find("wisp: ", at + 1))
        ++lines;
    EXPECT_EQ(lines, 1u) << r.err;
}

// The environment prefix that loses the device at the `submission`-th queue submission.
inline std::string lostAt(int submission)
{
    return "WISP_INJECT_DEVICE_LOST=" + std::to_string(submission) + " timeout 300";
}

// Every file under `dir` left under a temporary name.
inline std::vector<std::string> partialFiles(const std::filesystem::path& dir)
{
    std::vector<std::string> out;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
        if (entry.path().filename().string().find(".partial") != std::string::npos)
            out.push_back(entry.path().string());
    return out;
}

} // namespace wisp::test
