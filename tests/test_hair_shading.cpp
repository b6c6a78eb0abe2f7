// tests/test_hair_shading.cpp: the real-time hair models of shaders/shared/hair_shading.h, compiled
// as C++, measured against the reference BSDF averaged across the fibre (relative RMS over a sphere
// of direction pairs, bounds a little above the measured values so a regression fails); the lookup
// tables and their Vulkan-style sampling; the header compiled as GLSL by glslangValidator.
#include "shading/hair_models.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>

using namespace wisp::shading;

namespace {

// compareModels for the typical (brown) hair, computed once for the suite (about 0.2 s).
const std::vector<ModelError>& typicalErrors()
{
    static const std::vector<ModelError> errors = compareModels(typicalHair());
    return errors;
}

double errorOf(HairModel m)
{
    for (const ModelError& e : typicalErrors())
        if (e.model == m)
            return e.relativeRms;
    return -1.0;
}

const glm::vec3 kT(1.0f, 0.0f, 0.0f);

} // namespace

// Measured (brown hair: eumelanin 1.3, beta_m = beta_n = 0.3, alpha 2 degrees, eta 1.55; 32 x 1024
// pairs; `wisp bsdf --compare`): Karis 0.464, Kajiya-Kay 0.877, lookup 0.0220.
TEST(HairShading, KarisErrorAgainstTheReference)
{
    // Karis's Gaussian M in sin(theta_i) + sin(theta_o) keeps one width at every inclination, where
    // the reference narrows (in sin theta) toward grazing angles, and his TT and TRT azimuthal fits
    // have a fixed width; he has no residual lobe. Brightness: 0.72 of the reference.
    EXPECT_LT(errorOf(HairModel::Karis), 0.50);
    EXPECT_GT(errorOf(HairModel::Karis), 0.0);
}

TEST(HairShading, KajiyaKayErrorAgainstTheReference)
{
    // Kajiya-Kay has no forward-scattering (TT) lobe at all; its albedos are matched to the
    // reference's (brightness 0.97), but the light goes to the wrong places.
    EXPECT_LT(errorOf(HairModel::KajiyaKay), 0.92);
}

// For brown hair. Not for every hair: for black hair (eumelanin 8) almost all is the surface
// reflection R and the two are about as far off (Karis 0.694, Kajiya-Kay 0.726, docs/shading.md).
TEST(HairShading, KarisIsClearlyBetterThanKajiyaKay)
{
    EXPECT_LT(errorOf(HairModel::Karis), 0.6 * errorOf(HairModel::KajiyaKay));
}

TEST(HairShading, LutErrorIsSmall)
{
    // Built from the reference itself: what is left is bilinear interpolation of 64 x 64 tables
    // and the 64-sample average over h (the reference uses 128).
    EXPECT_LT(errorOf(HairModel::Lut), 0.03);
    for (const ModelError& e : typicalErrors()) {
        EXPECT_TRUE(e.finiteNonNegative) << modelName(e.model);
        if (e.model == HairModel::Lut)
            EXPECT_NEAR(e.brightness, 1.0, 0.01);
        else
            EXPECT_GT(e.brightness, 0.5) << modelName(e.model); // same brightness range
    }
}

// Finite and non-negative on the awkward directions too: along the fibre, wi = wo, wi = -wo, and
// for black, white and rough hair.
TEST(HairShading, EveryModelFiniteAndNonNegative)
{
    std::vector<glm::vec3> dirs = fibonacciSphere(64);
    for (glm::vec3 d : {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, -1)})
        dirs.push_back(d);
    for (glm::vec3 sigma : {glm::vec3(0.0f), sigmaAFromMelanin(8.0f), sigmaAFromMelanin(1.3f)}) {
        for (float beta : {0.05f, 1.0f}) {
            HairParams p = typicalHair();
            p.sigmaA = sigma;
            p.betaM = p.betaN = beta;
            gpu::HairMaterial m = packHairMaterial(p);
            HairLut lut = buildHairLut(p, 16, 8);
            for (glm::vec3 wo : dirs)
                for (glm::vec3 wi : {dirs[3], dirs[40], wo, -wo, glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}) {
                    glm::vec3 all[] = {evaluateModel(HairModel::Karis, m, lut, wo, wi),
                                       evaluateModel(HairModel::KajiyaKay, m, lut, wo, wi),
                                       evaluateModel(HairModel::Lut, m, lut, wo, wi),
                                       gpu::hairKarisMultiple(kT, wi, wo, m, 0.5f),
                                       gpu::hairKarisLit(kT, wi, wo, m, 0.2f)};
                    for (glm::vec3 s : all)
                        for (int c = 0; c < 3; ++c) {
                            ASSERT_TRUE(std::isfinite(s[c]));
                            ASSERT_GE(s[c], 0.0f);
                        }
                }
        }
    }
}

