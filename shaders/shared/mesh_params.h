// shaders/shared/mesh_params.h: the mesh pass's vertex layout and push constants (model transform
// and surface colour), shared by mesh.vert/mesh.frag and renderer/mesh_pass.cpp.
#ifndef WISP_SHARED_MESH_PARAMS_H
#define WISP_SHARED_MESH_PARAMS_H
#include "prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kMeshLocationPosition = 0; // vec3, asset units
GPU_CONST uint kMeshLocationNormal = 1;   // vec3, unit length
GPU_CONST uint kMeshLocationScalp = 2;    // float, 0..1: how much hair grows here (the painted scalp)

// The shadow mask (mesh_shadow.comp writes it, mesh.frag reads it): per pixel, the key light's
// visibility at the nearest mesh surface, x the head's shadow and y the hair's transmittance.
GPU_CONST uint kMeshBindingShadowMask = 8; // mesh.frag: sampler2D; mesh_shadow.comp: image2D rgba8
GPU_CONST uint kMeshBindingDepth = 9;      // mesh_shadow.comp: the meshes' depth (sampler2D[MS])
GPU_CONST uint kMeshBindingFrame = 0;      // mesh_shadow.comp: FrameParams (= kFrameParamsBinding)

// Push constants of mesh_shadow.comp.
struct MeshShadowPush {
    mat4 inverseViewProjection; // clip -> world, to place each pixel's depth
    uint width;                 // pixels
    uint height;
    uint samples; // of the meshes' depth
    uint pad;
};

struct MeshPush {
    mat4 model;          // object -> world
    vec3 albedo;         // linear RGB diffuse reflectance, 0..1
    float roughness;     // GGX-free Blinn-Phong gloss control, 0 (sharp) .. 1 (matte)
    vec3 scalpAlbedo;    // the scalp under the hair: a darkened hair colour (production grooms paint it so
                         // that skin does not show between strands and along partings)
    float scalpStrength; // how far the scalp weight blends albedo toward scalpAlbedo, 0..1
};

GPU_NAMESPACE_END

#ifdef __cplusplus
// The layouts GLSL gives these blocks, checked where they are defined (C++ only).
static_assert(sizeof(gpu::MeshPush) == 96, "MeshPush: mat4 + vec3 + float + vec3 + float");
static_assert(sizeof(gpu::MeshShadowPush) == 80);
#endif

#endif
