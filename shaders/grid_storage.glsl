// grid_storage.glsl: the hair-hair grid's accumulators as the three kernels that write or read
// them see them: float sums (float atomics) or, in the GRID_FIXED variants, 64-bit integer sums
// scaled by params.gridFixedScale (deterministic: integer adds commute). The integer sums are
// four arrays one after another (density, then each momentum component), so the four atomics of
// one node go to four cache lines, which the GPU's memory serves in parallel (in one line they
// queue behind each other where many strands splat into the same node). Include after
// sim_common.glsl; the .comp file enables the extensions at its top.
#ifdef GRID_FIXED
layout(set = 0, binding = kSimBindingGrid, std430) buffer Grid { int64_t gridFixed[]; };  // 4 arrays of nodes

// Adds density and momentum already scaled to integers (the splat rounds each run's sums).
void gridAddSum(uint node, i64vec4 sum)
{
    for (uint w = 0u; w < kGridFixedWordsPerNode; ++w)
        atomicAdd(gridFixed[gridFixedWord(node, w, params.gridNodeCount)], sum[w]);
}

void gridZero(uint node)
{
    for (uint w = 0u; w < kGridFixedWordsPerNode; ++w)
        gridFixed[gridFixedWord(node, w, params.gridNodeCount)] = int64_t(0);
}

GridNode gridRead(uint node)
{
    uint n = params.gridNodeCount;
    float inv = 1.0 / params.gridFixedScale;
    GridNode g;
    g.density = float(gridFixed[gridFixedWord(node, 0u, n)]) * inv;
    g.momentum = vec3(float(gridFixed[gridFixedWord(node, 1u, n)]), float(gridFixed[gridFixedWord(node, 2u, n)]),
                      float(gridFixed[gridFixedWord(node, 3u, n)])) * inv;
    return g;
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
