// tests/test_atomic_file.cpp: core/atomic_file.h: a file appears whole or not at all, and no
// temporary file stays behind when writing fails.
#include "core/atomic_file.h"
#include "core/error.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

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
