// physics/hair_scene.cpp: head, colliders and strands assembled.
#include "physics/hair_scene.h"

#include "core/error.h"
#include "physics/colliders.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace wisp {

namespace {

void prepareHead(HairScene& scene)
{
    scene.unitsPerMetre = unitsPerMetre(scene.head);
    scene.colliders = scene.head.description.colliders;
    if (scene.colliders.empty()) {
        scene.colliders = fitColliders(scene.head.mesh);
        scene.collidersFitted = true;
    }
    scene.scalp = scene.head.description.scalp ? *scene.head.description.scalp : defaultScalpRule(scene.colliders.front());
    scene.gpuColliders.clear();
    for (const Ellipsoid& e : scene.colliders)
        scene.gpuColliders.push_back(toGpu(e));
}

}  // namespace

HairScene buildGrownScene(const std::filesystem::path& headFile, const GrowthSettings& growth)
{
    return buildGrownScene(loadHead(headFile), growth);
}

HairScene buildGrownScene(Head head, const GrowthSettings& growth)
{
    HairScene scene;
    scene.head = std::move(head);
    prepareHead(scene);
    scene.strands = growGuides(scene.head.mesh, scene.scalp, scene.gpuColliders, growth, scene.unitsPerMetre);
    return scene;
}

PartSettings styledPartDefaults()
{
    PartSettings p;
    p.globalStiffness = 0.1f;
    p.localStiffness = 0.4f;
    return p;
}

HairScene buildLoadedScene(const std::filesystem::path& headFile, const std::vector<HairPartSource>& parts,
                           uint32_t verticesPerStrand)
{
    return buildLoadedScene(loadHead(headFile), parts, verticesPerStrand);
}

HairScene buildLoadedScene(Head head, const std::vector<HairPartSource>& parts, uint32_t verticesPerStrand)
{
    if (parts.empty())
        throw std::invalid_argument("buildLoadedScene: no hair files");
    if (parts.size() > gpu::kSimMaxParts)
        throw UserError("at most " + std::to_string(gpu::kSimMaxParts) + " hair files can be loaded at once, got " +
                        std::to_string(parts.size()));
    HairScene scene;
    scene.head = std::move(head);
    prepareHead(scene);
    scene.strands.verticesPerStrand = verticesPerStrand;
    Bounds headBounds = scene.head.mesh.bounds();
    for (uint32_t index = 0; index < parts.size(); ++index) {
        const HairPartSource& source = parts[index];
        HairAsset asset = loadHairAsset(source.file);
        HairPlacement placement = source.placement ? *source.placement : autoPlacement(asset, headBounds);
        PartSettings settings = source.settings;
        if (settings.name.empty() || settings.name == PartSettings{}.name)
            settings.name = source.file.stem().string();
        scene.strands.parts.push_back(settings);
        uint64_t strandCount = scene.strands.strandCount() + asset.strands.size();
        if (strandCount > kMaxGuides)
            throw UserError(source.file.string() + ": " + std::to_string(asset.strands.size()) + " strands" +
                            (index > 0 ? " (" + std::to_string(strandCount) + " with the parts before it)" : std::string()) +
                            ", more than the " + std::to_string(kMaxGuides) + " guides Wisp simulates");
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
            scene.strands.add(resampleStrand(placed, verticesPerStrand), index, strand.pinnedRoot, strand.pinnedTip);
        }
    }
    shrinkCollidersToRestPose(scene.colliders, scene.strands);
    scene.gpuColliders.clear();
    for (const Ellipsoid& e : scene.colliders)
        scene.gpuColliders.push_back(toGpu(e));
    return scene;
}

}  // namespace wisp