// The cuticle tilt moves every model's primary highlight the same way as the reference's: with
// alpha = 8 degrees and TT/TRT absorbed away, R peaks at theta_i + theta_o = 2 alpha.
TEST(HairShading, HighlightShiftMatchesTheReference)
{
    HairParams p = typicalHair();
    p.alphaDeg = 8.0f;
    p.betaM = 0.15f;
    p.sigmaA = glm::vec3(50.0f);
    gpu::HairMaterial m = packHairMaterial(p);
    HairLut lut = buildHairLut(p);
    float thetaO = 0.3f;
    glm::vec3 wo(std::sin(thetaO), std::cos(thetaO), 0.0f);
    float peak[4] = {}, best[4] = {};
    for (float thetaI = -1.2f; thetaI < 0.6f; thetaI += 0.002f) {
        glm::vec3 wi(std::sin(thetaI), std::cos(thetaI), 0.0f); // phi = 0
        float v[4] = {fiberAveragedFsum(p, wo, wi).x, evaluateModel(HairModel::Karis, m, lut, wo, wi).x,
                      evaluateModel(HairModel::KajiyaKay, m, lut, wo, wi).x,
                      evaluateModel(HairModel::Lut, m, lut, wo, wi).x};
        for (int k = 0; k < 4; ++k)
            if (v[k] > best[k]) {
                best[k] = v[k];
                peak[k] = thetaI + thetaO;
            }
    }
    float twoAlpha = 2.0f * 8.0f * std::numbers::pi_v<float> / 180.0f;
    EXPECT_NEAR(peak[0], twoAlpha, 0.01f);
    for (int k = 1; k < 4; ++k)
        EXPECT_NEAR(peak[k], peak[0], 0.02f) << "model " << k;
}

// The Kajiya-Kay lobes' normalisation: a narrow lobe integrates to about 1 over the sphere of wi,
// at any inclination of wo; a broad one somewhat less.
TEST(HairShading, KajiyaLobesAreNormalised)
{
    std::vector<glm::vec3> wis = fibonacciSphere(40000);
    for (float e : {12.0f, 47.0f, 200.0f}) {
        for (float thetaO : {0.0f, 0.5f, 1.0f}) {
            glm::vec3 wo(std::sin(thetaO), std::cos(thetaO), 0.0f);
            double sum = 0.0;
            for (glm::vec3 wi : wis) {
                glm::vec3 h = glm::normalize(wi + wo);
                sum += gpu::hairKajiyaLobe(h.x, std::cos(thetaO), 0.0f, e);
            }
            sum *= 4.0 * std::numbers::pi / double(wis.size());
            if (e < 20.0f) { // broad: 0.81 .. 1.0 measured
                EXPECT_GT(sum, 0.75) << "exponent " << e << " theta_o " << thetaO;
                EXPECT_LT(sum, 1.05) << "exponent " << e << " theta_o " << thetaO;
            } else {
                EXPECT_NEAR(sum, 1.0, 0.05) << "exponent " << e << " theta_o " << thetaO;
            }
        }
    }
}

