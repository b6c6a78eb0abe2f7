// physics/simulation.h: what a simulation run is configured with (the settings, with units and
// defaults; their ranges are the settings table's, app/settings/settings_table.cpp), how it packs into the
// GPU's SimParams and per-step SimStep, the state both solvers advance, and the quality metrics
// `wisp simulate` reports.
#pragma once

#include "physics/mesh_sdf.h"
#include "physics/strand_set.h"
#include "shaders/shared/sim.h"

#include <memory>
#include <optional>
#include <vector>

namespace wisp {

struct SimSettings {
    float stepHz = 120.0f;                // fixed steps per simulated second
    uint32_t substeps = 2;                // integrate/FTL substeps per step
    float gravity = 9.81f;                // m/s², downward (scaled to the head's units)
    glm::vec3 wind{0.0f};                 // m/s² (scaled to the head's units)
    float windFrequency = 0.35f;          // Hz of gusts
    uint32_t gridResolution = 32;         // hair-hair grid nodes per axis
    float gridFriction = 0.05f;           // Petrovic blend toward the grid velocity
    float gridRepulsion = 0.0f;           // volume keeping: blend toward moving down the density gradient, [0, 1]
    float penaltyStiffness = 4000.0f;     // 1/s²
    float collisionMarginMetres = 0.003f; // colliders act this far outside their surface
    // The head mesh's signed distance field, cells along the mesh's longest extent (0: none, the
    // ellipsoids and the sphere alone keep the hair out).
    // Off by default for now: its build and its cost in a step are not yet measured on a GPU, and
    // growth still lays the rest pose over the ellipsoids (docs/physics.md, "The head mesh's
    // distance field").
    uint32_t sdfResolution = 0;
    // Every part's parameters when set, over each part's own (PartSettings: grown hair's, or a
    // loaded groom's styled defaults); a part's own override (--part) still wins.
    std::optional<float> globalStiffness, localStiffness, ftlDamping, drag;
    // The hair-hair grid's sums: 64-bit fixed point (deterministic: the same run gives the same
    // bits) or float atomics (order-dependent in the last bits). Each falls back to the other on a
    // device that lacks it.
    enum class GridAtomics { Fixed, Float } gridAtomics = GridAtomics::Fixed;
};

// Everything needed to run: packed parameters plus the grid's placement relative to the head.
struct SimSetup {
    gpu::SimParams params{};
    uint32_t substeps = 1;          // integrate/FTL passes per step (each params.dt long)
    glm::vec3 wind{0.0f};           // the settings' wind, asset units / s² (a step may have its own)
    float windFrequency = 0.0f;     // Hz of the gusts
    float unitsPerMetre = 1.0f;     // the head's units
    glm::vec3 gridCenterHead{0.0f}; // grid centre in head space (the grid follows the head)
    float gridSide = 0.0f;          // asset units
    // The head mesh's signed distance field to build (params.sdf its grid), or none.
    std::shared_ptr<const SdfPlan> sdf;
};

SimSetup makeSimSetup(const SimSettings& settings, const StrandSet& strands,
                      const std::vector<gpu::Ellipsoid>& colliders, float unitsPerMetre);
// The setup with the head mesh's field (planMeshSdf at `settings.sdfResolution`; 0: none) for
// the solvers to build and read beside the colliders.
SimSetup makeSimSetup(const SimSettings& settings, const StrandSet& strands,
                      const std::vector<gpu::Ellipsoid>& colliders, float unitsPerMetre, const Mesh& head);
// The largest scale at which no fixed-point grid node can overflow 2^62: every vertex adds at
// most 1 (density) or maxSpeed (each momentum component) to a node.
float gridFixedScale(uint64_t vertexCount, float maxSplatSpeed);

// The density of the hair-hair grid (grid node `origin`, `cellSize`, `resolution` per axis) that a
// vertex of the rest pose typically sits in: sum(density²) / sum(density) over the nodes, density
// being the trilinear weights splatted. Repulsion measures gradients against it (sim.h gridRepulsionChange).
float restGridDensity(const StrandSet& strands, const glm::vec3& origin, float cellSize, uint32_t resolution);
// The device memory the GPU solver allocates (gpu_solver.cpp) for `strands` strands of V vertices
// and a grid of `gridNodes` nodes summed in 64-bit fixed point (4 words a node) or float atomics:
// the interleaved vertex buffers (positions, velocities, tangents, rest; strands padded to blocks
// of 32), the per-strand info, the grid's sums and velocities, the parameters and counters. The
// solver checks it against the device before allocating, and the command line before building.
uint64_t solverDeviceBytes(uint64_t strands, uint32_t verticesPerStrand, uint64_t gridNodes, bool fixedPointGrid);
// One step: the head's pose, the user's sphere (xyz, radius; 0: none), the time at its start, and
// the wind (m/s², scaled here to the head's units; the setup's when not given).
gpu::SimStep makeStep(const SimSetup& setup, const glm::mat4& headTransform, const glm::vec4& sphere, float time);
gpu::SimStep makeStep(const SimSetup& setup, const glm::mat4& headTransform, const glm::vec4& sphere, float time,
                      const glm::vec3& windMetres);

// The simulated state, one entry per vertex (world space).
struct SimState {
    std::vector<glm::vec4> positions;  // xyz, w = inverse mass (0 pinned)
    std::vector<glm::vec4> velocities; // xyz
    std::vector<glm::vec4> tangents;   // xyz
    uint32_t nonfiniteResets = 0;
};

// The rest pose placed by `headTransform`, at rest.
SimState initialState(const StrandSet& strands, const glm::mat4& headTransform);

struct SimMetrics {
    float maxStretch =
        0.0f; // max |length - rest| / rest over the simulated segments (not those between pinned vertices)
    float maxPenetration = 0.0f; // deepest vertex inside any collider (or the sphere), asset units
    float rootDrift = 0.0f;      // max distance of a pinned vertex from where the head puts it
    // 0.5 sum |dx/dt|² over the last step (unit mass per vertex): the motion a viewer sees. Not
    // from the velocity buffer: Muller's correction term keeps a steady velocity along each strand
    // (about s_damp g dt / (1 - s_damp) at rest) that FTL cancels every step; it is damping
    // bookkeeping, not motion.
    float kineticEnergy = 0.0f;
};
// `previous`: positions one step before `state` (for the kinetic energy); `stepSeconds`: that step.
SimMetrics measure(const SimState& state, const std::vector<glm::vec4>& previous, float stepSeconds,
                   const StrandSet& strands, const SimSetup& setup, const gpu::SimStep& step);

} // namespace wisp
