// tests/test_layers.cpp: the folders' boundaries as the include lines draw them. Outside
// renderer/graphics/, only the renderer's pass list (renderer/renderer.cpp) knows the graphics
// (tessellation) path: the shared renderer, the compute path, the commands, the sessions, the
// window and the device-free settings include none of its headers. (The tests may: they test it.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

// The include lines of `file` that name a header of renderer/graphics/.
std::vector<std::string> graphicsIncludes(const fs::path& file)
{
    std::vector<std::string> found;
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        size_t start = line.find_first_not_of(" \t");
        if (start == std::string::npos || line.compare(start, 1, "#") != 0)
            continue;
        size_t word = line.find_first_not_of(" \t", start + 1);
        if (word != std::string::npos && line.compare(word, 7, "include") == 0 &&
            line.find("renderer/graphics/") != std::string::npos)
            found.push_back(line);
    }
    return found;
}

bool isSource(const fs::path& p)
{
    std::string ext = p.extension().string();
    return ext == ".h" || ext == ".cpp" || ext == ".glsl" || ext == ".comp";
}

} // namespace

TEST(Layers, OnlyThePassListIncludesTheGraphicsPath)
{
    const fs::path root = WISP_SOURCE_DIR;
    const std::string passList = "renderer/renderer.cpp";
    size_t scanned = 0;
    std::vector<std::string> leaks;
    for (const char* folder :
         {"app", "assets", "core", "gpu", "physics", "renderer", "shading", "shaders", "tools", "fuzz"}) {
        if (!fs::exists(root / folder))
            continue;
        for (const fs::directory_entry& e : fs::recursive_directory_iterator(root / folder)) {
            if (!e.is_regular_file() || !isSource(e.path()))
                continue;
            std::string rel = fs::relative(e.path(), root).generic_string();
            if (rel.rfind("renderer/graphics/", 0) == 0 || rel == passList)
                continue;
            ++scanned;
            for (const std::string& line : graphicsIncludes(e.path()))
                leaks.push_back(rel + ": " + line);
        }
    }
    EXPECT_GT(scanned, 100u) << "the source tree was not found under " << root;
    std::string list;
    for (const std::string& leak : leaks)
        list += "\n  " + leak;
    EXPECT_TRUE(leaks.empty()) << "the graphics path is included outside renderer/graphics/ and " << passList << ":"
                               << list;
    // The check sees an include where there is one: the pass list's own.
    EXPECT_FALSE(graphicsIncludes(root / passList).empty());
}
