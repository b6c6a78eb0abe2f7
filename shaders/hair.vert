#version 460
// hair.vert: one "vertex" per patch: it only names the patch (guide and length chunk) and the
// instance (a chunk of up to 64 strands); the tessellation stages read the guide from the physics
// buffer themselves, so the patch size limit never caps a guide's vertex count.
layout(location = 0) flat out uint outPatch;
layout(location = 1) flat out uint outChunk;

void main()
{
    outPatch = uint(gl_VertexIndex);
    outChunk = uint(gl_InstanceIndex);
    gl_Position = vec4(0.0);
}
