// grid_storage.glsl: the hair-hair grid's accumulators as the three kernels that write or read
// them see them: float sums (float atomics) or, in the GRID_FIXED variants, 64-bit integer sums
// scaled by params.gridFixedScale (deterministic: integer adds commute). Include after
// sim_common.glsl; the .comp file enables the extensions at its top.
#ifdef GRID_FIXED
layout(set = 0, binding = kSimBindingGrid, std430) buffer Grid { int64_t gridFixed[]; };  // 4 per node

void gridAdd(uint node, float density, vec3 momentum)
{
    float s = params.gridFixedScale;
    uint base = node * kGridFixedWordsPerNode;
    atomicAdd(gridFixed[base + 0u], int64_t(round(density * s)));
    atomicAdd(gridFixed[base + 1u], int64_t(round(momentum.x * s)));
    atomicAdd(gridFixed[base + 2u], int64_t(round(momentum.y * s)));
    atomicAdd(gridFixed[base + 3u], int64_t(round(momentum.z * s)));
}

void gridZero(uint node)
{
    for (uint w = 0u; w < kGridFixedWordsPerNode; ++w)
        gridFixed[node * kGridFixedWordsPerNode + w] = int64_t(0);
}

GridNode gridRead(uint node)
{
    uint base = node * kGridFixedWordsPerNode;
    float inv = 1.0 / params.gridFixedScale;
    GridNode n;
    n.density = float(gridFixed[base]) * inv;
    n.momentum = vec3(float(gridFixed[base + 1u]), float(gridFixed[base + 2u]), float(gridFixed[base + 3u])) * inv;
    return n;
}
#else
layout(set = 0, binding = kSimBindingGrid, std430) buffer Grid { GridNode grid[]; };

void gridAdd(uint node, float density, vec3 momentum)
{
    atomicAdd(grid[node].density, density);
    atomicAdd(grid[node].momentum.x, momentum.x);
    atomicAdd(grid[node].momentum.y, momentum.y);
    atomicAdd(grid[node].momentum.z, momentum.z);
}

void gridZero(uint node)
{
    grid[node].momentum = vec3(0.0);
    grid[node].density = 0.0;
}

GridNode gridRead(uint node)
{
    return grid[node];
}
#endif
