// tests/fiber_bsdf_cases.h: random fibres, directions and sampling numbers for comparing the fibre
// BSDF of shaders/shared/fiber_bsdf.h (its C++ compile, and the GPU's through fiber_probe.comp)
// with the CPU reference, and the comparison itself.
#pragma once

#include "shaders/shared/fiber_probe.h"
#include "shading/hair_bsdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace wisp::test {

struct FiberCase {
    float h, eta, betaM, betaN, alphaDeg;
    glm::vec3 sigmaA, wo, wi;
    glm::vec4 u;
};

// Parameters over the ranges of hair a head shows (the look's default beta is 0.3), directions
// uniform on the sphere. beta_m and beta_n from 0.25: narrower lobes magnify the last bits of the
// angles past 1e-5, and neither side is then the more exact. M_p's exponent
// (cos_i cos_o - sin_i sin_o - 1) / v cancels near the lobe's peak: the CPU reference takes it in
// double but from float sines and cosines, which agree with sin^2 + cos^2 = 1 only to float's eps,
// so its own value is uncertain by eps / v (3e-5 for the TT lobe at beta_m = 0.1), the header's by
// eps / sqrt(v) (fiber_bsdf.h); N_p moves by (an angle's error) / s, and the C library's atan2 and
// the header's differ by an ULP or two (2e-7 / s = 1e-5 at beta_n = 0.1).
inline std::vector<FiberCase> randomFiberCases(int n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto sphere = [&] {
        float x = 1.0f - 2.0f * u(rng), phi = 2.0f * std::numbers::pi_v<float> * u(rng);
        float r = std::sqrt(std::max(0.0f, 1.0f - x * x));
        return glm::vec3(x, r * std::cos(phi), r * std::sin(phi));
    };
    std::vector<FiberCase> cases;
    for (int i = 0; i < n; ++i) {
        FiberCase c;
        c.h = -0.999f + 1.998f * u(rng);
        c.eta = 1.3f + 0.7f * u(rng);
        c.betaM = 0.25f + 0.75f * u(rng);
        c.betaN = 0.25f + 0.75f * u(rng);
        c.alphaDeg = -10.0f + 20.0f * u(rng);
        c.sigmaA = glm::vec3(5.0f * u(rng), 5.0f * u(rng), 5.0f * u(rng));
        c.wo = sphere();
        c.wi = sphere();
        c.u = glm::vec4(u(rng), u(rng), u(rng), u(rng));
        cases.push_back(c);
    }
    return cases;
}

inline shading::HairParams hairParams(const FiberCase& c)
{
    shading::HairParams p;
    p.h = c.h;
    p.eta = c.eta;
    p.sigmaA = c.sigmaA;
    p.betaM = c.betaM;
    p.betaN = c.betaN;
    p.alphaDeg = c.alphaDeg;
    return p;
}

inline gpu::FiberMaterial fiberMaterial(const FiberCase& c)
{
    return gpu::makeFiberMaterial(c.sigmaA, c.eta, c.betaM, c.betaN, c.alphaDeg * std::numbers::pi_v<float> / 180.0f);
}

inline gpu::FiberProbeCase probeCase(const FiberCase& c)
{
    return {.material = fiberMaterial(c), .wo = c.wo, .h = c.h, .wi = c.wi, .pad = 0.0f, .u = c.u};
}

// What fiber_probe.comp computes for a case, here through the C++ compile of the header.
inline gpu::FiberProbeResult evaluateFiberCase(const gpu::FiberBsdf& b, const FiberCase& c)
{
    gpu::FiberSample s = gpu::fiberSample(b, c.wo, c.u);
    return {.f = gpu::fiberF(b, c.wo, c.wi),
            .pdf = gpu::fiberPdf(b, c.wo, c.wi),
            .sampleWi = s.wi,
            .samplePdf = s.pdf,
            .sampleFsum = s.fsum,
            .pad = 0.0f};
}

// |got - want| <= tol * max(|want|, floor): relative, with a floor for values near 0 (a lobe's far
// tail, where the absolute error is what counts): 1e-2 for the BSDF's values (O(0.1..100) where
// they matter), 1 for the components of a unit direction.
inline bool fiberNear(float got, float want, float tol)
{
    return std::abs(got - want) <= tol * std::max(std::abs(want), 1e-2f);
}

inline bool directionNear(float got, float want, float tol)
{
    return std::abs(got - want) <= tol;
}

inline void expectFiberNear(const gpu::FiberProbeResult& got, glm::vec3 f, float pdf, glm::vec3 wi, float samplePdf,
                            glm::vec3 sampleFsum, float tol, const FiberCase& c)
{
    auto where = [&] {
        return ::testing::Message() << "h " << c.h << " eta " << c.eta << " beta_m " << c.betaM << " beta_n " << c.betaN
                                    << " alpha " << c.alphaDeg << " sigma_a " << c.sigmaA.x << "," << c.sigmaA.y << ","
                                    << c.sigmaA.z << " wo " << c.wo.x << "," << c.wo.y << "," << c.wo.z << " wi "
                                    << c.wi.x << "," << c.wi.y << "," << c.wi.z << " u " << c.u.x << "," << c.u.y << ","
                                    << c.u.z << "," << c.u.w;
    };
    for (int k = 0; k < 3; ++k) {
        EXPECT_PRED3(fiberNear, got.f[k], f[k], tol) << "f[" << k << "] " << where();
        EXPECT_PRED3(directionNear, got.sampleWi[k], wi[k], tol) << "sampled wi[" << k << "] " << where();
        EXPECT_PRED3(fiberNear, got.sampleFsum[k], sampleFsum[k], tol) << "sampled fsum[" << k << "] " << where();
    }
    EXPECT_PRED3(fiberNear, got.pdf, pdf, tol) << "pdf " << where();
    EXPECT_PRED3(fiberNear, got.samplePdf, samplePdf, tol) << "sampled pdf " << where();
}

} // namespace wisp::test
