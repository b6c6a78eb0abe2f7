// shaders/shared/reference_path.h: the path-traced reference of the real-time frame, one sample of
// one pixel, one copy for the kernel (shaders/reference_trace.comp) and its CPU twin
// (renderer/reference/path_reference.cpp). What it renders is the real-time frame's (FrameParams):
//   camera   the frame's view and projection, a ray through a uniformly jittered point of the pixel
//   hair     the drawn strands' segments as capsules (trace.h) with the exact fibre BSDF of Chiang et
//            al. 2016 (fiber_bsdf.h): the look's absorption, varied per strand and along it as the
//            real-time shading varies it (strandAbsorptionScale), its roughness and cuticle tilt
//   meshes   the real-time meshes' material (lighting.h surfaceRadiance: Lambert and a weak
//            normalized Blinn-Phong, the scalp painted as mesh_shade.comp paints it), two-sided
//   lights   the frame's three directional lights (key, fill, rim: frameLight), each a disc of
//            angular radius kReferenceLightRadius of the same irradiance, every one shadowed by
//            everything (the real-time frame shadows the key alone); the ambient as a sky of
//            radiance ambientIntensity * hemisphereAmbient(direction) seen by paths that escape
//   backdrop a camera ray that meets nothing shows the frame's backdrop (frameBackground), laid
//            under the pixel's hits by their share of its samples as the real-time frame lays the
//            hair over the backdrop
// The path: next-event estimation of each light at every hit, then the BSDF sampled (the fibre's
// importance sampling; the meshes' cosine-weighted), Russian roulette after kReferenceRouletteStart
// bounces (blonde hair scatters light through many fibres: paths end by roulette, not by a count,
// up to maxBounces). A path leaving a fibre starts on its axis: inside its own capsule, which it is not
// hit by again (trace.h: hits are entries), and the neighbouring segments it passes through at a joint
// before it leaves the strand are no hits either (trace_bvh.h traceThroughJoint).
// Units: radiance as the real-time frame's (a light of intensity E and colour c gives a surface
// facing it the irradiance E c), tone-mapped the same way (exposure, ACES) once the samples are
// averaged (renderer/reference/reference_tracer.cpp).
#ifndef WISP_SHARED_REFERENCE_PATH_H
#define WISP_SHARED_REFERENCE_PATH_H
#include "fiber_bsdf.h"
#include "frame_params.h"
#include "lighting.h"
#include "mesh_raster.h"
#include "prelude.h"
#include "reference_params.h"
#include "sim.h"
#include "strand_shading.h"
#include "trace_bvh.h"

GPU_NAMESPACE_BEGIN

// ---- Random numbers: a counter per pixel and sample, hashed (deterministic, order-free) ----------

GPU_FN uint referenceRngStart(uint seed, uvec2 pixel, uint width, uint sampleIndex)
{
    return hashUint(hashUint(seed * 0x9E3779B9u + pixel.y * width + pixel.x) ^
                    (sampleIndex * 0x85EBCA6Bu + 0x27D4EB2Fu));
}

GPU_FN float referenceNext(GPU_INOUT(uint) state)
{
    state = hashUint(state);
    return float(state >> 8u) * (1.0f / 16777216.0f);
}

// Two and four numbers in sequence (named, not as a call's arguments: C++ leaves their order open).
GPU_FN vec2 referenceNext2(GPU_INOUT(uint) state)
{
    float a = referenceNext(state);
    float b = referenceNext(state);
    return vec2(a, b);
}

GPU_FN vec4 referenceNext4(GPU_INOUT(uint) state)
{
    vec2 a = referenceNext2(state);
    vec2 b = referenceNext2(state);
    return vec4(a, b);
}

// ---- Lights and sky ------------------------------------------------------------------------------

