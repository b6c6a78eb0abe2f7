#version 460
// hair.vert: one "vertex" per patch: it only names the patch (guide and length chunk) and the
// instance (a chunk of up to 64 strands); the tessellation stages read the guide from the physics
// buffer themselves, so the patch size limit never caps a guide's vertex count. With
// push.reverseOrder the same patches come last to first (the OIT order-independence test).
#extension GL_GOOGLE_include_directive : require
#include "shared/strands.h"

layout(push_constant) uniform PushBlock { HairPush push; };
layout(location = 0) flat out uint outPatch;
layout(location = 1) flat out uint outChunk;

void main()
{
    uint patchIndex = uint(gl_VertexIndex);
    uint chunk = uint(gl_InstanceIndex);
    if (push.reverseOrder != 0u) {
        uint chunks = (push.strandsPerGuide + push.strandsPerPatch - 1u) / push.strandsPerPatch;
        patchIndex = push.guideCount * push.lengthChunks - 1u - patchIndex;
        chunk = chunks - 1u - chunk;
    }
    outPatch = patchIndex;
    outChunk = chunk;
    gl_Position = vec4(0.0);
}
