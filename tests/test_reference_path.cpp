// tests/test_reference_path.cpp: the path-traced reference's path (shaders/shared/reference_path.h,
// compiled as C++: the kernel's CPU twin) on one straight fibre of short thick segments, seen
// straight on and tilted out of the picture up to grazing, against integrals of the fibre's BSDF
// (shaders/shared/fiber_bsdf.h) over the offsets h the camera's rays meet it at:
// - a white furnace: an absorption-free fibre under a uniform sky of radiance 1: what leaves is the
//   fibre's albedo at each h (1 up to the BSDF's own energy balance, pbrt's hair furnace);
// - lit from behind by one light, no sky: what leaves is the light's single scattering, the BSDF at
//   the light's direction times its irradiance (a straight fibre cannot light itself).
// Each within its Monte Carlo noise, measured from the samples.
#include "renderer/reference/bvh.h"
#include "shaders/shared/reference_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

using namespace wisp;

namespace {

constexpr float kRadius = 0.05f;
constexpr float kSegment = 4.0f * kRadius; // short segments: many joints under the picture
constexpr uint32_t kDivisions = 40;
constexpr float kBetaM = 0.3f, kBetaN = 0.3f, kAlpha = 0.035f, kEta = 1.55f;

// The fibre through the origin along (0, cos tilt, sin tilt): tilted toward the camera (on +z,
// looking down -z) by `tilt`.
struct FibreScene {
    std::vector<gpu::TraceSegment> segments;
    reference::Bvh bvh;
    gpu::TraceBuffers buffers() const { return reference::traceBuffers(bvh, segments, {}); }
};

glm::vec3 fibreAxis(float tiltDegrees)
{
    float a = glm::radians(tiltDegrees);
    return {0.0f, std::cos(a), std::sin(a)};
}

FibreScene fibreScene(float tiltDegrees)
{
    FibreScene s;
    glm::vec3 t = fibreAxis(tiltDegrees);
    float half = 0.5f * kSegment * float(kDivisions);
    for (uint32_t i = 0; i < kDivisions; ++i)
        s.segments.push_back({(-half + kSegment * float(i)) * t, kRadius, (-half + kSegment * float(i + 1)) * t, 0u});
    s.bvh = reference::buildBvh(s.segments, {});
    return s;
}

// An orthographic camera on +z looking down -z over x in +-0.08 (the fibre 0.1 wide: every
// column of pixels that meets it meets it whole), y in +-0.06, depth 0 at z = 6, 1 at z = -6.
gpu::ReferenceParams params(const FibreScene& s, uint32_t width, uint32_t height)
{
    gpu::ReferenceParams p{};
    glm::mat4 vp(1.0f);
    vp[0][0] = 1.0f / 0.08f;
    vp[1][1] = -1.0f / 0.06f;
    vp[2][2] = -1.0f / 12.0f;
    vp[3][2] = 0.5f;
    p.inverseViewProjection = glm::inverse(vp);
    p.width = width;
    p.height = height;
    p.segmentCount = uint32_t(s.segments.size());
    p.nodeCount = uint32_t(s.bvh.nodes.size());
    p.divisions = kDivisions;
    p.maxBounces = 64;
    p.seed = 5;
    p.surfaceOffset = 1e-4f;
    p.frame.hair.sigmaA = glm::vec4(0.0f, 0.0f, 0.0f, kEta);
    p.frame.hair.roughness = glm::vec4(kBetaM, kBetaN, kAlpha, 0.0f);
    return p;
}

gpu::FiberBsdf bsdfAt(float h)
{
    return gpu::makeFiberBsdf(gpu::makeFiberMaterial(glm::vec3(0.0f), kEta, kBetaM, kBetaN, kAlpha), h);
}

// The mean over h in (-1, 1) (an orthographic camera meets a cylinder uniformly across it) of
// `value(h)`, by the midpoint rule at `steps` points.
template <typename F> double meanOverH(int steps, F value)
{
    double sum = 0.0;
    for (int i = 0; i < steps; ++i)
        sum += value(-1.0f + (2.0f * float(i) + 1.0f) / float(steps));
    return sum / steps;
}

// The fibre's albedo toward wo (local frame) at h: the integral of fsum = f |cos| over the sphere,
// on a grid in (sin theta_i, phi_i), where the solid angle is d(sin theta) d(phi).
double albedo(float h, glm::vec3 wo)
{
    gpu::FiberBsdf b = bsdfAt(h);
    gpu::FiberOutgoing o = gpu::fiberOutgoing(b, wo);
    constexpr int kS = 160, kP = 320;
    double sum = 0.0;
    for (int i = 0; i < kS; ++i) {
        float sinI = -1.0f + (2.0f * float(i) + 1.0f) / float(kS);
        for (int j = 0; j < kP; ++j) {
            float phi = 2.0f * std::numbers::pi_v<float> * (float(j) + 0.5f) / float(kP);
            sum += gpu::fiberLobeSumAt(b, o, sinI, phi).y; // green: the three are equal here
        }
    }
    return sum * (2.0 / kS) * (2.0 * std::numbers::pi / kP);
}

struct Measured {
    double mean = 0.0, error = 0.0; // over the samples whose camera ray met the fibre; the standard error
    int samples = 0;
};

Measured measure(const FibreScene& s, const gpu::ReferenceParams& p, uint32_t samplesPerPixel)
{
    gpu::TraceBuffers b = s.buffers();
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (uint32_t y = 0; y < p.height; ++y)
        for (uint32_t x = 0; x < p.width; ++x)
            for (uint32_t k = 0; k < samplesPerPixel; ++k) {
                uint32_t rays = 0;
                glm::vec4 v = gpu::referenceSample(b, p, {x, y}, k, rays);
                if (v.w > 0.0f)
                    continue; // the backdrop
                sum += v.y;
                sum2 += double(v.y) * v.y;
                ++n;
            }
    Measured m;
    m.samples = n;
    m.mean = sum / n;
    m.error = std::sqrt(std::max(sum2 / n - m.mean * m.mean, 0.0) / n);
    return m;
}

// The direction toward the camera in the fibre's frame (fiber_bsdf.h makeFiberFrame).
glm::vec3 cameraInFibreFrame(float tiltDegrees)
{
    glm::vec3 d(0.0f, 0.0f, -1.0f);
    gpu::FiberFrame f = gpu::makeFiberFrame(fibreAxis(tiltDegrees), d);
    return gpu::fiberToLocal(f, -d);
}

} // namespace

