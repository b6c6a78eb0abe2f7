// tests/test_fiber_bsdf.cpp: the path tracer's fibre BSDF (shaders/shared/fiber_bsdf.h, compiled as
// C++) against the CPU ground truth (shading/hair_bsdf.cpp) on random parameters and directions
// (eval, pdf and sampling to 1e-5), and on its own: the white furnace through its sampling, a
// chi-square test of the sampled directions against its pdf (pbrt's style), and the sampled
// weight agreeing with eval / pdf.
#include "fiber_bsdf_cases.h"
#include "shaders/shared/fiber_bsdf.h"
#include "shading/hair_bsdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

using namespace wisp;

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

gpu::FiberBsdf whiteFiber(float beta, float h)
{
    return gpu::makeFiberBsdf(gpu::makeFiberMaterial(glm::vec3(0.0f), 1.55f, beta, beta, 2.0f * kPi / 180.0f), h);
}

glm::vec3 uniformSphere(float u0, float u1)
{
    float x = 1.0f - 2.0f * u0;
    float r = std::sqrt(std::max(0.0f, 1.0f - x * x));
    float phi = 2.0f * kPi * u1;
    return {x, r * std::cos(phi), r * std::sin(phi)};
}

} // namespace

// The header and the CPU reference are one model: every value agrees to 1e-5 (relative, with a
// floor of 1e-5 of the pdf's scale for values near 0) on random fibres and directions.
TEST(FiberBsdf, MatchesTheCpuReferenceOnRandomInputs)
{
    std::vector<test::FiberCase> cases = test::randomFiberCases(2000, 11);
    for (const test::FiberCase& c : cases) {
        shading::HairBsdf ref(test::hairParams(c));
        gpu::FiberBsdf b = gpu::makeFiberBsdf(test::fiberMaterial(c), c.h);
        gpu::FiberProbeResult got = test::evaluateFiberCase(b, c);

        glm::vec3 f = ref.f(c.wo, c.wi);
        float pdf = ref.pdf(c.wo, c.wi);
        glm::vec3 wi;
        float samplePdf = 0.0f;
        glm::vec3 sampleF = ref.sampleF(c.wo, {c.u.x, c.u.y, c.u.z, c.u.w}, &wi, &samplePdf);
        float cosWi = std::abs(wi.z);
        glm::vec3 sampleFsum = cosWi > 0.0f ? sampleF * cosWi : sampleF;
        test::expectFiberNear(got, f, pdf, wi, samplePdf, sampleFsum, 1e-5f, c);
    }
}

// Without absorption the fibre keeps every bit of energy: sampled fsum / pdf averages to 1 within
// 1% for any wo, h uniform across the fibre (pbrt-v3's WhiteFurnaceSampled).
TEST(FiberBsdf, WhiteFurnaceThroughSampling)
{
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (float beta : {0.1f, 0.3f, 0.7f}) {
        double sum = 0.0;
        constexpr int kSamples = 100000;
        for (int i = 0; i < kSamples; ++i) {
            gpu::FiberBsdf b = whiteFiber(beta, -1.0f + 2.0f * u(rng));
            glm::vec3 wo = uniformSphere(u(rng), u(rng));
            gpu::FiberSample s = gpu::fiberSample(b, wo, glm::vec4(u(rng), u(rng), u(rng), u(rng)));
            if (s.pdf > 0.0f)
                sum += double(s.fsum.y / s.pdf);
        }
        EXPECT_NEAR(sum / kSamples, 1.0, 0.01) << "beta " << beta;
    }
}

