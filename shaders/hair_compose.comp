#version 460
// hair_compose.comp: one thread per pixel: the compute strands' hair (premultiplied) over the
// compute meshes' resolved colour, blended in linear light as the sRGB target blends, and stored
// sRGB-encoded (the frame's storage image is copied into the target's sRGB result). With
// push.object 0 there is no hair: the meshes alone. See shared/mesh_raster.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/mesh_raster.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform PushBlock { MeshRasterPush push; };
layout(set = 0, binding = kMeshRasterBindingColor, rgba16f) uniform readonly image2D meshColor;
layout(set = 0, binding = kMeshRasterBindingHair, rgba16f) uniform readonly image2D hairColor;
layout(set = 0, binding = kMeshRasterBindingOut, rgba8) uniform writeonly image2D frameColor;

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height))
        return;
    vec3 color = imageLoad(meshColor, pixel).rgb;
    if (push.object != 0u) {
        vec4 hair = imageLoad(hairColor, pixel);
        color = hair.rgb + (1.0 - hair.a) * color;
    }
    imageStore(frameColor, pixel, vec4(encodeSrgb(color.r), encodeSrgb(color.g), encodeSrgb(color.b), 1.0));
}
