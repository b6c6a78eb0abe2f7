// shaders/shared/mesh_raster.h: the meshes (head, collision sphere, light marker) drawn in compute
// beside the compute strands (hair_raster=compute), one copy of the math for the kernels
// (shaders/mesh_raster.comp, mesh_shade.comp, hair_compose.comp) and their C++ twin
// (renderer/compute/mesh_raster_reference.cpp). On GPUs that run their graphics stages on a few units
// (the H100: 4x MSAA depth and shading of a 6,000-triangle head cost 1.8 ms there) the whole
// frame then stays in compute:
//   raster   one workgroup per triangle, its threads over the triangle's pixels: at each of the
//            pixel's samples (the standard MSAA positions) covered, the depth (atomicMin of its
//            float bits: depths in [0, 1] order as their bits do), then, in a second pass, which
//            triangle holds that depth (atomicMin of its id: the same winner every frame)
//   shade    one thread per pixel: each distinct triangle among its samples shaded once at the
//            pixel's centre (as a fragment shader is run under MSAA), weighted by the samples it
//            holds, the rest the backdrop (frameBackground): the resolved colour; the key light's visibility
//            from the nearest sample, as mesh_shadow.comp has it
//   compose  one thread per pixel: the hair (premultiplied) over the meshes, sRGB-encoded
// Triangles are set up in homogeneous 2D (Olano and Greer, "Triangle scan conversion using 2D
// homogeneous coordinates", 1997): no clipping, triangles behind the eye or across it fall out of
// the same inside test, and depth is clipped to [0, 1] per sample as Vulkan's depth clip does.
#ifndef WISP_SHARED_MESH_RASTER_H
#define WISP_SHARED_MESH_RASTER_H
#include "frame_params.h"
#include "lighting.h"
#include "prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kMeshRasterGroupSize = 64u; // threads per triangle (raster), per 8 x 8 pixels (shade)

// Bindings (the light's maps 4..7 are shared/shadows.h's).
GPU_CONST uint kMeshRasterBindingFrame = 0;          // uniform FrameParams
GPU_CONST uint kMeshRasterBindingVertices = 1;       // the object's vertices: 7 floats (position, normal, scalp)
GPU_CONST uint kMeshRasterBindingIndices = 2;        // the object's triangles: 3 uints each
GPU_CONST uint kMeshRasterBindingSphereVertices = 3; // (mesh_shade.comp) the unit sphere's vertices
GPU_CONST uint kMeshRasterBindingSphereIndices = 10; // (mesh_shade.comp) and triangles
GPU_CONST uint kMeshRasterBindingDepth = 11;         // uint per sample (pixel * samples + s): depth bits
GPU_CONST uint kMeshRasterBindingIds = 12;           // uint per sample: packMeshId, kNoMesh where none
GPU_CONST uint kMeshRasterBindingColor = 13;         // image2D rgba16f: the meshes, resolved, tone-mapped linear
GPU_CONST uint kMeshRasterBindingHair = 14;          // image2D rgba16f: the hair, premultiplied
GPU_CONST uint kMeshRasterBindingOut = 15;           // image2D rgba8: the frame, sRGB-encoded

GPU_CONST uint kMeshObjectHead = 0u;
GPU_CONST uint kMeshObjectSphere = 1u; // the collision sphere (push.sphere)
GPU_CONST uint kMeshObjectMarker = 2u; // the light's marker (push.marker)
GPU_CONST uint kNoMesh = 0xffffffffu;
GPU_CONST uint kMeshVertexFloats = 7u;
GPU_CONST uint kMeshDepthClear = 0x3f800000u; // 1.0: nothing drawn

// The collision sphere and the light's marker (mesh_pass.cpp draws them with the same).
GPU_CONST vec3 kSphereAlbedo = vec3(0.35f, 0.45f, 0.6f); // a blue-grey ball, apart from skin and hair
GPU_CONST float kSphereRoughness = 0.4f;
GPU_CONST vec3 kMarkerAlbedo = vec3(1.0f, 0.85f, 0.3f);
GPU_CONST float kMarkerRoughness = 0.2f;

