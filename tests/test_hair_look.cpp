// tests/test_hair_look.cpp: the hair's look as a person sets it (shading/hair_look.h) on the CPU: the
// presets go from dark to light and auburn is red, and bad look settings are refused naming the
// setting.
#include "app/settings/settings_table.h"
#include "core/error.h"
#include "shaders/shared/strand_shading.h"
#include "shading/hair_look.h"

#include <gtest/gtest.h>

using namespace wisp;

namespace {

float luminance(glm::vec3 c)
{
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

glm::vec3 presetSigmaA(const std::string& name)
{
    HairLook look;
    EXPECT_TRUE(applyHairPreset(look, name));
    return hairParams(look).sigmaA;
}

} // namespace

TEST(HairLook, PresetsGoFromDarkToLightAndAuburnIsRed)
{
    float black = luminance(presetSigmaA("black")), brown = luminance(presetSigmaA("brown"));
    float auburn = luminance(presetSigmaA("auburn")), blonde = luminance(presetSigmaA("blonde"));
    EXPECT_GT(black, brown);
    EXPECT_GT(brown, blonde);
    EXPECT_GT(auburn, blonde);
    glm::vec3 a = presetSigmaA("auburn");
    EXPECT_LT(a.r, 0.5f * a.b) << "auburn absorbs blue far more than red";
    HairLook look;
    EXPECT_FALSE(applyHairPreset(look, "green"));
}

TEST(HairLook, BadLookSettingsAreRefusedNamingTheSetting)
{
    Settings settings;
    const RenderSettings& s = settings.render;
    auto message = [&](const std::string& assignment) {
        try {
            applySetting(settings, assignment);
        } catch (const UserError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_NE(message("shading=phong").find("karis | kajiya | lut"), std::string::npos);
    EXPECT_NE(message("hair_preset=green").find("black | brown | auburn | blonde"), std::string::npos);
    EXPECT_NE(message("hair_color=0.5,0.2").find("hair_color"), std::string::npos);
    EXPECT_NE(message("hair_color=0.5,0.2,2").find("out of range"), std::string::npos);
    EXPECT_NE(message("beta_m=0").find("beta_m"), std::string::npos);
    EXPECT_EQ(message("hair_color=0.5,0.3,0.1"), "accepted");
    EXPECT_TRUE(s.hair.useColor);
    EXPECT_EQ(s.hair.color, glm::vec3(0.5f, 0.3f, 0.1f));
    EXPECT_EQ(message("hair_preset=blonde"), "accepted");
    EXPECT_FALSE(s.hair.useColor);
}

// absorption_along: at 1 a strand's absorption falls from 1.25 times at the root to 0.75 at the tip
// (the drawn hair's lighter tips), at 0 it is the same all along; the per-strand factor and the
// streaks ride on top either way. Every renderer takes it from this one function.
TEST(HairLook, AbsorptionAlongAStrandCanBeTurnedOff)
{
    gpu::FrameParams frame{};
    frame.hairVariation = 0.3f;
    frame.hairStreaks = 0.0f;
    for (uint32_t strand : {0u, 7u, 1234u}) {
        frame.hairAlong.x = 1.0f;
        float root = gpu::strandAbsorptionScale(frame, strand, 0.0f);
        float tip = gpu::strandAbsorptionScale(frame, strand, 1.0f);
        EXPECT_NEAR(root / tip, 1.25f / 0.75f, 1e-5f) << strand;
        frame.hairAlong.x = 0.0f;
        float flat = gpu::strandAbsorptionScale(frame, strand, 0.0f);
        EXPECT_EQ(gpu::strandAbsorptionScale(frame, strand, 0.5f), flat) << strand;
        EXPECT_EQ(gpu::strandAbsorptionScale(frame, strand, 1.0f), flat) << strand;
        EXPECT_NEAR(flat, root / 1.25f, 1e-6f) << strand; // the per-strand factor alone
    }
    EXPECT_EQ(HairLook{}.along, 1.0f);
}
