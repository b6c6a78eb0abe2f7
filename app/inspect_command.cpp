// app/inspect_command.cpp: `wisp inspect FILE`: what a hair file (TressFX 2/3/4, cyHair) or a mesh
// holds, as one JSON object.
#include "app/commands.h"

#include "assets/hair_asset.h"
#include "assets/mesh.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <memory>

namespace wisp {

namespace {

int run(const std::string& file)
{
    std::string ext = std::filesystem::path(file).extension().string();
    if (ext == ".tfx" || ext == ".hair") {
        std::cout << describeHairAsset(loadHairAsset(file)).dump() << "\n";
        return 0;
    }
    Mesh mesh = loadMesh(file);
    Bounds b = mesh.bounds();
    nlohmann::json out = {{"kind", "mesh"},
                          {"vertices", mesh.sourceVertices},
                          {"triangles", mesh.triangleCount()},
                          {"bbox", {{b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z}}}};
    std::cout << out.dump() << "\n";
    return 0;
}

}  // namespace

CommandRun addInspectCommand(CLI::App& app)
{
    auto file = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand("inspect", "print what a hair or mesh file holds, as one JSON object");
    cmd->add_option("file", *file,
                    "a hair file (.tfx: TressFX 2/3/4, .hair: cyHair) or a mesh (.obj through tinyobjloader, others "
                    "through assimp)")
        ->required();
    return [cmd, file] { return cmd->parsed() ? run(*file) : -1; };
}

}  // namespace wisp
