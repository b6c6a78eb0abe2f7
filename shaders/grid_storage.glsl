// grid_storage.glsl: the hair-hair grid's accumulators as the two kernels that write or read them
// see them: float sums (float atomics) or, in the GRID_FIXED variants, 64-bit integer sums scaled
// by params.gridFixedScale (deterministic: integer adds commute). There are two sets: this step's
// (`Grid`, splatted by sim_integrate, read by grid_gather) and the next step's (`GridNext`, which
// grid_gather zeroes while it reads this step's, so no pass of its own clears them). The integer sums are
// four arrays one after another (density, then each momentum component), so the four atomics of
// one node go to four cache lines, which the GPU's memory serves in parallel (in one line they
// queue behind each other where many strands splat into the same node). Include after
// sim_common.glsl; the .comp file enables the extensions at its top.
#ifdef GRID_FIXED
layout(set = 0, binding = kSimBindingGrid, std430) buffer Grid { int64_t gridFixed[]; };  // 4 arrays of nodes
layout(set = 0, binding = kSimBindingGridNext, std430) writeonly buffer GridNext { int64_t gridFixedNext[]; };

void gridAdd(uint node, float density, vec3 momentum)
{
    i64vec4 sum = i64vec4(round(vec4(density, momentum) * params.gridFixedScale));
    for (uint w = 0u; w < kGridFixedWordsPerNode; ++w)
        atomicAdd(gridFixed[gridFixedWord(node, w, params.gridNodeCount)], sum[w]);
}

void gridZeroNext(uint node)
{
    for (uint w = 0u; w < kGridFixedWordsPerNode; ++w)
        gridFixedNext[gridFixedWord(node, w, params.gridNodeCount)] = int64_t(0);
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
layout(set = 0, binding = kSimBindingGridNext, std430) writeonly buffer GridNext { GridNode gridNext[]; };

void gridAdd(uint node, float density, vec3 momentum)
{
    atomicAdd(grid[node].density, density);
    atomicAdd(grid[node].momentum.x, momentum.x);
    atomicAdd(grid[node].momentum.y, momentum.y);
    atomicAdd(grid[node].momentum.z, momentum.z);
}

void gridZeroNext(uint node)
{
    gridNext[node].momentum = vec3(0.0);
    gridNext[node].density = 0.0;
}

GridNode gridRead(uint node)
{
    return grid[node];
}
#endif

// A node's velocity (momentum / density where it holds enough hair, else 0) and density.
vec4 gridNodeVelocity(uint node)
{
    GridNode g = gridRead(node);
    return vec4(g.density > kGridMinDensity ? g.momentum / g.density : vec3(0.0), g.density);
}