// The sampled directions follow the pdf: a histogram over equal-area cells of the sphere (uniform
// in sin(theta) = wi.x and in phi) against the pdf integrated over each cell, cells with fewer than
// 5 expected merged into one, Pearson's chi-square and the Wilson-Hilferty normal approximation of
// its distribution; rejected at z > 4 (p about 3e-5). pbrt-v3's chi2 tests of its distributions.
TEST(FiberBsdf, SampledDirectionsFollowThePdf)
{
    constexpr int kThetaBins = 16, kPhiBins = 32, kSub = 8;
    constexpr int kSamples = 200000;
    const glm::vec3 outgoing[] = {glm::normalize(glm::vec3(0.3f, 0.5f, 0.8f)),
                                  glm::normalize(glm::vec3(-0.7f, 0.1f, -0.5f))};
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (float beta : {0.25f, 0.6f}) {
        for (float h : {-0.5f, 0.3f}) {
            gpu::FiberBsdf b = gpu::makeFiberBsdf(
                gpu::makeFiberMaterial(glm::vec3(0.25f, 0.5f, 1.0f), 1.55f, beta, beta, 2.0f * kPi / 180.0f), h);
            for (glm::vec3 wo : outgoing) {
                std::vector<double> observed(kThetaBins * kPhiBins, 0.0), expected(kThetaBins * kPhiBins, 0.0);
                for (int i = 0; i < kSamples; ++i) {
                    gpu::FiberSample s = gpu::fiberSample(b, wo, glm::vec4(u(rng), u(rng), u(rng), u(rng)));
                    float x = std::clamp(s.wi.x, -1.0f, 0.999999f);
                    float phi = std::atan2(s.wi.z, s.wi.y);
                    if (phi < 0.0f)
                        phi += 2.0f * kPi;
                    int ti = std::min(int((x + 1.0f) * 0.5f * kThetaBins), kThetaBins - 1);
                    int pi = std::min(int(phi / (2.0f * kPi) * kPhiBins), kPhiBins - 1);
                    observed[size_t(ti * kPhiBins + pi)] += 1.0;
                }
                // The pdf over each cell (area 4 pi / cells), midpoint rule on kSub x kSub sub-cells.
                double cellArea = 4.0 * std::numbers::pi / (kThetaBins * kPhiBins);
                for (int ti = 0; ti < kThetaBins; ++ti)
                    for (int pi = 0; pi < kPhiBins; ++pi) {
                        double sum = 0.0;
                        for (int a = 0; a < kSub; ++a)
                            for (int c = 0; c < kSub; ++c) {
                                float x = -1.0f + 2.0f * (float(ti) + (float(a) + 0.5f) / kSub) / kThetaBins;
                                float phi = 2.0f * kPi * (float(pi) + (float(c) + 0.5f) / kSub) / kPhiBins;
                                float r = std::sqrt(std::max(0.0f, 1.0f - x * x));
                                sum += double(gpu::fiberPdf(b, wo, {x, r * std::cos(phi), r * std::sin(phi)}));
                            }
                        expected[size_t(ti * kPhiBins + pi)] = sum / (kSub * kSub) * cellArea * kSamples;
                    }
                double chi2 = 0.0, poolObserved = 0.0, poolExpected = 0.0;
                int dof = -1;
                for (size_t k = 0; k < observed.size(); ++k) {
                    if (expected[k] < 5.0) {
                        poolObserved += observed[k];
                        poolExpected += expected[k];
                        continue;
                    }
                    chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
                    ++dof;
                }
                if (poolExpected > 0.0) {
                    chi2 += (poolObserved - poolExpected) * (poolObserved - poolExpected) / std::max(poolExpected, 5.0);
                    ++dof;
                }
                ASSERT_GT(dof, 20);
                double k = dof, m = 1.0 - 2.0 / (9.0 * k), sd = std::sqrt(2.0 / (9.0 * k));
                double z = (std::cbrt(chi2 / k) - m) / sd;
                EXPECT_LT(z, 4.0) << "beta " << beta << " h " << h << " wo " << wo.x << "," << wo.y << "," << wo.z
                                  << ": chi2 " << chi2 << " with " << dof << " degrees of freedom";
            }
        }
    }
}

// pdf and eval agree with what sampling returns: the sample's pdf and fsum are the pdf and fsum at
// its direction, and the integral of fsum over the sphere is the same estimated uniformly and by
// importance sampling (pbrt-v3's SamplingConsistency).
TEST(FiberBsdf, PdfAndEvalAgreeWithSampling)
{
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (float beta : {0.2f, 0.5f}) {
        gpu::FiberBsdf b = gpu::makeFiberBsdf(
            gpu::makeFiberMaterial(glm::vec3(0.4f, 0.8f, 1.6f), 1.55f, beta, beta, 2.0f * kPi / 180.0f), 0.4f);
        glm::vec3 wo = glm::normalize(glm::vec3(0.2f, -0.6f, 0.7f));
        glm::dvec3 uniform(0.0), sampled(0.0);
        constexpr int kSamples = 200000;
        for (int i = 0; i < kSamples; ++i) {
            glm::vec3 wi = uniformSphere(u(rng), u(rng));
            uniform += glm::dvec3(gpu::fiberFsum(b, wo, wi)) * (4.0 * std::numbers::pi);
            gpu::FiberSample s = gpu::fiberSample(b, wo, glm::vec4(u(rng), u(rng), u(rng), u(rng)));
            ASSERT_GT(s.pdf, 0.0f);
            EXPECT_NEAR(s.pdf, gpu::fiberPdf(b, wo, s.wi), 1e-4f * s.pdf);
            glm::vec3 fsum = gpu::fiberFsum(b, wo, s.wi);
            EXPECT_NEAR(s.fsum.x, fsum.x, 1e-4f * fsum.x + 1e-7f);
            sampled += glm::dvec3(s.fsum / s.pdf);
        }
        uniform /= double(kSamples);
        sampled /= double(kSamples);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(sampled[c], uniform[c], 0.02 * uniform[c]) << "beta " << beta << " channel " << c;
    }
}

// The local frame at a hit: x the tangent, z toward the ray's origin across the fibre, right-handed;
// the view direction has phi_o = pi / 2 (the offset h is then the hit's y in radii, Chiang's gamma_o).
TEST(FiberBsdf, FrameAtAHitFacesTheRay)
{
    glm::vec3 t = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
    glm::vec3 d = glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f));
    gpu::FiberFrame f = gpu::makeFiberFrame(t, d);
    EXPECT_NEAR(glm::dot(f.x, f.y), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f.x, f.z), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(glm::cross(f.x, f.y) - f.z), 0.0f, 1e-6f);
    glm::vec3 wo = gpu::fiberToLocal(f, -d);
    EXPECT_NEAR(wo.y, 0.0f, 1e-6f);
    EXPECT_GT(wo.z, 0.0f);
    glm::vec3 back = gpu::fiberToWorld(f, wo);
    EXPECT_NEAR(glm::length(back + d), 0.0f, 1e-6f);
    // A ray along the fibre still gets a frame.
    gpu::FiberFrame along = gpu::makeFiberFrame(t, -t);
    EXPECT_NEAR(glm::length(along.z), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(along.z, t), 0.0f, 1e-6f);
}
