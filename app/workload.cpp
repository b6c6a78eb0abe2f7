// app/workload.cpp: a workload's 32-bit counts and its GPU memory, estimated from the same sizes
// the owners allocate (physics/gpu_solver.cpp, renderer/hair_pass.cpp, guide_pass.cpp,
// render_target.cpp, light_maps.cpp, oit.cpp) and checked against the device up front.
#include "app/workload.h"

#include "core/error.h"
#include "gpu/context.h"
#include "shaders/shared/hair_shading.h"
#include "shaders/shared/shadows.h"

#include <algorithm>
#include <limits>
#include <string>

namespace wisp {

namespace {

// Bytes per texel of the formats the render parts use.
constexpr uint64_t kRgba8Bytes = 4;     // the target's colour (R8G8B8A8_SRGB)
constexpr uint64_t kDepth32Bytes = 4;   // every depth image (D32_SFLOAT)
constexpr uint64_t kRgba16fBytes = 8;   // the light's opacity layers, the OIT's resolved colour
constexpr uint64_t kRgba32fBytes = 16;  // the hair's lookup tables
constexpr uint64_t kMaxCount = std::numeric_limits<uint32_t>::max();

uint64_t mebibytes(uint64_t bytes)
{
    return (bytes + (uint64_t(1) << 20) - 1) >> 20;
}

std::string mib(uint64_t bytes)
{
    return std::to_string(mebibytes(bytes)) + " MiB";
}

}  // namespace

GpuMemory estimateGpuMemory(const Workload& w)
{
    GpuMemory m;
    uint64_t grid = uint64_t(w.sim.gridResolution) * w.sim.gridResolution * w.sim.gridResolution;
    if (w.guides > 0)
        m.simulation = solverDeviceBytes(w.guides, w.verticesPerStrand, grid, /*fixedPointGrid=*/true);
    if (!w.render)
        return m;
    const RenderSettings& r = *w.render;
    uint64_t lines = w.guides * (w.verticesPerStrand > 0 ? w.verticesPerStrand - 1 : 0);
    m.hair = w.guides * sizeof(glm::uvec4) + uint64_t(gpu::kHairLutSize) * gpu::kHairLutSize * gpu::kHairLutLayers * kRgba32fBytes +
             lines * 2 * sizeof(uint32_t);
    uint64_t pixels = uint64_t(r.width) * r.height;
    uint64_t samples = std::max<uint32_t>(r.samples, 1);
    m.target = pixels * (samples > 1 ? samples * kRgba8Bytes : 0) + pixels * samples * kDepth32Bytes + pixels * kRgba8Bytes;
    uint64_t texels = uint64_t(r.shadows.mapSize) * r.shadows.mapSize;
    m.lightMaps = texels * (2 * kDepth32Bytes + kRgba16fBytes);
    if (r.transparency.mode == Transparency::Oit) {
        uint64_t nodesPerPixel = std::max<uint32_t>(r.transparency.oitNodesPerPixel, 1);
        m.oit = pixels * (sizeof(uint32_t) + kRgba16fBytes + nodesPerPixel * sizeof(gpu::OitNode));
    }
    return m;
}

void checkCounts(const Workload& w)
{
    if (!w.render)
        return;
    const StrandSettings& s = w.render->strands;
    uint64_t strands = w.guides * s.strandsPerGuide;
    if (strands > kMaxCount)
        throw UserError(std::to_string(w.guides) + " guides x strands_per_guide " + std::to_string(s.strandsPerGuide) +
                        " = " + std::to_string(strands) + " drawn strands, more than the " + std::to_string(kMaxCount) +
                        " the GPU numbers in 32 bits; lower --guides or strands_per_guide");
    uint64_t segments = strands * s.divisions;
    if (segments > kMaxCount)
        throw UserError(std::to_string(strands) + " drawn strands x divisions " + std::to_string(s.divisions) + " = " +
                        std::to_string(segments) + " segments, more than the " + std::to_string(kMaxCount) +
                        " a frame draws; lower --guides, strands_per_guide or divisions");
}

void checkWorkload(const Workload& w, const vk::DeviceReport& device)
{
    checkCounts(w);
    GpuMemory m = estimateGpuMemory(w);
    if (m.total() <= device.deviceLocalBytes)
        return;
    std::string parts = "simulation " + mib(m.simulation) + " for " + std::to_string(w.guides) + " guides x " +
                        std::to_string(w.verticesPerStrand) + " vertices and a " + std::to_string(w.sim.gridResolution) +
                        "^3 grid";
    std::string lower = "lower --guides, --vertices or --grid";
    if (w.render) {
        parts += ", hair " + mib(m.hair) + ", target " + mib(m.target) + " (" + std::to_string(w.render->width) + " x " +
                 std::to_string(w.render->height) + " x " + std::to_string(w.render->samples) + " samples), light maps " +
                 mib(m.lightMaps) + ", OIT " + mib(m.oit);
        lower += ", the size, samples, shadow_size or oit_nodes_per_pixel";
    }
    throw UserError("the workload needs " + mib(m.total()) + " of GPU memory (" + parts + "), but '" + device.name +
                    "' has " + mib(device.deviceLocalBytes) + "; " + lower);
}

}  // namespace wisp
