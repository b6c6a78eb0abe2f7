#version 460
// grid_normalize.comp: node velocity = momentum / density where the node holds enough hair;
// w keeps the density for the gather's repulsion term.
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
    GridNode node = gridRead(n);
    vec3 velocity = node.density > kGridMinDensity ? node.momentum / node.density : vec3(0.0);
    gridVelocity[n] = vec4(velocity, node.density);
}