// Push constants of the three kernels (96 bytes). The head's pose is FrameParams::headTransform.
struct MeshRasterPush {
    vec4 sphere; // centre, radius (0: none)
    vec4 marker; // centre, radius (0: none)
    vec3 headAlbedo;
    float headRoughness;
    vec3 scalpAlbedo;
    float scalpStrength;
    uint samples; // 1, 2, 4 or 8 per pixel
    uint width;   // pixels
    uint height;
    uint object;    // raster: kMeshObject*; compose: 1 when there is hair to lay over
    uint triangles; // raster: the object's triangle count
    uint pad0;
    uint pad1;
    uint pad2;
};

GPU_FN uint packMeshId(uint object, uint triangle)
{
    return (object << 30u) | triangle;
}

// Vulkan's standard sample locations (the spec's table), in [0, 1) of the pixel.
GPU_FN vec2 meshSamplePosition(uint s, uint samples)
{
    if (samples == 2u)
        return s == 0u ? vec2(0.75f, 0.75f) : vec2(0.25f, 0.25f);
    if (samples == 4u) {
        if (s == 0u)
            return vec2(0.375f, 0.125f);
        if (s == 1u)
            return vec2(0.875f, 0.375f);
        if (s == 2u)
            return vec2(0.125f, 0.625f);
        return vec2(0.625f, 0.875f);
    }
    if (samples == 8u) {
        if (s == 0u)
            return vec2(0.5625f, 0.3125f);
        if (s == 1u)
            return vec2(0.4375f, 0.6875f);
        if (s == 2u)
            return vec2(0.8125f, 0.5625f);
        if (s == 3u)
            return vec2(0.3125f, 0.1875f);
        if (s == 4u)
            return vec2(0.1875f, 0.8125f);
        if (s == 5u)
            return vec2(0.0625f, 0.4375f);
        if (s == 6u)
            return vec2(0.6875f, 0.9375f);
        return vec2(0.9375f, 0.0625f);
    }
    return vec2(0.5f, 0.5f);
}

// An object's model matrix: the head's pose, or a sphere placed and scaled.
GPU_FN mat4 meshObjectModel(uint object, mat4 headTransform, vec4 sphere, vec4 marker)
{
    if (object == kMeshObjectHead)
        return headTransform;
    vec4 s = object == kMeshObjectSphere ? sphere : marker;
    mat4 m = mat4(s.w);
    m[3] = vec4(s.x, s.y, s.z, 1.0f);
    return m;
}

// A triangle in homogeneous 2D: u = rows * (ndc.x, ndc.y, 1) / det are the perspective-correct
// barycentrics scaled by 1/w; inside where all three are >= 0 and their sum > 0 (in front of the
// eye). Two triangles sharing an edge compute its row as exact negatives (a cross product), so
// no sample falls between them. The depth, where all three vertices are in front of the eye, is
// the plane through their projections (pixels relative to the first vertex: small numbers, as a
// hardware rasterizer has them; a far head's depths differ in their fifth digit); else dot(u, z).
struct MeshTriangle {
    vec3 row0;
    vec3 row1;
    vec3 row2;
    vec3 z;      // the vertices' clip z
    vec4 bounds; // pixels: min x, min y, max x, max y (the whole target when a vertex is behind the eye)
    vec4 plane;  // pixels: the first vertex's projection (xy), its depth (z), the plane's use (w: 1)
    vec4 slopes; // the plane: the depth's change per pixel in x and y (xy)
    float det;   // 0: edge-on or degenerate, nothing drawn
};

GPU_FN MeshTriangle setupMeshTriangle(vec4 c0, vec4 c1, vec4 c2, vec2 size)
{
    MeshTriangle t;
    vec3 a = vec3(c0.x, c0.y, c0.w), b = vec3(c1.x, c1.y, c1.w), c = vec3(c2.x, c2.y, c2.w);
    t.row0 = cross(b, c);
    t.row1 = cross(c, a);
    t.row2 = cross(a, b);
    t.det = dot(a, t.row0);
    t.z = vec3(c0.z, c1.z, c2.z);
    t.plane = vec4(0.0f);
    t.slopes = vec4(0.0f);
    if (c0.w > 0.0f && c1.w > 0.0f && c2.w > 0.0f) {
        vec2 p0 = (vec2(c0.x, c0.y) / c0.w * 0.5f + 0.5f) * size;
        vec2 p1 = (vec2(c1.x, c1.y) / c1.w * 0.5f + 0.5f) * size;
        vec2 p2 = (vec2(c2.x, c2.y) / c2.w * 0.5f + 0.5f) * size;
        t.bounds = vec4(min(min(p0, p1), p2), max(max(p0, p1), p2));
        vec2 e1 = p1 - p0, e2 = p2 - p0;
        float area = e1.x * e2.y - e1.y * e2.x;
        if (area != 0.0f) {
            float z0 = c0.z / c0.w, dz1 = c1.z / c1.w - z0, dz2 = c2.z / c2.w - z0;
            t.plane = vec4(p0.x, p0.y, z0, 1.0f);
            t.slopes = vec4((dz1 * e2.y - dz2 * e1.y) / area, (dz2 * e1.x - dz1 * e2.x) / area, 0.0f, 0.0f);
        }
    } else {
        t.bounds = vec4(0.0f, 0.0f, size.x, size.y);
    }
    return t;
}