TEST(ReferencePath, AbsorptionFreeFibreInAWhiteFurnaceGivesItsAlbedoAtEveryTilt)
{
    for (float tilt : {0.0f, 30.0f, 60.0f, 75.0f, 85.0f}) {
        FibreScene s = fibreScene(tilt);
        gpu::ReferenceParams p = params(s, 32, 24);
        p.frame.ambientIntensity = 1.0f;
        p.frame.skyColor = glm::vec3(1.0f);
        p.frame.groundColor = glm::vec3(1.0f);
        glm::vec3 wo = cameraInFibreFrame(tilt);
        double want = meanOverH(16, [&](float h) { return albedo(h, wo); });
        Measured got = measure(s, p, 24);
        std::printf("furnace, tilt %2.0f deg: path %.4f +- %.4f (%d samples), the BSDF's albedo %.4f\n", double(tilt),
                    got.mean, got.error, got.samples, want);
        ASSERT_GT(got.samples, 1000);
        EXPECT_NEAR(got.mean, want, 4.0 * got.error + 0.005) << "tilt " << tilt;
    }
}

TEST(ReferencePath, BackLitFibreGivesTheLightsSingleScatteringAtEveryTilt)
{
    glm::vec3 toLight = glm::normalize(glm::vec3(0.0f, 0.35f, -1.0f)); // behind the fibre, a little above
    for (float tilt : {0.0f, 30.0f, 60.0f, 75.0f, 85.0f}) {
        FibreScene s = fibreScene(tilt);
        gpu::ReferenceParams p = params(s, 32, 24);
        p.frame.lightDirection = toLight;
        p.frame.lightIntensity = 1.0f;
        p.frame.lightColor = glm::vec3(1.0f);
        gpu::FiberFrame f = gpu::makeFiberFrame(fibreAxis(tilt), glm::vec3(0.0f, 0.0f, -1.0f));
        glm::vec3 wo = gpu::fiberToLocal(f, glm::vec3(0.0f, 0.0f, 1.0f));
        // The light's disc sampled as the path samples it, on a fixed grid.
        float cosMax = std::cos(gpu::kReferenceLightRadius);
        double want = meanOverH(1024, [&](float h) {
            gpu::FiberBsdf b = bsdfAt(h);
            gpu::FiberOutgoing o = gpu::fiberOutgoing(b, wo);
            double sum = 0.0;
            for (int i = 0; i < 8; ++i)
                for (int j = 0; j < 8; ++j) {
                    glm::vec3 wi =
                        gpu::sampleLightCone(toLight, cosMax, (float(i) + 0.5f) / 8.0f, (float(j) + 0.5f) / 8.0f);
                    sum += gpu::fiberLobeSum(b, o, gpu::fiberToLocal(f, wi)).y;
                }
            return sum / 64.0;
        });
        Measured got = measure(s, p, 48);
        std::printf("back-lit, tilt %2.0f deg: path %.4f +- %.4f (%d samples), single scattering %.4f\n", double(tilt),
                    got.mean, got.error, got.samples, want);
        ASSERT_GT(got.samples, 1000);
        EXPECT_NEAR(got.mean, want, 4.0 * got.error + 0.005 * want) << "tilt " << tilt;
    }
}
