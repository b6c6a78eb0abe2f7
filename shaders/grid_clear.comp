#version 460
// grid_clear.comp: zeroes the hair-hair grid's accumulators, one node per thread. A separate
// dispatch: a workgroup barrier() cannot order the clear before other workgroups' splats.
#extension GL_GOOGLE_include_directive : require
#ifdef GRID_FIXED
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#else
#extension GL_EXT_shader_atomic_float : require
#endif
#include "sim_common.glsl"
#include "grid_storage.glsl"

layout(local_size_x = SIM_GROUP_SIZE) in;

void main()
{
    uint n = gl_GlobalInvocationID.x;
    if (n >= params.gridNodeCount)
        return;
    gridZero(n);
}
