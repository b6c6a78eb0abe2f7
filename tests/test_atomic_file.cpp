// tests/test_atomic_file.cpp: core/atomic_file.h: a file appears whole or not at all, and no
// temporary file stays behind when writing fails.
#include "core/atomic_file.h"
#include "core/error.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

using namespace wisp;
using wisp::test::readFile;
using wisp::test::TempDir;

namespace {

size_t filesIn(const std::filesystem::path& dir)
{
    size_t n = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir))
        ++n;
    return n;
}

} // namespace

TEST(AtomicFile, WritesTheBytesAndReplacesAnOldFile)
{
    TempDir dir;
    writeFileAtomically(dir / "a.txt", "first");
    writeFileAtomically(dir / "a.txt", "second, longer");
    EXPECT_EQ(readFile(dir / "a.txt"), "second, longer");
    EXPECT_EQ(filesIn(dir.path()), 1u);
}

TEST(AtomicFile, AFailedWriteLeavesTheTargetAsItWasAndNoTemporaryFile)
{
    TempDir dir;
    writeFileAtomically(dir / "a.txt", "kept");
    std::filesystem::path seen;
    EXPECT_THROW(writeAtomically(dir / "a.txt",
                                 [&](const std::filesystem::path& temp) {
                                     seen = temp;
                                     writeFileAtomically(temp, "half"); // as a writer that fails midway
                                     return false;
                                 }),
                 UserError);
    EXPECT_EQ(seen.parent_path(), dir.path()); // beside the target: the rename stays on one file system
    EXPECT_EQ(seen.extension(), ".txt");       // writers that read the format from the name still can
    EXPECT_EQ(readFile(dir / "a.txt"), "kept");
    EXPECT_EQ(filesIn(dir.path()), 1u);
    EXPECT_THROW(writeAtomically(dir / "b.txt",
                                 [&](const std::filesystem::path& temp) -> bool {
                                     writeFileAtomically(temp, "half");
                                     throw std::runtime_error("the writer's own error");
                                 }),
                 std::runtime_error);
    EXPECT_FALSE(std::filesystem::exists(dir / "b.txt"));
    EXPECT_EQ(filesIn(dir.path()), 1u);
}

TEST(AtomicFile, AMissingFolderIsAUserErrorNamingTheFile)
{
    try {
        writeFileAtomically("/nonexistent/folder/a.txt", "x");
        FAIL() << "no error";
    } catch (const UserError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/folder/a.txt"), std::string::npos) << e.what();
    }
}

// A real full disk (a 64 KiB tmpfs, filled): the write's ENOSPC is reported naming the file, the
// earlier file keeps its bytes and no temporary file stays. (`wisp render --out FULL/r.png` on a
// full disk left r.png at 0 bytes and exited 0.)
TEST(AtomicFile, AFullDiskIsReportedNamingTheFileAndKeepsTheEarlierOne)
{
    WISP_REQUIRE_SMALL_DISK(disk, 64 * 1024);
    writeFileAtomically(disk / "r.png", "the earlier picture");
    ASSERT_GT(disk.fill(), 0u);
    try {
        writeFileAtomically(disk / "r.png", std::string(20000, 'p'));
        FAIL() << "no error on a full disk";
    } catch (const UserError& e) {
        std::string what = e.what();
        EXPECT_NE(what.find((disk / "r.png").string()), std::string::npos) << what;
        EXPECT_NE(what.find("No space left on device"), std::string::npos) << what;
    }
    EXPECT_EQ(readFile(disk / "r.png"), "the earlier picture");
    EXPECT_EQ(filesIn(disk.path()), 2u); // r.png and the filler: no temporary file
    // The writers that write the temporary file themselves (ffmpeg's video) are checked too.
    EXPECT_THROW(writeAtomically(disk / "v.mp4",
                                 [](const std::filesystem::path& temp) {
                                     std::FILE* f = std::fopen(temp.c_str(), "wb");
                                     std::string bytes(20000, 'v');
                                     bool ok = f && std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
                                     ok = f && std::fclose(f) == 0 && ok;
                                     return ok;
                                 }),
                 UserError);
    EXPECT_EQ(filesIn(disk.path()), 2u);
}

// The same through WISP_INJECT_WRITE_FAILURE=N (docs/hardening.md), which runs everywhere: the
// N-th file written from when the variable is set fails half-written, as on a full disk.
TEST(AtomicFile, AnInjectedWriteFailureIsReportedAndKeepsTheEarlierFile)
{
    TempDir dir;
    writeFileAtomically(dir / "a.txt", "kept");
    ASSERT_EQ(setenv("WISP_INJECT_WRITE_FAILURE", "2", 1), 0);
    writeFileAtomically(dir / "b.txt", "the first file is written");
    std::string message;
    try {
        writeFileAtomically(dir / "a.txt", std::string(10000, 'n'));
    } catch (const UserError& e) {
        message = e.what();
    }
    writeFileAtomically(dir / "c.txt", "the third is written again");
    // A writer writing its own temporary file fails the same way once its turn comes.
    ASSERT_EQ(setenv("WISP_INJECT_WRITE_FAILURE", "1", 1), 0);
    EXPECT_THROW(writeAtomically(dir / "d.txt",
                                 [](const std::filesystem::path& temp) {
                                     writeFileAtomically(temp, "written, then cut short");
                                     return true;
                                 }),
                 UserError);
    ASSERT_EQ(unsetenv("WISP_INJECT_WRITE_FAILURE"), 0);
    EXPECT_EQ(message, "cannot write " + (dir / "a.txt").string() + ": No space left on device");
    EXPECT_EQ(readFile(dir / "a.txt"), "kept");
    EXPECT_EQ(readFile(dir / "b.txt"), "the first file is written");
    EXPECT_EQ(readFile(dir / "c.txt"), "the third is written again");
    EXPECT_FALSE(std::filesystem::exists(dir / "d.txt"));
    EXPECT_EQ(filesIn(dir.path()), 3u); // no temporary file
}
