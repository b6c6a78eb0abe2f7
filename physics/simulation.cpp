// physics/simulation.cpp: settings packing, initial state and metrics.
#include "physics/simulation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wisp {

uint64_t solverDeviceBytes(uint64_t strands, uint32_t verticesPerStrand, uint64_t gridNodes, bool fixedPointGrid)
{
    uint64_t block = gpu::kSimStrandBlock;
    uint64_t slots = (strands + block - 1) / block * block * verticesPerStrand;
    uint64_t vertexBuffers = slots * (3 * sizeof(glm::vec4) + sizeof(gpu::RestVertex));
    uint64_t gridSums = fixedPointGrid ? gpu::kGridFixedWordsPerNode * sizeof(int64_t) : sizeof(gpu::GridNode);
    // Two sets of grid sums: a step splats into one while its gather zeroes the other for the next.
    return vertexBuffers + strands * sizeof(gpu::StrandInfo) + gridNodes * 2 * gridSums + sizeof(gpu::SimParams) +
           sizeof(gpu::SimCounters);
}

SimSetup makeSimSetup(const SimSettings& settings, const StrandSet& strands,
                      const std::vector<gpu::Ellipsoid>& colliders, float unitsPerMetre, const Mesh& head)
{
    SimSetup setup = makeSimSetup(settings, strands, colliders, unitsPerMetre);
    if (settings.sdfResolution > 0) {
        // The band reaches past the margin the penalty acts in, at any resolution.
        setup.sdf = std::make_shared<const SdfPlan>(
            planMeshSdf(head, settings.sdfResolution, 2.0f * setup.params.collisionMargin));
        setup.params.sdf = setup.sdf->grid;
    }
    return setup;
}

SimSetup makeSimSetup(const SimSettings& s, const StrandSet& strands, const std::vector<gpu::Ellipsoid>& colliders,
                      float unitsPerMetre)
{
    if (colliders.size() > gpu::kSimMaxColliders)
        throw std::invalid_argument("more than " + std::to_string(gpu::kSimMaxColliders) + " colliders");
    if (strands.parts.size() > gpu::kSimMaxParts)
        throw std::invalid_argument("more than " + std::to_string(gpu::kSimMaxParts) + " hair parts");
    SimSetup setup;
    gpu::SimParams& p = setup.params;
    setup.substeps = s.substeps;
    p.gravity = glm::vec3(0.0f, -s.gravity * unitsPerMetre, 0.0f);
    p.dt = 1.0f / (s.stepHz * float(s.substeps));
    p.substeps = s.substeps;
    setup.wind = s.wind * unitsPerMetre;
    setup.windFrequency = s.windFrequency;
    setup.unitsPerMetre = unitsPerMetre;
    p.strandCount = uint32_t(strands.strandCount());
    p.verticesPerStrand = strands.verticesPerStrand;
    p.colliderCount = uint32_t(colliders.size());
    p.gridResolution = s.gridResolution;
    p.gridNodeCount = s.gridResolution * s.gridResolution * s.gridResolution;
    p.penaltyStiffness = s.penaltyStiffness;
    p.collisionMargin = s.collisionMarginMetres * unitsPerMetre;
    p.gridFriction = s.gridFriction;
    p.gridRepulsion = s.gridRepulsion;
    p.partCount = uint32_t(strands.parts.size());
    p.gridMaxSplatSpeed = gpu::kGridMaxSplatSpeed * unitsPerMetre;
    p.gridFixedScale = s.gridAtomics == SimSettings::GridAtomics::Fixed
                           ? gridFixedScale(strands.vertexCount(), p.gridMaxSplatSpeed)
                           : 0.0f;
    for (size_t i = 0; i < strands.parts.size(); ++i) {
        const PartSettings& part = strands.parts[i];
        p.parts[i] = {part.globalStiffness, part.localStiffness, part.ftlDamping, part.drag};
    }
    for (size_t i = 0; i < colliders.size(); ++i)
        p.colliders[i] = colliders[i];

    // The grid: a cube around the rest pose grown by the longest strand (hair can swing that far),
    // wide enough to hold that box however the head turns.
    Bounds b = strands.bounds();
    float reach = strands.maxLength();
    setup.gridCenterHead = b.center();
    setup.gridSide = glm::length(b.size() + glm::vec3(2.0f * reach));
    p.gridCellSize = setup.gridSide / float(s.gridResolution - 1);
    // Repulsion in the grid's own terms (sim.h gridRepulsionChange): density gradients relative to the rest
    // pose's density, speeds in cells per step.
    p.gridRestDensity = restGridDensity(strands, setup.gridCenterHead - glm::vec3(0.5f * setup.gridSide),
                                        p.gridCellSize, s.gridResolution);
    p.gridSeparationSpeed = gpu::kRepulsionCellsPerStep * p.gridCellSize * s.stepHz;
    return setup;
}

