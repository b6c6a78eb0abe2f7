// app/settings/workload.cpp: a workload's 32-bit counts and its GPU memory, summed from what each owner
// says it allocates (solverDeviceBytes; GuidePass, RenderTarget, LightMaps and StrandRaster's
// deviceBytes; the graphics path's through neutral headers: guideTriangleBytes, oitDeviceBytes;
// each in its own formats) and checked against the device up front.
#include "app/settings/workload.h"

#include "core/error.h"
#include "gpu/context.h"
#include "renderer/compute/mesh_raster.h"
#include "renderer/compute/strand_raster.h"
#include "renderer/guide_pass.h"
#include "renderer/hair_lut_image.h"
#include "renderer/light_maps.h"
#include "renderer/oit_stats.h"
#include "renderer/render_target.h"
#include "renderer/strand_draw.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace wisp {

namespace {

constexpr uint64_t kMaxCount = std::numeric_limits<uint32_t>::max();

uint64_t mebibytes(uint64_t bytes)
{
    return (bytes + (uint64_t(1) << 20) - 1) >> 20;
}

std::string mib(uint64_t bytes)
{
    return std::to_string(mebibytes(bytes)) + " MiB";
}

bool drawnInCompute(const Workload& w)
{
    return w.render && w.guides > 0 && resolveHairRaster(w.render->hairRaster) == HairRaster::Compute;
}

// What the compute path allocates for a first frame: every strand at full detail (LOD draws
// fewer); the light's share as Renderer::prepare draws them (at least one a guide, none with
// shadows off); the fragments within the budget.
StrandRaster::DeviceSizes rasterSizes(const Workload& w, const vk::DeviceReport& device)
{
    const RenderSettings& r = *w.render;
    uint32_t perGuide = r.strands.strandsPerGuide;
    uint32_t light = drawnStrandsPerGuide(perGuide, lightLodStrands(float(perGuide), r.shadows.strandFraction));
    return {.extent = {r.width, r.height},
            .guides = w.guides,
            .strandsPerGuide = perGuide,
            .lightStrandsPerGuide = r.shadows.enabled ? light : 0,
            .divisions = r.strands.divisions,
            .lightMapSize = r.shadows.mapSize,
            .samples = std::max<uint32_t>(r.samples, 1),
            .fragmentBudget = StrandRaster::fragmentBudget(uint64_t(r.fragmentBudgetMiB) << 20, device.deviceLocalBytes,
                                                           device.maxStorageBufferRange)};
}

} // namespace

GpuMemory estimateGpuMemory(const Workload& w)
{
    vk::DeviceReport any;
    any.maxStorageBufferRange = std::numeric_limits<uint32_t>::max();
    any.deviceLocalBytes = std::numeric_limits<uint64_t>::max();
    return estimateGpuMemory(w, any);
}

// Each owner states what it allocates, in its own formats, beside the allocation.
GpuMemory estimateGpuMemory(const Workload& w, const vk::DeviceReport& device)
{
    GpuMemory m;
    uint64_t grid = uint64_t(w.sim.gridResolution) * w.sim.gridResolution * w.sim.gridResolution;
    if (w.guides > 0)
        m.simulation = solverDeviceBytes(w.guides, w.verticesPerStrand, grid, /*fixedPointGrid=*/true);
    if (!w.render)
        return m;
    const RenderSettings& r = *w.render;
    VkExtent2D extent{r.width, r.height};
    // The tessellation's guide triangles only where it draws (the compute path counts its own).
    m.hair = (drawnInCompute(w) ? 0 : guideTriangleBytes(w.guides)) + HairLutImage::kBytes +
             GuidePass::deviceBytes(w.guides, w.verticesPerStrand);
    m.target = RenderTarget::deviceBytes(extent, std::max<uint32_t>(r.samples, 1));
    m.lightMaps = LightMaps::deviceBytes(r.shadows.mapSize);
    if (r.transparency.mode == Transparency::Oit && w.guides > 0 && !drawnInCompute(w))
        m.oit = oitDeviceBytes(extent, r.transparency.oitNodesPerPixel); // (only the graphics path's hair uses it)
    if (drawnInCompute(w)) {
        // Every strand at full detail (LOD draws fewer); the light's share as Renderer::prepare
        // draws them: at least one a guide, none with shadows off.
        m.raster = StrandRaster::deviceBytes(rasterSizes(w, device));
        // The meshes drawn in compute beside it (unless the guides are shown).
        if (!r.strands.showGuides)
            m.raster += MeshRaster::deviceBytes(extent, std::max<uint32_t>(r.samples, 1));
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
    GpuMemory m = estimateGpuMemory(w, device);
    if (m.total() <= device.deviceLocalBytes) {
        // It fits the memory; each buffer must fit one storage buffer's range too.
        if (drawnInCompute(w)) {
            for (const StrandRaster::SizedBuffer& b : StrandRaster::growingBuffers(rasterSizes(w, device)))
                if (b.bytes > device.maxStorageBufferRange)
                    throw UserError("the compute path's " + std::string(b.name) + " needs " + std::to_string(b.bytes) +
                                    " bytes for " + std::to_string(w.guides) + " guides x strands_per_guide " +
                                    std::to_string(w.render->strands.strandsPerGuide) + " x divisions " +
                                    std::to_string(w.render->strands.divisions) + " at " +
                                    std::to_string(w.render->width) + " x " + std::to_string(w.render->height) +
                                    ", more than the " + std::to_string(device.maxStorageBufferRange) +
                                    " bytes one storage buffer may hold on '" + device.name +
                                    "'; lower --guides, strands_per_guide, divisions or the size");
        }
        return;
    }
    std::string parts = "simulation " + mib(m.simulation) + " for " + std::to_string(w.guides) + " guides x " +
                        std::to_string(w.verticesPerStrand) + " vertices and a " +
                        std::to_string(w.sim.gridResolution) + "^3 grid";
    std::string lower = "lower --guides, --vertices or --grid";
    if (w.render) {
        parts += ", hair " + mib(m.hair) + ", target " + mib(m.target) + " (" + std::to_string(w.render->width) +
                 " x " + std::to_string(w.render->height) + " x " + std::to_string(w.render->samples) +
                 " samples), light maps " + mib(m.lightMaps);
        // Advice only of what lowers what is counted: the lists' pool where the graphics path draws
        // the hair with them, and only when its size is the user's (the automatic one fits itself).
        std::string oit = m.oit > 0 && w.render->transparency.oitNodesPerPixel > 0 ? ", oit_nodes_per_pixel" : "";
        if (m.oit > 0)
            parts += ", OIT " + mib(m.oit);
        lower += ", the size, samples or shadow_size" + oit;
        if (drawnInCompute(w)) {
            const StrandSettings& s = w.render->strands;
            parts += ", compute raster " + mib(m.raster) + " (" + std::to_string(w.guides * s.strandsPerGuide) +
                     " strands x " + std::to_string(s.divisions) + " divisions)";
            lower = "lower --guides, --vertices or --grid, strands_per_guide, divisions, the size, samples or "
                    "shadow_size";
        }
    }
    throw UserError("the workload needs " + mib(m.total()) + " of GPU memory (" + parts + "), but '" + device.name +
                    "' has " + mib(device.deviceLocalBytes) + "; " + lower);
}

} // namespace wisp
