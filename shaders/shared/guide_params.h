// shaders/shared/guide_params.h: the guide-line pass (simulated guide strands drawn as lines,
// the physics' debug view): vertex layout and push constants.
#ifndef WISP_SHARED_GUIDE_PARAMS_H
#define WISP_SHARED_GUIDE_PARAMS_H
#include "prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kGuideLocationPosition = 0; // vec4: the solver's positions buffer (w: inverse mass)

struct GuidePush {
    vec3 rootColor;         // linear RGB at the root
    uint verticesPerStrand; // to find a vertex's place along its strand
    vec3 tipColor;          // linear RGB at the tip
    float pad;
};

GPU_NAMESPACE_END

#ifdef __cplusplus
// The layouts GLSL gives these blocks, checked where they are defined (C++ only).
static_assert(sizeof(gpu::GuidePush) == 32, "GuidePush: two vec3s, each with a scalar");
#endif

#endif
