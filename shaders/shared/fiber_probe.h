// shaders/shared/fiber_probe.h: the interface of shaders/fiber_probe.comp, the kernel that
// evaluates the fibre BSDF (fiber_bsdf.h) on the GPU for given cases, so that a test can compare
// the GPU's eval, pdf and sampling with the C++ compile of the same header and with the CPU
// reference (tests/test_fiber_bsdf_gpu.cpp). One copy for GLSL and C++.
#ifndef WISP_SHARED_FIBER_PROBE_H
#define WISP_SHARED_FIBER_PROBE_H
#include "fiber_bsdf.h"
#include "prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kFiberProbeGroupSize = 64u;
GPU_CONST uint kFiberProbeBindingCases = 0;   // FiberProbeCase per case
GPU_CONST uint kFiberProbeBindingResults = 1; // FiberProbeResult per case

struct FiberProbeCase {
    FiberMaterial material;
    vec3 wo; // local frame, unit
    float h; // offset across the fibre
    vec3 wi; // local frame, unit: where eval and pdf are taken
    float pad;
    vec4 u; // the four uniform numbers of fiberSample
};

struct FiberProbeResult {
    vec3 f;    // fiberF(wo, wi)
    float pdf; // fiberPdf(wo, wi)
    vec3 sampleWi;
    float samplePdf;
    vec3 sampleFsum;
    float pad;
};

struct FiberProbePush {
    uint count;
};

GPU_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(gpu::FiberProbeCase) == 80);
static_assert(sizeof(gpu::FiberProbeResult) == 48);
#endif

#endif
