// physics/hair_scene.cpp: head, colliders and strands assembled.
#include "physics/hair_scene.h"

#include "physics/colliders.h"

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
    HairScene scene;
    scene.head = loadHead(headFile);
    prepareHead(scene);
    scene.strands = growGuides(scene.head.mesh, scene.scalp, scene.gpuColliders, growth, scene.unitsPerMetre);
    return scene;
}

}  // namespace wisp
