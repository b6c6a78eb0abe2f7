// app/commands/inspect.cpp: the `inspect` subcommand: a mesh's counts and bounds; a groom's counts, bounds,
// units, up axis, pinned tips, lengths and short strands; with --head, the groom placed as `render`
// and `simulate` would place it (the same GroomedHead), its roots against the head, the strands
// moved onto its scalp and its side standoff (physics/groom_metrics.h).
#include "app/commands/inspect.h"

#include "app/scene/session_options.h"
#include "assets/hair_asset.h"
#include "assets/head.h"
#include "assets/placement.h"
#include "core/error.h"
#include "physics/groom_metrics.h"
#include "physics/groomed_head.h"
#include "physics/strand_set.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <iostream>
#include <memory>

namespace wisp {

namespace {

// The likely unit of a groom from its size: a head of hair spans about 0.2 to 1 m.
const char* unitsGuess(float diagonal)
{
    if (diagonal >= 0.05f && diagonal < 5.0f)
        return "m";
    if (diagonal >= 5.0f && diagonal < 500.0f)
        return "cm";
    if (diagonal >= 500.0f && diagonal < 5000.0f)
        return "mm";
    return "unknown";
}

bool isHairFile(const std::string& file)
{
    std::string ext = std::filesystem::path(file).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".tfx" || ext == ".hair";
}

nlohmann::json lengths(const HairAsset& asset, float scale)
{
    std::vector<float> l;
    for (const HairStrand& s : asset.strands)
        l.push_back(scale * strandLength(s.points));
    std::sort(l.begin(), l.end());
    if (l.empty())
        return nullptr;
    return {{"min", l.front()}, {"median", l[l.size() / 2]}, {"max", l.back()}};
}

const char* kTreatment =
    "kept rigid: they follow the head and are drawn, not simulated; strands of no length are dropped";

int inspectGroomOnHead(const InspectOptions& o, const PlacementRequest& request)
{
    std::vector<std::string> files = o.hair;
    if (!o.file.empty())
        files.insert(files.begin(), o.file);
    std::vector<HairPartSource> parts;
    for (const std::string& f : files)
        parts.push_back({.file = f, .placement = std::nullopt, .settings = styledPartDefaults()});
    Head head = loadHead(o.head.empty() ? defaultHeadPath() : std::filesystem::path(o.head));
    Bounds b = head.mesh.bounds();
    float diagonal = b.diagonal();
    // The scene render and simulate build: the same placement, the same treatment of strands.
    GroomedHead scene = buildLoadedHead(std::move(head), parts, o.verticesPerStrand, request);
    nlohmann::json out = {
        {"kind", "groom_on_head"},
        {"head",
         {{"file", o.head.empty() ? defaultHeadPath().string() : o.head},
          {"diagonal", diagonal},
          {"bbox", {{b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z}}}}},
        {"files", files},
        {"strands", scene.strands.strandCount()},
        {"vertices_per_strand", o.verticesPerStrand},
        {"placement", scene.placement->toJson()},
        {"transfer", scene.transfer ? scene.transfer->toJson() : nlohmann::json(nullptr)},
        {"short_strands",
         {{"shorter_than", scene.loaded.shortThreshold},
          {"reference", "head diagonal"},
          {"kept_rigid", scene.loaded.rigid},
          {"dropped_zero_length", scene.loaded.dropped},
          {"treatment", kTreatment}}},
        {"pinned_tips", scene.loaded.pinnedTips},
        {"side_standoff", sideStandoff(scene.head.mesh, scene.strands, scene.unitsPerMetre).value},
        {"inside_mesh", insideMesh(MeshSignedDistance(scene.head.mesh), diagonal, scene.strands).toJson()},
        {"warnings", scene.warnings}};
    std::cout << out.dump() << "\n";
    return 0;
}

} // namespace

nlohmann::json describeGroom(const HairAsset& asset, uint32_t verticesPerStrand)
{
    nlohmann::json out = describeHairAsset(asset);
    Bounds b = asset.bounds();
    float diagonal = b.diagonal();
    size_t pinnedTips = 0, zero = 0, shortStrands = 0;
    uint32_t pinnedRoots = 0;
    float threshold = shortStrandLength(diagonal, verticesPerStrand);
    for (const HairStrand& s : asset.strands) {
        pinnedTips += s.pinnedTip ? 1 : 0;
        pinnedRoots = std::max(pinnedRoots, s.pinnedRoot);
        float length = strandLength(s.points);
        zero += length > 0.0f ? 0 : 1;
        shortStrands += length > 0.0f && length < threshold ? 1 : 0;
    }
    out["units"] = {{"guess", unitsGuess(diagonal)}, {"diagonal", diagonal}};
    out["up_axis"] = asset.zUp ? "z" : "y";
    out["up_axis_from"] =
        asset.format == HairFormat::CyHair ? "the format (cyHair files are z-up)" : "the format (TressFX is y-up)";
    out["mirror_z"] = asset.mirroredZ;
    out["pinned_tips"] = pinnedTips;
    out["pinned_root_vertices_max"] = pinnedRoots;
    out["lengths"] = lengths(asset, 1.0f);
    out["short_strands"] = {{"shorter_than", threshold},
                            {"reference", "the groom's own diagonal (with --head: the head's)"},
                            {"vertices_per_strand", verticesPerStrand},
                            {"count", shortStrands},
                            {"zero_length", zero},
                            {"treatment", kTreatment}};
    return out;
}

std::function<int()> addInspectCommand(CLI::App& app)
{
    auto o = std::make_shared<InspectOptions>();
    CLI::App* cmd = app.add_subcommand(
        "inspect",
        "print what a hair or mesh file holds, as one JSON object; with --head, where a groom's roots land on it");
    cmd->add_option("file", o->file,
                    "a hair file (.tfx: TressFX 2/3/4, .hair: cyHair) or a mesh (.obj through tinyobjloader, others "
                    "through assimp)");
    cmd->add_option("--hair", o->hair, "a groom file (repeat for a groom in parts), placed on --head as render would");
    cmd->add_option("--head", o->head,
                    "head description (.json) or mesh to place the groom on (default with --hair: models/head.json)");
    cmd->add_option("--vertices", o->verticesPerStrand,
                    "vertices per strand after resampling (what short strands are measured against)")
        ->check(wholeWithin(kMinVerticesPerStrand, kMaxVerticesPerStrand))
        ->capture_default_str();
    auto placement = std::make_shared<PlacementOptions>(cmd); // as render places a groom
    return [o, cmd, placement]() -> int {
        if (!*cmd)
            return -1;
        if (o->file.empty() && o->hair.empty())
            throw UserError("inspect: name a file, or a groom with --hair (and a head with --head)");
        HairSource source;
        placement->apply(source);
        PlacementRequest request = source.placementRequest();
        bool placed = request.scale || request.offset || request.zUp || request.mirrorZ || request.halfTurn;
        if (!o->hair.empty() || !o->head.empty() || placed) {
            if (!o->file.empty() && !isHairFile(o->file))
                throw UserError("inspect: " + o->file +
                                " is not a hair file (.tfx, .hair): with --head or a placement, inspect places a "
                                "groom");
            return inspectGroomOnHead(*o, request);
        }
        if (isHairFile(o->file)) {
            std::cout << describeGroom(loadHairAsset(o->file), o->verticesPerStrand).dump() << "\n";
            return 0;
        }
        Mesh mesh = loadMesh(o->file);
        Bounds b = mesh.bounds();
        nlohmann::json out = {{"kind", "mesh"},
                              {"vertices", mesh.sourceVertices},
                              {"triangles", mesh.triangleCount()},
                              {"bbox", {{b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z}}},
                              {"diagonal", b.diagonal()}};
        std::cout << out.dump() << "\n";
        return 0;
    };
}

} // namespace wisp
