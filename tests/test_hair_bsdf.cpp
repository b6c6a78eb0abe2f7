// tests/test_hair_bsdf.cpp: the reference hair BSDF (shading/hair_bsdf.h): energy conservation (white
// furnace, uniform and importance-sampled), sampling consistent with the pdf, the pdf normalised,
// the symmetries that hold, hand-computed values of its pieces and of the melanin and colour
// mappings, and bad parameters.
#include "core/error.h"
#include "shading/hair_bsdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

using namespace wisp::shading;

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

HairParams whiteHair(float beta, float h)
{
    HairParams p;
    p.sigmaA = glm::vec3(0.0f);
    p.betaM = beta;
    p.betaN = beta;
    p.h = h;
    return p;
}

// The integral over the sphere of g(w), stratified in (cos, phi): n x n cells, one jittered sample each.
double integrateSphere(int n, std::mt19937& rng, const std::function<double(glm::vec3)>& g)
{
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            float x = 1.0f - 2.0f * (float(i) + u(rng)) / float(n);
            float phi = 2.0f * kPi * (float(j) + u(rng)) / float(n);
            float r = std::sqrt(std::max(0.0f, 1.0f - x * x));
            sum += g(glm::vec3(x, r * std::cos(phi), r * std::sin(phi)));
        }
    }
    return sum * 4.0 * std::numbers::pi / double(n * n);
}

const glm::vec3 kOutgoing[] = {glm::normalize(glm::vec3(0.3f, 0.5f, 0.8f)), glm::vec3(0.0f, 1.0f, 0.0f),
                               glm::normalize(glm::vec3(-0.8f, 0.1f, -0.5f))};

} // namespace

// Without absorption every bit of light leaves again: the integral of f |cos| = fsum over the
// sphere of wi is 1 for any wo (pbrt-v3's WhiteFurnace test, here stratified).
TEST(Bsdf, WhiteFurnaceUniform)
{
    std::mt19937 rng(7);
    for (float beta : {0.2f, 0.5f, 0.9f}) {
        for (float h : {-0.6f, 0.25f}) {
            HairBsdf bsdf(whiteHair(beta, h));
            for (glm::vec3 wo : kOutgoing) {
                double e =
                    integrateSphere(96, rng, [&](glm::vec3 wi) { return double(bsdf.f(wo, wi).y * std::abs(wi.z)); });
                EXPECT_GE(e, 0.95) << "beta " << beta << " h " << h;
                EXPECT_LE(e, 1.05) << "beta " << beta << " h " << h;
            }
        }
    }
}

// The sampled version: without absorption the sampling reproduces f |cos| exactly, so every
// sample's weight f |wi.z| / pdf is 1 (within 0.1%) and so is their mean (pbrt-v3's
// WhiteFurnaceSampled and SamplingWeights).
TEST(Bsdf, WhiteFurnaceSampled)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (float beta : {0.1f, 0.3f, 0.7f, 1.0f}) {
        for (float h : {-0.9f, 0.0f, 0.4f}) {
            HairBsdf bsdf(whiteHair(beta, h));
            for (glm::vec3 wo : kOutgoing) {
                double sum = 0.0;
                const int n = 2000;
                for (int k = 0; k < n; ++k) {
                    glm::vec3 wi;
                    float pdf = 0.0f;
                    glm::vec3 f = bsdf.sampleF(wo, {u(rng), u(rng), u(rng), u(rng)}, &wi, &pdf);
                    ASSERT_GT(pdf, 0.0f);
                    double w = double(f.y * std::abs(wi.z) / pdf);
                    EXPECT_NEAR(w, 1.0, 1e-3) << "beta " << beta << " h " << h;
                    sum += w;
                }
                EXPECT_NEAR(sum / n, 1.0, 0.01);
            }
        }
    }
}