// Karis's multiple scattering: untinted sqrt(C) when lit, more saturated as the light crosses more
// hair; hairKarisLit vanishes in full shadow.
TEST(HairShading, KarisMultipleScatteringSaturatesWithDepth)
{
    gpu::HairMaterial m = packHairMaterial(typicalHair());
    glm::vec3 wo(0, 1, 0), wi = glm::normalize(glm::vec3(0.2f, 0.6f, 0.7f));
    glm::vec3 lit = gpu::hairKarisMultiple(kT, wi, wo, m, 0.0f);
    glm::vec3 deep = gpu::hairKarisMultiple(kT, wi, wo, m, 1.0f);
    glm::vec3 c = glm::vec3(m.baseColor);
    EXPECT_NEAR(lit.x / lit.y, std::sqrt(c.x / c.y), 1e-4f);
    EXPECT_GT(deep.x / deep.y, 1.5f * lit.x / lit.y);
    EXPECT_EQ(gpu::hairKarisLit(kT, wi, wo, m, 1.0f), glm::vec3(0.0f));
    glm::vec3 combined = gpu::hairKarisLit(kT, wi, wo, m, 0.25f);
    glm::vec3 expected = 0.75f * (gpu::hairKaris(kT, wi, wo, m) + gpu::hairKarisMultiple(kT, wi, wo, m, 0.25f));
    EXPECT_NEAR(combined.x, expected.x, 1e-6f);
}

// hairAngles takes cos(theta_d) from the sines alone (no arcsine, no cosine): the definition's value,
// cos((asin(sin_o) - asin(sin_i)) / 2), over directions spread on the sphere, grazing ones included;
// and beta_m's longitudinal width, its 20th power taken by products, as pow gives it.
TEST(HairShading, AnglesMatchTheirTrigonometricDefinitions)
{
    std::mt19937 rng(7);
    std::normal_distribution<float> normal;
    auto direction = [&] { return glm::normalize(glm::vec3(normal(rng), normal(rng), normal(rng))); };
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
        glm::vec3 t = direction();
        glm::vec3 wi = direction();
        glm::vec3 wo = i % 10 == 0 ? t : direction(); // (along the fibre: theta_o = 90 degrees)
        gpu::HairAngles a = gpu::hairAngles(t, wi, wo);
        double expected = std::cos(0.5 * (std::asin(double(a.sinThetaO)) - std::asin(double(a.sinThetaI))));
        worst = std::max(worst, std::abs(double(a.cosThetaD) - expected));
    }
    EXPECT_LT(worst, 2e-6);
    for (float b : {0.05f, 0.3f, 0.6f, 0.9f, 1.0f}) {
        double expected = 0.726 * b + 0.812 * b * b + 3.7 * std::pow(double(b), 20.0);
        EXPECT_NEAR(gpu::hairLongitudinalWidth(b), expected, 2e-6 * expected) << b;
    }
}

TEST(HairShading, MaterialPacksTheParameters)
{
    HairParams p = typicalHair();
    gpu::HairMaterial m = packHairMaterial(p);
    EXPECT_EQ(glm::vec3(m.sigmaA), p.sigmaA);
    EXPECT_EQ(m.sigmaA.w, 1.55f);
    EXPECT_EQ(m.roughness.x, 0.3f);
    EXPECT_NEAR(m.roughness.z, 2.0f * std::numbers::pi_v<float> / 180.0f, 1e-7f);
    glm::vec3 c = colorFromSigmaA(p.sigmaA, p.betaN);
    EXPECT_EQ(glm::vec3(m.baseColor), c);
    // Brown: red > green > blue, dark.
    EXPECT_GT(c.x, c.y);
    EXPECT_GT(c.y, c.z);
    EXPECT_LT(c.x, 0.1f);
    // The primary lobe's albedo is the reference's R albedo at normal incidence: a few percent.
    EXPECT_GT(m.kajiyaWeights.y, 0.04f);
    EXPECT_LT(m.kajiyaWeights.y, 0.12f);
}

TEST(Lut, LayoutAndContents)
{
    HairParams p = typicalHair();
    HairLut lut = buildHairLut(p);
    ASSERT_EQ(lut.size, gpu::kHairLutSize);
    EXPECT_EQ(lut.texels.size(), size_t(gpu::kHairLutLayers) * lut.size * lut.size * 4);
    // Layer 0, texel (x, y): M_p at sin(theta_i) = 2 (x + 0.5) / size - 1, sin(theta_o) likewise.
    HairLobes lobes(p);
    uint32_t x = 40, y = 17;
    float si = 2.0f * (float(x) + 0.5f) / float(lut.size) - 1.0f,
          so = 2.0f * (float(y) + 0.5f) / float(lut.size) - 1.0f;
    auto mp = lobes.longitudinal(si, so);
    glm::vec4 t = lut.texel(gpu::kHairLutLayerM, x, y);
    EXPECT_NEAR(t.x, mp[0], 1e-6f * mp[0]);
    EXPECT_NEAR(t.w, mp[3], 1e-6f * mp[3]);
    // Layer 2 (N_TT) at phi = pi (x + 0.5) / size, |sin(theta_o)| = (y + 0.5) / size.
    FiberAverage average(p, (float(y) + 0.5f) / float(lut.size), kHairLutHSamples);
    glm::vec3 n = average.azimuthal(1, std::numbers::pi_v<float> * (float(x) + 0.5f) / float(lut.size));
    glm::vec4 tt = lut.texel(gpu::kHairLutLayerNTT, x, y);
    EXPECT_NEAR(tt.y, n.y, 1e-4f * n.y);
    EXPECT_EQ(tt.w, 0.0f);
    // Every texel finite and non-negative.
    for (float v : lut.texels) {
        ASSERT_TRUE(std::isfinite(v));
        ASSERT_GE(v, 0.0f);
    }
}

