// physics/groomed_head.cpp: head, colliders and strands assembled.
#include "physics/groomed_head.h"

#include "core/error.h"
#include "physics/colliders.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

namespace wisp {

namespace {

void prepareHead(GroomedHead& scene)
{
    scene.unitsPerMetre = unitsPerMetre(scene.head);
    scene.colliders = scene.head.description.colliders;
    if (scene.colliders.empty()) {
        scene.colliders = fitColliders(scene.head.mesh);
        scene.collidersFitted = true;
    }
    scene.scalp =
        scene.head.description.scalp ? *scene.head.description.scalp : defaultScalpRule(scene.colliders.front());
    if (scene.collidersFitted) {
        // The scalp outside them, within a quarter of a percent of the head.
        std::vector<uint32_t> scalp = scalpTriangles(scene.head.mesh, scene.scalp);
        inscribeColliders(scene.colliders, scene.head.mesh, scalp,
                          kInscribedTolerance * scene.head.mesh.bounds().diagonal());
        // A mesh that is no head is said to be one, naming it.
        std::string mesh = scene.head.description.meshPath.empty() ? scene.head.description.name
                                                                   : scene.head.description.meshPath.string();
        std::string wrong;
        for (const std::string& w : fittedColliderWarnings(scene.head.mesh, scene.colliders, scalp))
            wrong += (wrong.empty() ? "" : "; ") + w;
        if (!wrong.empty()) // one line for the mesh, whatever is wrong with it
            scene.warnings.push_back(mesh + ": " + wrong);
    }
    scene.gpuColliders.clear();
    for (const Ellipsoid& e : scene.colliders)
        scene.gpuColliders.push_back(toGpu(e));
}

} // namespace

GroomedHead buildGrownHead(const std::filesystem::path& headFile, const GrowthSettings& growth)
{
    return buildGrownHead(loadHead(headFile), growth);
}

GroomedHead buildGrownHead(Head head, const GrowthSettings& growth)
{
    GroomedHead scene;
    scene.head = std::move(head);
    prepareHead(scene);
    scene.strands = growGuides(scene.head.mesh, scene.scalp, scene.gpuColliders, growth, scene.unitsPerMetre);
    // Counted as a loaded groom's are: a rigid strand is pinned at every vertex.
    scene.loaded.shortThreshold = kRigidStrandMetres * scene.unitsPerMetre;
    for (const gpu::StrandInfo& info : scene.strands.strands)
        scene.loaded.rigid += info.pinnedRoot >= scene.strands.verticesPerStrand ? 1 : 0;
    return scene;
}

PartSettings styledPartDefaults()
{
    PartSettings p;
    p.globalStiffness = 0.1f;
    p.localStiffness = 0.4f;
    return p;
}

GroomedHead buildLoadedHead(const std::filesystem::path& headFile, const std::vector<HairPartSource>& parts,
                            uint32_t verticesPerStrand, const PlacementRequest& request)
{
    return buildLoadedHead(loadHead(headFile), parts, verticesPerStrand, request);
}

namespace {

std::string percent(float fraction)
{
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f%%", double(100.0f * fraction));
    return text;
}

} // namespace

GroomedHead buildLoadedHead(Head head, const std::vector<HairPartSource>& parts, uint32_t verticesPerStrand,
                            const PlacementRequest& request)
{
    if (parts.empty())
        throw std::invalid_argument("buildLoadedHead: no hair files");
    if (parts.size() > gpu::kSimMaxParts)
        throw UserError("at most " + std::to_string(gpu::kSimMaxParts) + " hair files can be loaded at once, got " +
                        std::to_string(parts.size()));
    GroomedHead scene;
    scene.head = std::move(head);
    prepareHead(scene);
    scene.strands.verticesPerStrand = verticesPerStrand;

    std::vector<HairAsset> assets;
    assets.reserve(parts.size());
    uint64_t strandCount = 0;
    for (uint32_t index = 0; index < parts.size(); ++index) {
        assets.push_back(loadHairAsset(parts[index].file));
        strandCount += assets.back().strands.size();
        if (strandCount > kMaxGuides)
            throw UserError(
                parts[index].file.string() + ": " + std::to_string(assets.back().strands.size()) + " strands" +
                (index > 0 ? " (" + std::to_string(strandCount) + " with the parts before it)" : std::string()) +
                ", more than the " + std::to_string(kMaxGuides) + " guides Wisp simulates");
    }

    // Parts of other formats than the groom's first (a cyHair export beside a TressFX one): each is
    // brought into the first one's axes (its own format's turn, then the first's undone), so that
    // one placement puts every part where its own format says.
    auto firstPlaced = std::find_if(parts.begin(), parts.end(), [](const HairPartSource& p) { return !p.placement; });
    if (firstPlaced != parts.end()) {
        const bool firstZUp = assets[size_t(firstPlaced - parts.begin())].zUp;
        const bool firstMirrored = assets[size_t(firstPlaced - parts.begin())].mirroredZ;
        for (size_t index = 0; index < parts.size(); ++index) {
            HairAsset& asset = assets[index];
            if (parts[index].placement || (asset.zUp == firstZUp && asset.mirroredZ == firstMirrored))
                continue;
            HairPlacement own{.zUpToYUp = asset.zUp, .mirrorZ = asset.mirroredZ};
            for (HairStrand& strand : asset.strands)
                for (glm::vec3& p : strand.points) {
                    glm::vec3 q = applyPlacement(own, p); // y-up, right-handed
                    if (firstZUp)
                        q = glm::vec3(q.x, -q.z, q.y); // (x, z, -y) undone
                    if (firstMirrored)
                        q.z = -q.z;
                    p = q;
                }
            asset.zUp = firstZUp;
            asset.mirroredZ = firstMirrored;
        }
    }

    // One placement for the whole groom, from the roots of the parts that have none of their own
    // (and a sample of their strands, which tells the groom's front from its back).
    GroomShape shape{.roots = {}, .strands = {}, .headFront = scene.head.description.front};
    std::vector<glm::vec3>& roots = shape.roots;
    Bounds groomBounds;
    bool firstPoint = true;
    size_t unplaced = 0;
    for (size_t index = 0; index < parts.size(); ++index)
        unplaced += parts[index].placement ? 0 : assets[index].strands.size();
    constexpr size_t kFacingStrands = 2000;
    size_t seen = 0;
    for (size_t index = 0; index < parts.size(); ++index) {
        if (parts[index].placement)
            continue;
        for (const HairStrand& strand : assets[index].strands) {
            // Up to kFacingStrands of them, evenly spaced through the parts.
            if (shape.strands.size() < kFacingStrands && seen * kFacingStrands >= shape.strands.size() * unplaced)
                shape.strands.push_back(strand.points);
            ++seen;
            roots.push_back(strand.points.front());
            for (const glm::vec3& p : strand.points) {
                groomBounds.min = firstPoint ? p : glm::min(groomBounds.min, p);
                groomBounds.max = firstPoint ? p : glm::max(groomBounds.max, p);
                firstPoint = false;
            }
        }
    }
    if (!roots.empty()) {
        const HairAsset& lead = assets[size_t(
            std::find_if(parts.begin(), parts.end(), [](const HairPartSource& p) { return !p.placement; }) -
            parts.begin())];
        HairPlacement defaults{
            .scale = 1.0f, .offset = glm::vec3(0.0f), .zUpToYUp = lead.zUp, .mirrorZ = lead.mirroredZ};
        scene.placement = placeGroom(shape, groomBounds, defaults, scene.head.mesh, request);
        const GroomPlacement& placed = *scene.placement;
        // Most roots off the surface after the best fit: no groom to move onto the scalp, but
        // another head's, another part of the body's or a misread file's.
        std::string where = "the groom's roots are not on the head: " + placed.describe() + " leaves " +
                            percent(1.0f - placed.fit.onSurface) + " of them farther than " + percent(kRootOnSurface) +
                            " of the head's size from its surface (median " + percent(placed.fit.median) + ")";
        // The parts it is about: those placed together (a part with its own placement is not).
        std::string file;
        for (const HairPartSource& part : parts)
            if (!part.placement)
                file += (file.empty() ? "" : " + ") + part.file.string();
        if (placed.method != GroomPlacement::Method::Given && placed.fit.offHead())
            throw UserError(file + ": " + where + ", more than the " + percent(1.0f - kRootsOffHead) +
                            " that can be moved onto the scalp; place it by hand with --hair-scale S, --hair-offset "
                            "X,Y,Z, --hair-z-up true|false, --hair-mirror-z true|false and --hair-half-turn "
                            "true|false (in a scene: hair's scale, offset, z_up, mirror_z, half_turn)");
        if (placed.fit.offHead())
            scene.warnings.push_back(file + ": " + where + "; kept as given, not moved onto the scalp");
        if (std::string ambiguous = placed.ambiguity(); !ambiguous.empty())
            scene.warnings.push_back(file + ": " + ambiguous);
    }

    float headDiagonal = scene.head.mesh.bounds().diagonal();
    scene.loaded.shortThreshold = shortStrandLength(headDiagonal, verticesPerStrand);
    // Every strand resampled, then the groom's moved onto the scalp where its roots are off it.
    struct Resampled {
        uint32_t part = 0;
        uint32_t pinnedRoot = 0;
        bool pinnedTip = false;
    };
    std::vector<Resampled> resampled;
    std::vector<std::vector<glm::vec3>> strandPoints;
    std::vector<bool> movable;
    for (uint32_t index = 0; index < parts.size(); ++index) {
        const HairPartSource& source = parts[index];
        const HairAsset& asset = assets[index];
        HairPlacement placement = source.placement ? *source.placement : scene.placement->placement;
        PartSettings settings = source.settings;
        if (settings.name.empty() || settings.name == PartSettings{}.name)
            settings.name = source.file.stem().string();
        scene.strands.parts.push_back(settings);
        for (size_t s = 0; s < asset.strands.size(); ++s) {
            const HairStrand& strand = asset.strands[s];
            std::vector<glm::vec3> placed;
            placed.reserve(strand.points.size());
            for (const glm::vec3& p : strand.points) {
                placed.push_back(applyPlacement(placement, p));
                glm::vec3 q = placed.back();
                if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
                    throw UserError(source.file.string() + ": strand " + std::to_string(s) +
                                    " is not finite once placed (scale " + std::to_string(placement.scale) +
                                    "): its coordinates are too large");
            }
            float length = strandLength(placed);
            if (!std::isfinite(length))
                throw UserError(source.file.string() + ": strand " + std::to_string(s) + " (of " +
                                std::to_string(asset.strands.size()) +
                                " in the file) is too long for floats once placed: its length overflows");
            if (!(length > 0.0f)) {
                ++scene.loaded.dropped; // every point at one place: nothing to draw or simulate
                continue;
            }
            bool rigid = length < scene.loaded.shortThreshold;
            scene.loaded.rigid += rigid ? 1 : 0;
            scene.loaded.pinnedTips += strand.pinnedTip && !rigid ? 1 : 0;
            // A strand that already has its vertex count (a groom Wisp wrote, read back) keeps its
            // points where they were; others are resampled evenly.
            bool kept = placed.size() == verticesPerStrand;
            for (size_t i = 1; kept && i < placed.size(); ++i)
                kept = glm::length(placed[i] - placed[i - 1]) > 0.0f;
            std::vector<glm::vec3> points = kept ? placed : resampleStrand(placed, verticesPerStrand);
            for (size_t i = 1; i < points.size(); ++i)
                if (!(glm::length(points[i] - points[i - 1]) > 0.0f))
                    throw UserError(source.file.string() + ": strand " + std::to_string(s) + " (of " +
                                    std::to_string(asset.strands.size()) + " in the file) is " +
                                    std::to_string(length) + " long, too short to split into " +
                                    std::to_string(verticesPerStrand - 1) + " segments in floats at its position");
            resampled.push_back({.part = index,
                                 .pinnedRoot = rigid ? verticesPerStrand : strand.pinnedRoot,
                                 .pinnedTip = strand.pinnedTip && !rigid});
            strandPoints.push_back(std::move(points));
            movable.push_back(!source.placement);
        }
    }
    // The groom's own parts (not those placed apart by hand), unless the fit left most roots off
    // the head (a placement given by hand, kept as given).
    if (scene.placement && !scene.placement->fit.offHead()) {
        // A groom fitted to this head (or placed by hand) was made for another: its roots off the
        // surface move, and every strand is kept out of the head. One as in its file is on its own
        // head: only roots off the head move.
        GroomPlacement::Method method = scene.placement->method;
        bool foreign = method == GroomPlacement::Method::Fitted || method == GroomPlacement::Method::Given;
        float beyond = foreign ? kRootMoved : kRootOnSurface;
        std::vector<uint32_t> scalp = scalpTriangles(scene.head.mesh, scene.scalp);
        if (scalp.empty()) {
            MeshDistance surface(scene.head.mesh);
            size_t off = 0;
            for (size_t s = 0; s < strandPoints.size(); ++s)
                off += movable[s] && surface.closest(strandPoints[s].front()).distance > beyond * headDiagonal ? 1 : 0;
            if (off > 0)
                throw UserError(parts.front().file.string() + ": " + std::to_string(off) +
                                " of the groom's roots lie off the head after the fit, and the head has no scalp to "
                                "move them onto: its scalp rule selects no triangle (its description's scalp)");
        }
        scene.transfer = transferStrands(strandPoints, scene.head.mesh, scalp, beyond, foreign, movable);
    }
    for (size_t s = 0; s < strandPoints.size(); ++s)
        scene.strands.add(strandPoints[s], resampled[s].part, resampled[s].pinnedRoot, resampled[s].pinnedTip);
    if (scene.strands.strandCount() == 0)
        throw UserError(parts.front().file.string() + ": every strand has no length: nothing to draw or simulate");
    shrinkCollidersToRestPose(scene.colliders, scene.strands);
    scene.gpuColliders.clear();
    for (const Ellipsoid& e : scene.colliders)
        scene.gpuColliders.push_back(toGpu(e));
    return scene;
}

std::string describeRigidStrands(const GroomedHead& scene)
{
    if (scene.placement || scene.loaded.rigid == 0)
        return "";
    char threshold[32];
    std::snprintf(threshold, sizeof(threshold), "%.3g", double(kRigidStrandMetres * 100.0f));
    return "hair strands: " + std::to_string(scene.loaded.rigid) + " of " +
           std::to_string(scene.strands.strandCount()) + " grown guides rigid (shorter than " + threshold +
           " cm: they follow the head, not simulated)";
}

std::vector<std::string> describeLoadedHair(const GroomedHead& scene)
{
    std::vector<std::string> out;
    if (!scene.placement) {
        if (std::string rigid = describeRigidStrands(scene); !rigid.empty())
            out.push_back(rigid);
        return out;
    }
    const RootFit& fit = scene.placement->fit;
    out.push_back("hair placement: " + scene.placement->describe() + "; roots: median " + percent(fit.median) +
                  " of the head's size from its surface, " + percent(fit.onSurface) + " within " +
                  percent(kRootOnSurface));
    char threshold[32];
    std::snprintf(threshold, sizeof(threshold), "%.3g", double(scene.loaded.shortThreshold));
    if (scene.transfer && scene.transfer->moved > 0)
        out.push_back("hair transfer: " + scene.transfer->describe());
    out.push_back("hair strands: " + std::to_string(scene.strands.strandCount()) + " simulated, " +
                  std::to_string(scene.loaded.rigid) + " of them kept rigid (shorter than " + threshold +
                  " head units), " + std::to_string(scene.loaded.dropped) + " dropped (no length), " +
                  std::to_string(scene.loaded.pinnedTips) + " pinned at both ends");
    out.insert(out.end(), scene.notes.begin(), scene.notes.end());
    return out;
}

nlohmann::json rigidStrandsJson(const GroomedHead& scene)
{
    return {{"count", scene.loaded.rigid},
            {"of", scene.strands.strandCount()},
            {"shorter_than", scene.loaded.shortThreshold}};
}

nlohmann::json loadedHairJson(const GroomedHead& scene)
{
    if (!scene.placement)
        return nullptr;
    return {{"placement", scene.placement->toJson()},
            {"short_strands",
             {{"shorter_than", scene.loaded.shortThreshold},
              {"kept_rigid", scene.loaded.rigid},
              {"dropped_zero_length", scene.loaded.dropped}}},
            {"transfer", scene.transfer ? scene.transfer->toJson() : nlohmann::json(nullptr)},
            {"pinned_tips", scene.loaded.pinnedTips},
            {"warnings", scene.warnings}};
}

} // namespace wisp