// With absorption the sampled estimate of the albedo matches the uniform one.
TEST(Bsdf, SampledAndUniformAlbedoAgreeWithAbsorption)
{
    HairParams p; // brown: melanin 1.3
    p.h = 0.3f;
    HairBsdf bsdf(p);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    glm::vec3 wo = kOutgoing[0];
    double uniform = integrateSphere(128, rng, [&](glm::vec3 wi) { return double(bsdf.fsum(wo, wi).y); });
    double sampled = 0.0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
        glm::vec3 wi;
        float pdf = 0.0f;
        glm::vec3 f = bsdf.sampleF(wo, {u(rng), u(rng), u(rng), u(rng)}, &wi, &pdf);
        sampled += double(f.y * std::abs(wi.z) / pdf);
    }
    sampled /= n;
    EXPECT_LT(uniform, 0.5); // brown hair absorbs most of it
    EXPECT_NEAR(sampled, uniform, 0.02 * uniform);
}

TEST(Bsdf, PdfIntegratesToOne)
{
    std::mt19937 rng(5);
    for (float beta : {0.3f, 0.6f}) {
        HairParams p;
        p.betaM = beta;
        p.betaN = beta;
        p.h = -0.3f;
        HairBsdf bsdf(p);
        for (glm::vec3 wo : kOutgoing) {
            double total = integrateSphere(96, rng, [&](glm::vec3 wi) { return double(bsdf.pdf(wo, wi)); });
            EXPECT_NEAR(total, 1.0, 0.02) << "beta " << beta;
        }
    }
}

// The pdf sampleF reports is the pdf of the direction it returns.
TEST(Bsdf, SampledPdfMatchesPdf)
{
    HairParams p;
    p.h = 0.5f;
    HairBsdf bsdf(p);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int k = 0; k < 500; ++k) {
        glm::vec3 wo = kOutgoing[size_t(k) % 3], wi;
        float pdf = 0.0f;
        bsdf.sampleF(wo, {u(rng), u(rng), u(rng), u(rng)}, &wi, &pdf);
        EXPECT_NEAR(glm::length(wi), 1.0f, 1e-4f);
        EXPECT_NEAR(bsdf.pdf(wo, wi), pdf, 1e-3f * pdf + 1e-6f);
    }
}

// f is fsum / |wi.z| (pbrt's convention), fsum >= 0 and finite everywhere, including along the fibre.
TEST(Bsdf, FIsFsumOverCosineAndFinite)
{
    HairBsdf bsdf(HairParams{});
    glm::vec3 wo = kOutgoing[0], wi = glm::normalize(glm::vec3(-0.2f, 0.4f, 0.9f));
    glm::vec3 f = bsdf.f(wo, wi), s = bsdf.fsum(wo, wi);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(f[c] * std::abs(wi.z), s[c], 1e-6f * s[c]);
    for (glm::vec3 a : {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1), wo})
        for (glm::vec3 b : {glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0.6f, 0.8f, 0.0f), -wo}) {
            glm::vec3 v = bsdf.fsum(a, b);
            for (int c = 0; c < 3; ++c) {
                EXPECT_TRUE(std::isfinite(v[c]));
                EXPECT_GE(v[c], 0.0f);
            }
        }
}

