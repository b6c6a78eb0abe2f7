// shaders/fiber_probe.comp: one thread per case: the fibre BSDF's eval, pdf and sample
// (shared/fiber_bsdf.h) written to a buffer, for tests/test_fiber_bsdf_gpu.cpp.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/fiber_probe.h"

layout(local_size_x = kFiberProbeGroupSize) in;
layout(std430, set = 0, binding = kFiberProbeBindingCases) readonly buffer Cases { FiberProbeCase cases[]; };
layout(std430, set = 0, binding = kFiberProbeBindingResults) writeonly buffer Results { FiberProbeResult results[]; };
layout(push_constant) uniform Push { FiberProbePush push; };

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count)
        return;
    FiberProbeCase c = cases[i];
    FiberBsdf b = makeFiberBsdf(c.material, c.h);
    FiberSample s = fiberSample(b, c.wo, c.u);
    FiberProbeResult r;
    r.f = fiberF(b, c.wo, c.wi);
    r.pdf = fiberPdf(b, c.wo, c.wi);
    r.sampleWi = s.wi;
    r.samplePdf = s.pdf;
    r.sampleFsum = s.fsum;
    r.pad = 0.0;
    results[i] = r;
}