float restGridDensity(const StrandSet& strands, const glm::vec3& origin, float cellSize, uint32_t resolution)
{
    // Splat the rest pose (as gridSplat does) into the block of nodes its bounds reach.
    Bounds b = strands.bounds();
    glm::ivec3 lo = glm::max(glm::ivec3(glm::floor((b.min - origin) / cellSize)), glm::ivec3(0));
    glm::ivec3 hi = glm::min(glm::ivec3(glm::floor((b.max - origin) / cellSize)) + 1, glm::ivec3(int(resolution) - 1));
    if (glm::any(glm::lessThan(hi, lo)))
        return 1.0f;
    glm::ivec3 dims = hi - lo + 1;
    std::vector<double> density(size_t(dims.x) * size_t(dims.y) * size_t(dims.z), 0.0);
    for (const glm::vec3& p : strands.rest) {
        gpu::GridCell cell = gpu::gridCell(p, origin, cellSize);
        if (!gpu::cellInside(cell.base, resolution))
            continue;
        for (uint32_t k = 0; k < 8; ++k) {
            glm::ivec3 n = glm::clamp(cell.base + gpu::cornerOffset(k) - lo, glm::ivec3(0), dims - 1);
            density[size_t(n.x) + size_t(dims.x) * (size_t(n.y) + size_t(dims.y) * size_t(n.z))] +=
                gpu::cornerWeight(cell.frac, k);
        }
    }
    double sum = 0.0, squares = 0.0;
    for (double d : density) {
        sum += d;
        squares += d * d;
    }
    return sum > 0.0 ? float(squares / sum) : 1.0f;
}

float gridFixedScale(uint64_t vertexCount, float maxSplatSpeed)
{
    double worst = double(std::max<uint64_t>(vertexCount, 1)) * std::max(1.0, double(maxSplatSpeed));
    return float(std::ldexp(1.0, 62) / worst);
}

gpu::SimStep makeStep(const SimSetup& setup, const glm::mat4& headTransform, const glm::vec4& sphere, float time)
{
    gpu::SimStep step{};
    step.headTransform = headTransform;
    step.sphereCenter = glm::vec3(sphere);
    step.sphereRadius = sphere.w;
    step.gridOrigin =
        glm::vec3(headTransform * glm::vec4(setup.gridCenterHead, 1.0f)) - glm::vec3(0.5f * setup.gridSide);
    step.time = time;
    step.wind = setup.wind;
    step.windFrequency = setup.windFrequency;
    return step;
}

gpu::SimStep makeStep(const SimSetup& setup, const glm::mat4& headTransform, const glm::vec4& sphere, float time,
                      const glm::vec3& windMetres)
{
    gpu::SimStep step = makeStep(setup, headTransform, sphere, time);
    step.wind = windMetres * setup.unitsPerMetre;
    return step;
}

SimState initialState(const StrandSet& strands, const glm::mat4& headTransform)
{
    SimState state;
    uint32_t V = strands.verticesPerStrand;
    state.positions.resize(strands.vertexCount());
    state.velocities.assign(strands.vertexCount(), glm::vec4(0.0f));
    state.tangents.resize(strands.vertexCount());
    for (size_t s = 0; s < strands.strandCount(); ++s) {
        const gpu::StrandInfo& info = strands.strands[s];
        for (uint32_t i = 0; i < V; ++i) {
            size_t g = s * V + i;
            bool pinned = i < info.pinnedRoot || (info.pinnedTip != 0u && i == V - 1);
            state.positions[g] =
                glm::vec4(glm::vec3(headTransform * glm::vec4(strands.rest[g], 1.0f)), pinned ? 0.0f : 1.0f);
            uint32_t j = std::min(i + 1, V - 1);
            glm::vec3 t = strands.rest[s * V + j] - strands.rest[s * V + j - 1];
            state.tangents[g] = glm::vec4(glm::mat3(headTransform) * glm::normalize(t), 0.0f);
        }
    }
    return state;
}

SimMetrics measure(const SimState& state, const std::vector<glm::vec4>& previous, float stepSeconds,
                   const StrandSet& strands, const SimSetup& setup, const gpu::SimStep& step)
{
    SimMetrics m;
    uint32_t V = strands.verticesPerStrand;
    glm::mat3 R(step.headTransform);
    glm::vec3 t(step.headTransform[3]);
    std::vector<gpu::Ellipsoid> colliders(setup.params.colliders, setup.params.colliders + setup.params.colliderCount);
    for (size_t s = 0; s < strands.strandCount(); ++s) {
        const gpu::StrandInfo& info = strands.strands[s];
        for (uint32_t i = 0; i < V; ++i) {
            size_t g = s * V + i;
            glm::vec3 p(state.positions[g]);
            glm::vec3 motion = (p - glm::vec3(previous[g])) / stepSeconds;
            m.kineticEnergy += 0.5f * glm::dot(motion, motion);
            bool pinned = i < info.pinnedRoot || (info.pinnedTip != 0u && i == V - 1);
            if (!pinned) { // roots sit on the scalp, which the colliders enclose by design
                glm::vec3 local = glm::transpose(R) * (p - t);
                for (const gpu::Ellipsoid& e : colliders)
                    m.maxPenetration = std::max(m.maxPenetration, gpu::ellipsoidContact(e, local, 0.0f).depth);
                if (step.sphereRadius > 0.0f)
                    m.maxPenetration =
                        std::max(m.maxPenetration, step.sphereRadius - glm::length(p - step.sphereCenter));
            }
            if (pinned)
                m.rootDrift = std::max(
                    m.rootDrift, glm::length(p - glm::vec3(step.headTransform * glm::vec4(strands.rest[g], 1.0f))));
            bool parentPinned = i > 0 && (i - 1 < info.pinnedRoot);
            if (i > 0 && !(pinned && parentPinned)) { // a segment between two pinned vertices is rigid, not simulated
                float rest = glm::length(strands.rest[g] - strands.rest[g - 1]);
                float now = glm::length(p - glm::vec3(state.positions[g - 1]));
                m.maxStretch = std::max(m.maxStretch, std::abs(now - rest) / rest);
            }
        }
    }
    return m;
}

} // namespace wisp
