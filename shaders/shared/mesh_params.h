// shaders/shared/mesh_params.h: the mesh pass's vertex layout and push constants (model transform
// and surface colour), shared by mesh.vert/mesh.frag and renderer/mesh_pass.cpp.
#ifndef WISP_SHARED_MESH_PARAMS_H
#define WISP_SHARED_MESH_PARAMS_H
#include "prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kMeshLocationPosition = 0;  // vec3, asset units
GPU_CONST uint kMeshLocationNormal = 1;    // vec3, unit length
GPU_CONST uint kMeshLocationScalp = 2;     // float, 0..1: how much hair grows here (the painted scalp)

struct MeshPush {
    mat4  model;          // object -> world
    vec3  albedo;         // linear RGB diffuse reflectance, 0..1
    float roughness;      // GGX-free Blinn-Phong gloss control, 0 (sharp) .. 1 (matte)
    vec3  scalpAlbedo;    // the scalp under the hair: a darkened hair colour (production grooms paint it so
                          // that skin does not show between strands and along partings)
    float scalpStrength;  // how far the scalp weight blends albedo toward scalpAlbedo, 0..1
};

GPU_NAMESPACE_END

#endif