// sampleHairLut follows Vulkan's linear filter with clamp to edge: a texel's centre returns the
// texel, halfway between two centres their mean, outside the edge centres the edge texel.
TEST(Lut, SamplingFollowsVulkansLinearFilter)
{
    HairLut lut = buildHairLut(typicalHair(), 8, 8);
    const uint32_t layer = gpu::kHairLutLayerNTT;
    auto centre = [](uint32_t i) { return (float(i) + 0.5f) / 8.0f; };
    glm::vec4 a = lut.texel(layer, 3, 5), b = lut.texel(layer, 4, 5), c = lut.texel(layer, 3, 6);
    glm::vec4 s = sampleHairLut(lut, layer, {centre(3), centre(5)});
    EXPECT_NEAR(s.x, a.x, 1e-6f * a.x);
    s = sampleHairLut(lut, layer, {0.5f * (centre(3) + centre(4)), centre(5)});
    EXPECT_NEAR(s.x, 0.5f * (a.x + b.x), 1e-5f * a.x);
    s = sampleHairLut(lut, layer, {centre(3), 0.25f * centre(5) + 0.75f * centre(6)});
    EXPECT_NEAR(s.x, 0.25f * a.x + 0.75f * c.x, 1e-5f * a.x);
    glm::vec4 corner = lut.texel(layer, 0, 7);
    s = sampleHairLut(lut, layer, {0.0f, 1.0f});
    EXPECT_NEAR(s.x, corner.x, 1e-6f * corner.x);
    s = sampleHairLut(lut, layer, {0.01f, 0.99f}); // inside the outer half texel: still the edge
    EXPECT_NEAR(s.x, corner.x, 1e-6f * corner.x);
}

// The header is GLSL too: compile a fragment shader using every function with the same
// glslangValidator and flags the build uses.
TEST(HairShading, HeaderCompilesAsGlsl)
{
    wisp::test::TempDir dir;
    wisp::test::writeFile(dir / "check.frag", R"(#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/hair_shading.h"
layout(set = 0, binding = 0) uniform sampler2DArray hairLut;
layout(set = 0, binding = 1) uniform MaterialBlock { HairMaterial material; };
layout(location = 0) in vec3 inTangent;
layout(location = 1) in vec3 inLight;
layout(location = 2) in vec3 inView;
layout(location = 0) out vec4 outColor;
void main()
{
    vec3 t = normalize(inTangent), wi = normalize(inLight), wo = normalize(inView);
    vec3 s = hairKaris(t, wi, wo, material) + hairKarisMultiple(t, wi, wo, material, 0.3)
           + hairKarisLit(t, wi, wo, material, 0.3) + hairKajiyaKay(t, wi, wo, material)
           + hairShadeLut(hairLut, t, wi, wo);
    outColor = vec4(s, 1.0);
}
)");
    std::string command = std::string("'") + WISP_GLSLANG +
                          "' --target-env vulkan1.3 -I'" WISP_SOURCE_DIR "/shaders' -o '" +
                          (dir / "check.spv").string() + "' '" + (dir / "check.frag").string() + "' >'" +
                          (dir / "log").string() + "' 2>&1";
    int status = std::system(command.c_str());
    EXPECT_EQ(status, 0) << wisp::test::readFile(dir / "log");
    EXPECT_TRUE(std::filesystem::exists(dir / "check.spv"));
}
