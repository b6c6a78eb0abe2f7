#version 460
// mesh.vert: transforms head/body mesh vertices to clip space and passes the world-space
// position and normal to mesh.frag (mesh_light.vert, MESH_FROM_LIGHT: into the light's view).
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/mesh_params.h"

layout(location = kMeshLocationPosition) in vec3 inPosition;
layout(location = kMeshLocationNormal) in vec3 inNormal;
layout(location = kMeshLocationScalp) in float inScalp;

layout(set = 0, binding = kFrameParamsBinding) uniform FrameBlock { FrameParams frame; };
layout(push_constant) uniform PushBlock { MeshPush push; };

// The depth pass and the shading pass compute the same depths bit for bit (the shading tests
// LESS_OR_EQUAL against the first), whatever else each pipeline leaves out.
invariant gl_Position;

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outWorldNormal;
layout(location = 2) out float outScalp;

void main()
{
    vec4 world = push.model * vec4(inPosition, 1.0);
    outWorldPosition = world.xyz;
    // Normal matrix: inverse transpose of the model's upper 3x3 (handles non-uniform scale).
    outWorldNormal = transpose(inverse(mat3(push.model))) * inNormal;
    outScalp = inScalp;
#ifdef MESH_FROM_LIGHT
    gl_Position = frame.lightViewProjection * world;  // the shadow pass (depth only)
#else
    gl_Position = frame.viewProjection * world;
#endif
}