// Where the model is symmetric: without the cuticle tilt M_p is symmetric in theta_i and theta_o;
// at h = 0 (no azimuthal skew) and |sin theta_i| = |sin theta_o| (equal A_p, T and gamma_t) the
// whole lobe sum is reciprocal, fsum(wo, wi) = fsum(wi, wo); and averaged across the fibre the
// BSDF is even in phi. (pbrt's f itself is not reciprocal: it divides by |wi.z|.)
TEST(Bsdf, SymmetriesThatHold)
{
    HairParams p;
    p.alphaDeg = 0.0f;
    HairLobes lobes(p);
    for (float a : {-0.7f, 0.1f, 0.5f})
        for (float b : {-0.3f, 0.2f, 0.9f}) {
            auto m1 = lobes.longitudinal(a, b), m2 = lobes.longitudinal(b, a);
            for (size_t k = 0; k <= kPMax; ++k)
                EXPECT_NEAR(m1[k], m2[k], 1e-5f * m1[k] + 1e-7f);
        }
    HairBsdf bsdf(p);
    for (float theta : {0.0f, 0.4f, -1.0f})
        for (float phi : {0.3f, 1.5f, 2.9f}) {
            glm::vec3 wo(std::sin(theta), std::cos(theta), 0.0f);
            glm::vec3 wi(-std::sin(theta), std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi));
            glm::vec3 x = bsdf.fsum(wo, wi), y = bsdf.fsum(wi, wo);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(x[c], y[c], 1e-4f * x[c] + 1e-8f);
        }
    HairParams tilted; // alpha 2 degrees, h averaged
    glm::vec3 wo = kOutgoing[0];
    for (float phi : {0.4f, 1.7f, 3.0f}) {
        float phiO = std::atan2(wo.z, wo.y), c = std::sqrt(1.0f - 0.09f);
        glm::vec3 plus(0.3f, c * std::cos(phiO + phi), c * std::sin(phiO + phi));
        glm::vec3 minus(0.3f, c * std::cos(phiO - phi), c * std::sin(phiO - phi));
        glm::vec3 x = fiberAveragedFsum(tilted, wo, plus), y = fiberAveragedFsum(tilted, wo, minus);
        EXPECT_NEAR(x.x, y.x, 1e-4f * x.x);
    }
}

TEST(Bsdf, PiecesMatchHandComputedValues)
{
    // I0(1) and I0(5) (Abramowitz & Stegun table 9.8), and log I0 across the switch at 12.
    EXPECT_NEAR(besselI0(1.0), 1.2660658778, 1e-9);
    EXPECT_NEAR(besselI0(5.0), 27.239871823, 1e-7);
    EXPECT_NEAR(logBesselI0(11.99), std::log(besselI0(11.99)), 1e-9);
    EXPECT_NEAR(logBesselI0(12.01), std::log(besselI0(12.01)), 2e-3);
    // Fresnel: ((1 - 1.5) / (1 + 1.5))^2 = 0.04 at normal incidence, 1 at grazing.
    EXPECT_NEAR(fresnelDielectric(1.0f, 1.5f), 0.04f, 1e-6f);
    EXPECT_NEAR(fresnelDielectric(0.0f, 1.55f), 1.0f, 1e-6f);
    // A_p of a clear fibre sum to 1 (the residual is the rest of the geometric series).
    Attenuations a = attenuation(0.8f, 1.55f, 0.3f, glm::vec3(1.0f));
    EXPECT_NEAR(a[0].x + a[1].x + a[2].x + a[3].x, 1.0f, 1e-5f);
    EXPECT_NEAR(a[1].x, (1.0f - a[0].x) * (1.0f - a[0].x), 1e-6f);
    // The longitudinal variance and the logistic scale (pbrt's fits) at beta = 0.3.
    float sd = 0.726f * 0.3f + 0.812f * 0.09f + 3.7f * std::pow(0.3f, 20.0f);
    EXPECT_NEAR(longitudinalVariance(0.3f), sd * sd, 1e-7f);
    EXPECT_NEAR(logisticScale(0.3f), 0.626657069f * (0.265f * 0.3f + 1.194f * 0.09f), 1e-6f);
}

// M_p integrates to 1 over theta_i with weight cos(theta_i), N_p to 1 over phi, for wide and
// narrow lobes (the log form below v = 0.1 included).
TEST(Bsdf, LobesAreNormalised)
{
    for (float v : {0.005f, 0.05f, 0.3f, 2.0f}) {
        for (float thetaO : {0.0f, 0.7f, -1.3f}) {
            double sum = 0.0;
            const int n = 20000;
            for (int k = 0; k < n; ++k) {
                double t = -0.5 * std::numbers::pi + (k + 0.5) * std::numbers::pi / n;
                sum += longitudinalScattering(float(std::cos(t)), std::cos(thetaO), float(std::sin(t)),
                                              std::sin(thetaO), v) *
                       std::cos(t);
            }
            EXPECT_NEAR(sum * std::numbers::pi / n, 1.0, 2e-3) << "v " << v << " theta_o " << thetaO;
        }
    }
    for (float s : {0.02f, 0.2f, 1.5f})
        for (int p = 0; p < kPMax; ++p) {
            double sum = 0.0;
            const int n = 20000;
            for (int k = 0; k < n; ++k)
                sum += azimuthalScattering(-kPi + (float(k) + 0.5f) * 2.0f * kPi / float(n), p, s, 0.4f, 0.2f);
            EXPECT_NEAR(sum * 2.0 * std::numbers::pi / n, 1.0, 1e-3) << "s " << s;
        }
}

