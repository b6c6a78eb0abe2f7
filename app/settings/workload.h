// app/settings/workload.h: a workload as a whole, checked before anything is built or allocated: the
// counts that must fit 32 bits (drawn strands, their segments), and the GPU memory the simulation
// and the drawing of it need, against what the device has. The command line calls it before it
// grows or loads hair; the solver (gpu_solver.cpp) and the OIT pool (renderer/graphics/oit.cpp) check
// their own allocations again against the same device.
#pragma once

#include "physics/simulation.h"
#include "renderer/settings.h"

#include <cstdint>

namespace wisp {

namespace vk {
struct DeviceReport;
}

struct Workload {
    uint64_t guides = 0; // simulated guide strands (0: the head alone, nothing simulated)
    uint32_t verticesPerStrand = 0;
    SimSettings sim;                        // the grid's resolution and sums
    const RenderSettings* render = nullptr; // null: the simulation alone (wisp simulate)
};

// Device memory by owner, in bytes. Estimates from the counts and settings, following what each
// owner allocates; the render parts are device-local images and buffers only.
struct GpuMemory {
    uint64_t simulation = 0; // the solver's buffers: solverDeviceBytes (fixed-point grid, the larger)
    uint64_t hair = 0;       // the tessellation's guide triangles, the lookup tables, the guides' lines
    uint64_t target = 0;     // MSAA colour and depth, the resolved colour
    uint64_t lightMaps = 0;  // the light's two depth maps and its opacity layers
    uint64_t oit = 0;        // list heads, resolved colour, and the node pool when its size is set
                             // (an automatic pool takes what the device allows: at least a node a pixel);
                             // made with transparency=oit whichever path draws the hair
    uint64_t raster = 0;     // the compute path's strand vertices (camera and light), per-pixel buffers,
                             // first fragment buffer, light buffers and hair image, when it draws the hair
    uint64_t total() const { return simulation + hair + target + lightMaps + oit + raster; }
};

// On `device` (hair_raster=auto resolved for its type, the fragment buffer within its storage-buffer
// range); without one, on a device of no type with a 4 GiB range.
GpuMemory estimateGpuMemory(const Workload& w, const vk::DeviceReport& device);
GpuMemory estimateGpuMemory(const Workload& w);

// Throws UserError when the drawn strands (guides x strands_per_guide) or their segments
// (x divisions) pass 2^32 - 1: strands are numbered in 32 bits on the GPU.
void checkCounts(const Workload& w);
// checkCounts, then the memory: throws UserError "the workload needs N MiB of GPU memory
// (simulation A MiB, ..., compute raster R MiB), but 'DEVICE' has M MiB; lower ..." when it is more
// than the device has.
void checkWorkload(const Workload& w, const vk::DeviceReport& device);

} // namespace wisp
