// tests/test_render.cpp: the head rendered offscreen on the real device with validation on:
// deterministic, covering a plausible part of the frame, brighter on the light's side, and the
// same through the single-sample path.
#include "app/headless.h"
#include "assets/head.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace wisp;

namespace {

constexpr uint32_t kWidth = 320;
constexpr uint32_t kHeight = 240;

RenderSettings smallSettings()
{
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    return s;
}

struct Coverage {
    double fraction = 0.0;        // of all pixels, differing from the background
    double leftLuminance = 0.0;   // mean over covered pixels in the left half
    double rightLuminance = 0.0;  // ... and in the right half
};

Coverage measure(const Picture& p)
{
    const uint8_t* bg = &p.rgba[0];  // the top-left corner is background in every framing here
    Coverage c;
    size_t covered = 0, left = 0, right = 0;
    for (uint32_t y = 0; y < p.height; ++y)
        for (uint32_t x = 0; x < p.width; ++x) {
            const uint8_t* px = &p.rgba[4 * (size_t(y) * p.width + x)];
            if (std::abs(px[0] - bg[0]) + std::abs(px[1] - bg[1]) + std::abs(px[2] - bg[2]) < 6)
                continue;
            ++covered;
            double lum = 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2];
            if (x < p.width / 2) {
                c.leftLuminance += lum;
                ++left;
            } else {
                c.rightLuminance += lum;
                ++right;
            }
        }
    c.fraction = double(covered) / double(p.width * p.height);
    c.leftLuminance /= double(std::max<size_t>(left, 1));
    c.rightLuminance /= double(std::max<size_t>(right, 1));
    return c;
}

class HeadRender : public testing::Test {
protected:
    static void SetUpTestSuite() { head_ = new Head(loadHead(defaultHeadPath())); }
    static void TearDownTestSuite() { delete head_; }
    static Head* head_;
};
Head* HeadRender::head_ = nullptr;

}  // namespace

TEST_F(HeadRender, TwoRendersAreByteIdentical)
{
    vk::Context ctx(test::validatedOptions());
    Picture a = renderPicture(ctx, *head_, smallSettings());
    Picture b = renderPicture(ctx, *head_, smallSettings());
    ASSERT_EQ(a.rgba.size(), size_t(kWidth) * kHeight * 4);
    EXPECT_TRUE(a.rgba == b.rgba);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST_F(HeadRender, WithSimulatedHairTwoRendersAreByteIdentical)
{
    // The fixed-point hair grid makes the whole simulated picture reproducible.
    GrowthSettings growth;
    growth.guides = 300;
    HairScene scene = buildGrownScene(defaultHeadPath(), growth);
    SimSettings sim;
    sim.wind = glm::vec3(3.0f, 0.0f, 0.0f);
    SceneTimeline held = stillTimeline(glm::vec4(0.0f, 0.1f, -0.12f, 0.05f), sim.wind, smallSettings().light);
    vk::Context ctx(test::validatedOptions());
    HairSession first(ctx, scene, sim, held), second(ctx, scene, sim, held);
    Picture a = renderPicture(ctx, first, smallSettings(), 12, 30.0f);
    Picture b = renderPicture(ctx, second, smallSettings(), 12, 30.0f);
    EXPECT_TRUE(a.rgba == b.rgba);
    Picture still = renderPicture(ctx, scene.head, smallSettings());
    EXPECT_FALSE(a.rgba == still.rgba);  // the hair is in the picture
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST_F(HeadRender, CoversAPlausiblePartOfTheFrame)
{
    vk::Context ctx(test::validatedOptions());
    Picture p = renderPicture(ctx, *head_, smallSettings());
    Coverage c = measure(p);
    EXPECT_GT(c.fraction, 0.10);
    EXPECT_LT(c.fraction, 0.70);
    // The corners are the clear colour: the bust is framed, not cropped.
    const uint8_t* bg = &p.rgba[0];
    const uint8_t* br = &p.rgba[4 * (size_t(kHeight) * kWidth - 1)];
    EXPECT_TRUE(bg[0] == br[0] && bg[1] == br[1] && bg[2] == br[2]) << "bottom-right corner is not background";
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST_F(HeadRender, LitOnTheLightsSide)
{
    vk::Context ctx(test::validatedOptions());
    RenderSettings s = smallSettings();
    s.light.azimuthDeg = 80.0f;  // toward +x: the right of the picture from the default camera
    Coverage fromRight = measure(renderPicture(ctx, *head_, s));
    s.light.azimuthDeg = -80.0f;
    Coverage fromLeft = measure(renderPicture(ctx, *head_, s));
    EXPECT_GT(fromRight.rightLuminance, fromRight.leftLuminance * 1.15);
    EXPECT_GT(fromLeft.leftLuminance, fromLeft.rightLuminance * 1.15);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST_F(HeadRender, SingleSamplePathMatchesInCoverage)
{
    vk::Context ctx(test::validatedOptions());
    RenderSettings s = smallSettings();
    s.samples = 1;
    Coverage single = measure(renderPicture(ctx, *head_, s));
    Coverage msaa = measure(renderPicture(ctx, *head_, smallSettings()));
    EXPECT_NEAR(single.fraction, msaa.fraction, 0.01);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}