TEST(Bsdf, MelaninMapsToChiangsAbsorption)
{
    glm::vec3 brown = sigmaAFromMelanin(1.3f, 0.0f);
    EXPECT_NEAR(brown.x, 1.3f * 0.419f, 1e-6f);
    EXPECT_NEAR(brown.y, 1.3f * 0.697f, 1e-6f);
    EXPECT_NEAR(brown.z, 1.3f * 1.37f, 1e-6f);
    glm::vec3 red = sigmaAFromMelanin(0.0f, 1.0f);
    EXPECT_EQ(red, glm::vec3(0.187f, 0.4f, 1.05f));
    glm::vec3 mix = sigmaAFromMelanin(2.0f, 0.5f);
    EXPECT_NEAR(mix.z, 2.0f * 1.37f + 0.5f * 1.05f, 1e-5f);
    EXPECT_EQ(HairParams{}.sigmaA, brown); // the default is pbrt's brown
}

TEST(Bsdf, ColorMapsToAbsorptionAndBack)
{
    // Chiang 2016 eq. 9 by hand at beta_n = 0.3: the polynomial is 5.8878.
    double d = 5.969 - 0.215 * 0.3 + 2.532 * 0.09 - 10.73 * 0.027 + 5.574 * 0.0081 + 0.245 * 0.00243;
    glm::vec3 s = sigmaAFromColor(glm::vec3(0.5f, 0.25f, 0.1f), 0.3f);
    EXPECT_NEAR(s.x, std::pow(std::log(0.5) / d, 2.0), 1e-6);
    EXPECT_NEAR(s.z, std::pow(std::log(0.1) / d, 2.0), 1e-6);
    glm::vec3 c = colorFromSigmaA(s, 0.3f);
    EXPECT_NEAR(c.x, 0.5f, 1e-5f);
    EXPECT_NEAR(c.y, 0.25f, 1e-5f);
    EXPECT_NEAR(c.z, 0.1f, 1e-5f);
    // Darker colours need more absorption.
    EXPECT_GT(s.z, s.y);
    EXPECT_GT(s.y, s.x);
}

TEST(Bsdf, BadParametersThrowNamingTheParameterAndRange)
{
    auto expectThrow = [](HairParams p, const std::string& name, const std::string& range) {
        try {
            HairBsdf bsdf(p);
            ADD_FAILURE() << "no error for " << name;
        } catch (const wisp::UserError& e) {
            std::string m = e.what();
            EXPECT_NE(m.find(name), std::string::npos) << m;
            EXPECT_NE(m.find(range), std::string::npos) << m;
        }
    };
    HairParams p;
    p.h = 1.5f;
    expectThrow(p, "h =", "[-1, 1]");
    p = {};
    p.eta = 0.5f;
    expectThrow(p, "eta", "[1, 4]");
    p = {};
    p.betaM = 0.0f;
    expectThrow(p, "beta_m", "[0.01, 1]");
    p = {};
    p.betaN = std::nanf("");
    expectThrow(p, "beta_n", "[0.01, 1]");
    p = {};
    p.alphaDeg = 45.0f;
    expectThrow(p, "alpha", "[-10, 10]");
    p = {};
    p.sigmaA = glm::vec3(0.1f, -1.0f, 0.1f);
    expectThrow(p, "sigma_a", "[0, 1000]");
    EXPECT_THROW(sigmaAFromColor(glm::vec3(0.0f, 0.5f, 0.5f), 0.3f), wisp::UserError);
    EXPECT_THROW(FiberAverage(p, 0.0f), wisp::UserError);
}
