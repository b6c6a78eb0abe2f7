// tests/test_bsdf_cli.cpp: `wisp bsdf` as a user runs it (the real binary, as a subprocess): the
// reference f and a model's value for a direction pair agree with the library, --compare lists
// every model, and each bad value ends with one line naming the option and exit status 2.
#include "shading/hair_models.h"

#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

using wisp::test::runWisp;

namespace {

glm::vec3 parseThree(const std::string& line)
{
    std::istringstream in(line);
    glm::vec3 v(NAN);
    in >> v.x >> v.y >> v.z;
    return v;
}

void expectUserError(const wisp::test::RunResult& r, const std::string& mention)
{
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
}

void expectNear(glm::vec3 a, glm::vec3 b)
{
    for (int c = 0; c < 3; ++c) {
        EXPECT_TRUE(std::isfinite(a[c]));
        EXPECT_NEAR(a[c], b[c], 1e-6f * std::abs(b[c]) + 1e-12f) << "channel " << c;
    }
}

} // namespace

TEST(BsdfCli, PrintsTheReferenceF)
{
    auto r = runWisp("bsdf --wo 0.3,0.8,0.5 --wi -0.2,0.4,0.9 --h 0.25 --beta-m 0.4 --melanin 2,0.5");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    wisp::shading::HairParams p;
    p.h = 0.25f;
    p.betaM = 0.4f;
    p.sigmaA = wisp::shading::sigmaAFromMelanin(2.0f, 0.5f);
    glm::vec3 f = wisp::shading::HairBsdf(p).f(glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f)),
                                               glm::normalize(glm::vec3(-0.2f, 0.4f, 0.9f)));
    expectNear(parseThree(r.out), f);
}

TEST(BsdfCli, ModelPrintsSOverCosine)
{
    glm::vec3 wo = glm::normalize(glm::vec3(0.1f, -0.6f, 0.7f)), wi = glm::normalize(glm::vec3(0.2f, 0.5f, -0.8f));
    wisp::shading::HairParams p = wisp::shading::typicalHair();
    p.sigmaA = glm::vec3(0.2f, 0.3f, 0.6f);
    gpu::HairMaterial m = wisp::shading::packHairMaterial(p);
    wisp::shading::HairLut lut = wisp::shading::buildHairLut(p);
    for (wisp::shading::HairModel model : wisp::shading::kHairModels) {
        auto r = runWisp(std::string("bsdf --wo 0.1,-0.6,0.7 --wi 0.2,0.5,-0.8 --sigma-a 0.2,0.3,0.6 --model ") +
                         wisp::shading::modelName(model));
        ASSERT_EQ(r.status, 0) << r.err;
        glm::vec3 s = wisp::shading::evaluateModel(model, m, lut, wo, wi) / std::abs(wi.z);
        expectNear(parseThree(r.out), s);
    }
}

TEST(BsdfCli, CompareListsEveryModel)
{
    auto r = runWisp("bsdf --compare");
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* name : {"karis", "kajiya", "lut", "relative RMS"})
        EXPECT_NE(r.out.find(name), std::string::npos) << name;
    auto j = runWisp("bsdf --compare --json");
    ASSERT_EQ(j.status, 0) << j.err;
    nlohmann::json out = nlohmann::json::parse(j.out);
    ASSERT_EQ(out["models"].size(), 3u);
    std::vector<wisp::shading::ModelError> errors = wisp::shading::compareModels(wisp::shading::typicalHair());
    for (size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(out["models"][k]["model"], wisp::shading::modelName(errors[k].model));
        EXPECT_NEAR(out["models"][k]["relative_rms"].get<double>(), errors[k].relativeRms, 1e-9);
        EXPECT_TRUE(out["models"][k]["finite_non_negative"].get<bool>());
    }
}

TEST(BadInput, BsdfValuesNameTheOption)
{
    expectUserError(runWisp("bsdf --wo 0,0,0 --wi 1,0,0"), "--wo");
    expectUserError(runWisp("bsdf --wo 1,0,0 --wi 1,2"), "--wi");
    expectUserError(runWisp("bsdf --wo 1,x,0 --wi 1,0,0"), "--wo");
    expectUserError(runWisp("bsdf --wo 1,0,0"), "--wi");
    auto beta = runWisp("bsdf --beta-m 2 --compare");
    expectUserError(beta, "--beta-m");
    EXPECT_NE(beta.err.find("0.01"), std::string::npos) << beta.err;
    expectUserError(runWisp("bsdf --beta-n 0 --compare"), "--beta-n");
    expectUserError(runWisp("bsdf --h 1.5 --wo 1,0,0 --wi 0,1,0"), "--h");
    expectUserError(runWisp("bsdf --h nan --wo 1,0,0 --wi 0,1,0"), "--h");
    expectUserError(runWisp("bsdf --eta 0.5 --compare"), "--eta");
    expectUserError(runWisp("bsdf --alpha 30 --compare"), "--alpha");
    expectUserError(runWisp("bsdf --sigma-a 1,-1,1 --compare"), "--sigma-a");
    expectUserError(runWisp("bsdf --sigma-a 1,1,1 --melanin 2 --compare"), "--melanin");
    expectUserError(runWisp("bsdf --melanin 1,2,3 --compare"), "--melanin");
    expectUserError(runWisp("bsdf --color 0,0.5,0.5 --compare"), "--color");
    expectUserError(runWisp("bsdf --model phong --wo 1,0,0 --wi 0,1,0"), "--model");
    expectUserError(runWisp("bsdf --json"), "--json");
}
