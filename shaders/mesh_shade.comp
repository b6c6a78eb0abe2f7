#version 460
// mesh_shade.comp: one thread per pixel, after mesh_raster.comp: each distinct triangle among the
// pixel's samples shaded once at the pixel's centre (as a fragment shader runs under MSAA: the
// barycentrics extrapolate where the centre lies outside), weighted by the samples it holds; the
// samples no mesh covers take the backdrop (frameBackground at the pixel's centre, as the graphics
// meshes' background.frag has it): the pixel's resolved colour. The key light's
// visibility (light_visibility.glsl) is evaluated once, on the nearest sample's surface at the
// centre, as mesh_shadow.comp does for mesh.frag. See shared/mesh_raster.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/mesh_raster.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kMeshRasterBindingFrame) uniform FrameBlock { FrameParams frame; };
layout(push_constant) uniform PushBlock { MeshRasterPush push; };
layout(set = 0, binding = kMeshRasterBindingVertices, std430) readonly buffer Vertices { float vertices[]; };
layout(set = 0, binding = kMeshRasterBindingIndices, std430) readonly buffer Indices { uint indices[]; };
layout(set = 0, binding = kMeshRasterBindingSphereVertices, std430) readonly buffer SphereVertices { float sphereVertices[]; };
layout(set = 0, binding = kMeshRasterBindingSphereIndices, std430) readonly buffer SphereIndices { uint sphereIndices[]; };
layout(set = 0, binding = kMeshRasterBindingDepth, std430) readonly buffer Depth { uint depth[]; };
layout(set = 0, binding = kMeshRasterBindingIds, std430) readonly buffer Ids { uint ids[]; };
layout(set = 0, binding = kMeshRasterBindingColor, rgba16f) uniform writeonly image2D meshColor;
#include "light_visibility.glsl"

// One vertex of an object: position, normal, scalp weight.
float vertexFloat(uint object, uint index, uint k)
{
    uint i = index * kMeshVertexFloats + k;
    return object == kMeshObjectHead ? vertices[i] : sphereVertices[i];
}

uint vertexIndex(uint object, uint triangle, uint corner)
{
    return object == kMeshObjectHead ? indices[3u * triangle + corner] : sphereIndices[3u * triangle + corner];
}

// The surface of a triangle at a point of the screen: world position, normal and scalp weight.
struct Surface {
    vec3 position;
    vec3 normal;
    float scalp;
};

Surface surfaceAt(uint id, vec2 pixel, vec2 size)
{
    uint object = id >> 30u, triangle = id & 0x3fffffffu;
    mat4 model = meshObjectModel(object, frame.headTransform, push.sphere, push.marker);
    vec4 clip[3];
    vec3 position[3], normal[3];
    float scalp[3];
    for (uint c = 0u; c < 3u; ++c) {
        uint v = vertexIndex(object, triangle, c);
        position[c] = vec3(vertexFloat(object, v, 0u), vertexFloat(object, v, 1u), vertexFloat(object, v, 2u));
        normal[c] = vec3(vertexFloat(object, v, 3u), vertexFloat(object, v, 4u), vertexFloat(object, v, 5u));
        scalp[c] = vertexFloat(object, v, 6u);
        clip[c] = frame.viewProjection * (model * vec4(position[c], 1.0));
    }
    MeshTriangle t = setupMeshTriangle(clip[0], clip[1], clip[2], size);
    vec3 b = meshTriangleBarycentrics(t, pixel, size);
    Surface s;
    s.position = vec3(model * vec4(b.x * position[0] + b.y * position[1] + b.z * position[2], 1.0));
    s.normal = transpose(inverse(mat3(model))) * (b.x * normal[0] + b.y * normal[1] + b.z * normal[2]);
    s.scalp = object == kMeshObjectHead ? b.x * scalp[0] + b.y * scalp[1] + b.z * scalp[2] : 0.0;
    return s;
}

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height))
        return;
    uint first = (uint(pixel.y) * push.width + uint(pixel.x)) * push.samples;
    vec2 size = vec2(push.width, push.height), centre = vec2(pixel) + 0.5;
    // The nearest sample's triangle carries the light's visibility for the pixel.
    uint nearest = kNoMesh, nearestDepth = kMeshDepthClear;
    for (uint s = 0u; s < push.samples; ++s)
        if (ids[first + s] != kNoMesh && depth[first + s] < nearestDepth) {
            nearestDepth = depth[first + s];
            nearest = ids[first + s];
        }
    vec3 color = vec3(0.0);
    uint covered = 0u;
    if (nearest != kNoMesh) {
        vec2 visibility = lightVisibilityParts(surfaceAt(nearest, centre, size).position, centre, frame.shadowBias, true);
        for (uint s = 0u; s < push.samples; ++s) {
            uint id = ids[first + s];
            bool seen = id == kNoMesh;
            for (uint e = 0u; e < s; ++e)
                seen = seen || ids[first + e] == id;
            if (seen)
                continue;  // no mesh, or shaded at an earlier sample
            uint count = 0u;
            for (uint e = s; e < push.samples; ++e)
                count += ids[first + e] == id ? 1u : 0u;
            uint object = id >> 30u;
            Surface surface = surfaceAt(id, centre, size);
            vec3 albedo = object == kMeshObjectHead ? push.headAlbedo : object == kMeshObjectSphere ? kSphereAlbedo : kMarkerAlbedo;
            float roughness = object == kMeshObjectHead ? push.headRoughness : object == kMeshObjectSphere ? kSphereRoughness : kMarkerRoughness;
            float scalp = push.scalpStrength * clamp(surface.scalp, 0.0, 1.0);
            color += float(count) * meshSurfaceColor(frame, normalize(surface.normal),
                                                     normalize(frame.cameraPosition - surface.position),
                                                     visibility.x * visibility.y, albedo, roughness,
                                                     push.scalpAlbedo, scalp);
            covered += count;
        }
    }
    color += float(push.samples - covered) * frameBackground(frame, centre.y);
    imageStore(meshColor, pixel, vec4(color / float(push.samples), 1.0));
}