// A direction toward a disc light of angular radius r around the unit direction l, uniform in its
// solid angle. With the disc's radiance E / solid angle, a sample's estimate is f |cos| E.
GPU_FN vec3 sampleLightCone(vec3 l, float cosMax, float u0, float u1)
{
    float c = 1.0f - u0 * (1.0f - cosMax);
    float s = sqrt(max(0.0f, 1.0f - c * c));
    float phi = 2.0f * kFiberPi * u1;
    vec3 a = abs(l.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
    vec3 x = normalize(cross(a, l));
    vec3 y = cross(l, x);
    return normalize(c * l + s * (cos(phi) * x + sin(phi) * y));
}

// What a path that escapes sees: the frame's hemisphere ambient as a sky.
GPU_FN vec3 referenceSky(FrameParams frame, vec3 d)
{
    return frame.ambientIntensity * hemisphereAmbient(d, frame.skyColor, frame.groundColor);
}

// fromStrand: the strand the shadow ray leaves from its axis, or kTraceNoHit (trace_bvh.h).
GPU_FN bool referenceOccluded(TraceBuffers scene, vec3 o, vec3 wi, uint fromStrand, GPU_INOUT(uint) rays)
{
    rays += 1u;
    return traceScene(scene, o, wi, 0.0f, kTraceInfinity, true, fromStrand).prim != kTraceNoHit;
}

// ---- Camera ----------------------------------------------------------------------------------------

// The ray through point `at` of the target (pixels, (0, 0) its top-left corner): from the near
// plane toward the far one, through the frame's inverse view-projection (Vulkan: y down, depth 0..1).
GPU_FN vec3 cameraRayPoint(mat4 inverseViewProjection, vec2 ndc, float depth)
{
    vec4 w = inverseViewProjection * vec4(ndc.x, ndc.y, depth, 1.0f);
    return vec3(w) / w.w;
}

// ---- One sample --------------------------------------------------------------------------------

// The radiance one path brings to pixel `pixel` (xyz), and in w 1 when its camera ray met nothing
// (the backdrop shows there; xyz is then 0). `rays` counts the rays cast (each walk of the
// hierarchy: the path's and the lights' shadow rays).
GPU_FN vec4 referenceSample(TraceBuffers scene, ReferenceParams P, uvec2 pixel, uint sampleIndex, GPU_INOUT(uint) rays)
{
    uint rng = referenceRngStart(P.seed, pixel, P.width, sampleIndex);
    vec2 at = vec2(pixel) + referenceNext2(rng);
    vec2 ndc = at / vec2(float(P.width), float(P.height)) * 2.0f - 1.0f;
    vec3 o = cameraRayPoint(P.inverseViewProjection, ndc, 0.0f);
    vec3 d = normalize(cameraRayPoint(P.inverseViewProjection, ndc, 1.0f) - o);
    float cosMax = cos(kReferenceLightRadius);

    vec3 radiance = vec3(0.0f);
    vec3 throughput = vec3(1.0f);
    uint fromStrand = kTraceNoHit; // the strand the path leaves, if it leaves one
    for (uint bounce = 0u; bounce < P.maxBounces; ++bounce) {
        rays += 1u;
        TraceHit hit = traceScene(scene, o, d, 0.0f, kTraceInfinity, false, fromStrand);
        if (hit.prim == kTraceNoHit) {
            if (bounce == 0u)
                return vec4(0.0f, 0.0f, 0.0f, 1.0f);
            radiance += throughput * referenceSky(P.frame, d);
            break;
        }
        vec3 p = o + hit.t * d;
        vec3 wo = -d;
        if (hit.prim < scene.segmentCount) {
            // A fibre: its frame, the offset h across it, its absorption at this point of its strand.
            TraceSegment s = traceSegment(scene, hit.prim);
            vec3 axis = mix(s.a, s.b, hit.u);
            FiberFrame f = makeFiberFrame(normalize(s.b - s.a), d);
            float h = clamp(hit.v, -1.0f, 1.0f); // capsuleEntry's, from the ray and the axis (not from p)
            float t = (float(hit.prim % P.divisions) + hit.u) / float(P.divisions);
            HairMaterial hm = P.frame.hair;
            FiberBsdf b = makeFiberBsdf(makeFiberMaterial(vec3(hm.sigmaA) * strandAbsorptionScale(P.frame, s.strand, t),
                                                          hm.sigmaA.w, hm.roughness.x, hm.roughness.y, hm.roughness.z),
                                        h);
            FiberOutgoing fo = fiberOutgoing(b, fiberToLocal(f, wo));
            for (uint i = 0u; i < kFrameLights; ++i) {
                FrameLight light = frameLight(P.frame, i);
                vec2 ul = referenceNext2(rng);
                vec3 wi = sampleLightCone(light.direction, cosMax, ul.x, ul.y);
                if (light.intensity > 0.0f && !referenceOccluded(scene, axis, wi, s.strand, rays))
                    radiance +=
                        throughput * vec3(fiberLobeSum(b, fo, fiberToLocal(f, wi))) * light.color * light.intensity;
            }
            FiberSample fs = fiberSampleFrom(b, fo, referenceNext4(rng));
            if (!(fs.pdf > 0.0f))
                break;
            throughput *= fs.fsum / fs.pdf;
            o = axis;
            d = normalize(fiberToWorld(f, fs.wi));
            fromStrand = s.strand;
        } else {
            // A mesh: its interpolated normal facing the viewer (as the real-time shading flips
            // back faces), the head's or the sphere's surface, the scalp painted on the head.
            TraceTriangle tri = traceTriangle(scene, hit.prim - scene.segmentCount);
            float w0 = 1.0f - hit.u - hit.v;
            vec3 n = normalize(w0 * vec3(tri.n0) + hit.u * vec3(tri.n1) + hit.v * vec3(tri.n2));
            vec3 ng = normalize(cross(vec3(tri.p1) - vec3(tri.p0), vec3(tri.p2) - vec3(tri.p0)));
            if (dot(ng, wo) < 0.0f)
                ng = -ng;
            if (dot(n, wo) < 0.0f)
                n = -n;
            uint object = uint(tri.n0.w);
            vec3 albedo = object == kMeshObjectHead ? P.headAlbedo
                                                    : (object == kMeshObjectSphere ? kSphereAlbedo : kMarkerAlbedo);
            float roughness = object == kMeshObjectHead
                                  ? P.headRoughness
                                  : (object == kMeshObjectSphere ? kSphereRoughness : kMarkerRoughness);
            float scalp = object == kMeshObjectHead
                              ? P.scalpStrength * clamp(w0 * tri.p0.w + hit.u * tri.p1.w + hit.v * tri.p2.w, 0.0f, 1.0f)
                              : 0.0f;
            vec3 a = mix(albedo, P.scalpAlbedo, scalp);
            float r = mix(roughness, 1.0f, scalp);
            vec3 off = p + ng * P.surfaceOffset;
            for (uint i = 0u; i < kFrameLights; ++i) {
                FrameLight light = frameLight(P.frame, i);
                vec2 ul = referenceNext2(rng);
                vec3 wi = sampleLightCone(light.direction, cosMax, ul.x, ul.y);
                if (light.intensity > 0.0f && dot(ng, wi) > 0.0f &&
                    !referenceOccluded(scene, off, wi, kTraceNoHit, rays))
                    radiance += throughput * surfaceRadiance(n, wi, wo, a, r, light.color * light.intensity);
            }
            // Cosine-weighted around n: the weight f cos / pdf = pi f = a + pi * highlight.
            vec2 uc = referenceNext2(rng);
            float u0 = uc.x, u1 = uc.y;
            float c = sqrt(1.0f - u0);
            float sn = sqrt(u0);
            vec3 ax = abs(n.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
            vec3 tx = normalize(cross(ax, n));
            vec3 ty = cross(n, tx);
            vec3 wi = c * n + sn * (cos(2.0f * kFiberPi * u1) * tx + sin(2.0f * kFiberPi * u1) * ty);
            if (dot(wi, ng) <= 0.0f || c <= 0.0f)
                break;
            throughput *= surfaceRadiance(n, wi, wo, a, r, vec3(1.0f)) * (kFiberPi / c);
            o = off;
            d = wi;
            fromStrand = kTraceNoHit;
        }
        // Russian roulette: a path continues with the probability of its largest throughput.
        if (bounce + 1u >= kReferenceRouletteStart) {
            float q = min(max(max(throughput.x, throughput.y), throughput.z), 1.0f);
            if (referenceNext(rng) >= q)
                break;
            throughput /= q;
        }
    }
    return vec4(radiance, 0.0f);
}

GPU_NAMESPACE_END

#endif