// The scaled barycentrics at a point of the target (pixels).
GPU_FN vec3 meshTriangleWeights(MeshTriangle t, vec2 pixel, vec2 size)
{
    vec3 p = vec3(pixel.x / size.x * 2.0f - 1.0f, pixel.y / size.y * 2.0f - 1.0f, 1.0f);
    return vec3(dot(t.row0, p), dot(t.row1, p), dot(t.row2, p)) / t.det;
}

// The depth a sample of the triangle holds, or a value above 1 where it does not cover it.
GPU_FN float meshSampleDepth(MeshTriangle t, vec2 pixel, vec2 size)
{
    if (t.det == 0.0f)
        return 2.0f;
    vec3 u = meshTriangleWeights(t, pixel, size);
    if (u.x < 0.0f || u.y < 0.0f || u.z < 0.0f || u.x + u.y + u.z <= 0.0f)
        return 2.0f;
    float depth = t.plane.w > 0.0f ? t.plane.z + t.slopes.x * (pixel.x - t.plane.x) + t.slopes.y * (pixel.y - t.plane.y)
                                   : dot(u, t.z);
    return depth >= 0.0f && depth <= 1.0f ? depth : 2.0f;
}

// The perspective-correct barycentrics (summing to 1) at a point, inside the triangle or not.
GPU_FN vec3 meshTriangleBarycentrics(MeshTriangle t, vec2 pixel, vec2 size)
{
    vec3 u = meshTriangleWeights(t, pixel, size);
    float sum = u.x + u.y + u.z;
    return abs(sum) > 0.0f ? u / sum : vec3(1.0f / 3.0f);
}

// The shading of mesh.frag: a surface (its scalp painted a darkened hair colour, matte) under the
// frame's lights (frameLight: the key as much as it reaches the point, `keyVisibility`; the fill and
// the rim unshadowed), plus the hemisphere ambient, tone-mapped.
GPU_FN vec3 meshSurfaceColor(FrameParams frame, vec3 n, vec3 v, float keyVisibility, vec3 albedo, float roughness,
                             vec3 scalpAlbedo, float scalp)
{
    if (dot(n, v) < 0.0f)
        n = -n; // back faces seen through open meshes shade like their front
    vec3 a = mix(albedo, scalpAlbedo, scalp);
    float r = mix(roughness, 1.0f, scalp);
    vec3 radiance = vec3(0.0f);
    for (uint i = 0u; i < kFrameLights; ++i) {
        FrameLight light = frameLight(frame, i);
        if (light.intensity <= 0.0f)
            continue;
        float visible = i == kFrameKeyLight ? keyVisibility : 1.0f;
        radiance += surfaceRadiance(n, light.direction, v, a, r, light.color * (light.intensity * visible));
    }
    radiance += a * frame.ambientIntensity * hemisphereAmbient(n, frame.skyColor, frame.groundColor);
    return toneMapAces(radiance * frame.exposure);
}

// Linear to sRGB-encoded (IEC 61966-2-1), per channel.
GPU_FN float encodeSrgb(float x)
{
    x = clamp(x, 0.0f, 1.0f);
    return x <= 0.0031308f ? 12.92f * x : 1.055f * pow(x, 1.0f / 2.4f) - 0.055f;
}

GPU_NAMESPACE_END

#ifdef __cplusplus
// The layouts GLSL gives these blocks, checked where they are defined (C++ only).
static_assert(sizeof(gpu::MeshRasterPush) == 96, "MeshRasterPush must fit the 128 bytes of push constants");
#endif

#endif
