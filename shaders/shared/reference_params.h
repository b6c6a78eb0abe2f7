// shaders/shared/reference_params.h: the interface of the path tracer's kernel
// (shaders/reference_trace.comp): its bindings, its uniform block and push constants. The path
// itself is reference_path.h's. One copy for GLSL and C++.
#ifndef WISP_SHARED_REFERENCE_PARAMS_H
#define WISP_SHARED_REFERENCE_PARAMS_H
#include "frame_params.h"
#include "prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kReferenceGroupSize = 8u; // 8 x 8 pixels a workgroup

// Bindings of reference_trace.comp.
GPU_CONST uint kReferenceBindingParams = 0;    // uniform ReferenceParams
GPU_CONST uint kReferenceBindingNodes = 1;     // BvhNode[]
GPU_CONST uint kReferenceBindingPrims = 2;     // uint[]: primitive numbers in the leaves' order
GPU_CONST uint kReferenceBindingSegments = 3;  // TraceSegment[]
GPU_CONST uint kReferenceBindingTriangles = 4; // TraceTriangle[]
GPU_CONST uint kReferenceBindingSums = 5;      // vec4 per pixel, twice: the even samples', then the odd
GPU_CONST uint kReferenceBindingRays = 6;      // uint per pixel: the rays its samples cast

// The lights' angular radius (radians): small, as a studio's softbox far away (the sun is 0.0047).
GPU_CONST float kReferenceLightRadius = 0.01f;
GPU_CONST uint kReferenceRouletteStart = 3u;

struct ReferenceParams {
    FrameParams frame;
    mat4 inverseViewProjection; // clip -> world
    vec3 headAlbedo;            // the meshes' material (MeshRasterPush)
    float headRoughness;
    vec3 scalpAlbedo;
    float scalpStrength;
    uint width; // pixels
    uint height;
    uint segmentCount; // primitives below are segments, the rest triangles
    uint nodeCount;
    uint divisions;  // segments per strand (a segment's t along its strand from its number)
    uint maxBounces; // scattering events a path may have at most
    uint seed;
    float surfaceOffset; // how far a path leaving a mesh starts off it (asset units)
};

struct ReferencePush {
    uint firstSample; // the pass's first sample index (samples are numbered per pixel)
    uint samples;     // samples each pixel takes this pass
    uint pad0;
    uint pad1;
};

GPU_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(gpu::ReferenceParams) == sizeof(gpu::FrameParams) + 64 + 32 + 32);
static_assert(sizeof(gpu::ReferencePush) == 16);
#endif

#endif
