// grid_storage.glsl: the hair-hair grid's accumulators as the three kernels that write or read
// them see them: float sums (float atomics) or, in the GRID_FIXED variants, 64-bit integer sums
// scaled by params.gridFixedScale (deterministic: integer adds commute). Include after
// sim_common.glsl; the .comp file enables the extensions at its top.
#ifdef GRID_FIXED
layout(set = 0, binding = kSimBindingGrid, std430) buffer Grid { int64_t gridFixed[]; };  // 4 per node

// Adds density and momentum already scaled to integers (the splat rounds each run's sums).
void gridAddSum(uint node, i64vec4 sum)
{
    uint base = node * kGridFixedWordsPerNode;
    for (uint w = 0u; w < kGridFixedWordsPerNode; ++w)
        atomicAdd(gridFixed[base + w], sum[w]);
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

// Adds (density, momentum).
void gridAddSum(uint node, vec4 sum)
{
    atomicAdd(grid[node].density, sum.x);
    atomicAdd(grid[node].momentum.x, sum.y);
    atomicAdd(grid[node].momentum.y, sum.z);
    atomicAdd(grid[node].momentum.z, sum.w);
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
