// tests/test_render.cpp: the head rendered offscreen on the real device with validation on:
// deterministic, covering a plausible part of the frame, brighter on the light's side, the
// same through the single-sample path, and the same in any units (no z-fighting in centimetres).
#include "app/session/headless.h"
#include "assets/head.h"
#include "shaders/shared/frame_params.h"
#include "shaders/shared/mesh_raster.h"
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

// The backdrop's sRGB bytes at row y (frameBackground: a vertical gradient).
glm::ivec3 backdrop(const RenderSettings& s, uint32_t y)
{
    gpu::FrameParams f{};
    f.backgroundTop = s.backgroundTop;
    f.backgroundBottom = s.backgroundBottom;
    f.viewportHeight = float(s.height);
    glm::vec3 c = gpu::frameBackground(f, float(y) + 0.5f);
    return glm::ivec3(glm::round(255.0f * glm::vec3(gpu::encodeSrgb(c.r), gpu::encodeSrgb(c.g), gpu::encodeSrgb(c.b))));
}

struct Coverage {
    double fraction = 0.0;       // of all pixels, differing from the backdrop
    double leftLuminance = 0.0;  // mean over covered pixels in the left half
    double rightLuminance = 0.0; // ... and in the right half
};

Coverage measure(const Picture& p, const RenderSettings& s = smallSettings())
{
    Coverage c;
    size_t covered = 0, left = 0, right = 0;
    for (uint32_t y = 0; y < p.height; ++y)
        for (uint32_t x = 0; x < p.width; ++x) {
            glm::ivec3 bg = backdrop(s, y);
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

} // namespace

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
    GroomedHead scene = buildGrownHead(defaultHeadPath(), growth);
    SimSettings sim;
    sim.wind = glm::vec3(3.0f, 0.0f, 0.0f);
    SceneTimeline held = stillTimeline(glm::vec4(0.0f, 0.1f, -0.12f, 0.05f), sim.wind, smallSettings().light);
    vk::Context ctx(test::validatedOptions());
    HairSession first(ctx, scene, sim, held), second(ctx, scene, sim, held);
    Picture a = renderPicture(ctx, first, smallSettings(), 12, 30.0f);
    Picture b = renderPicture(ctx, second, smallSettings(), 12, 30.0f);
    EXPECT_TRUE(a.rgba == b.rgba);
    Picture still = renderPicture(ctx, scene.head, smallSettings());
    EXPECT_FALSE(a.rgba == still.rgba); // the hair is in the picture
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST_F(HeadRender, CoversAPlausiblePartOfTheFrame)
{
    vk::Context ctx(test::validatedOptions());
    Picture p = renderPicture(ctx, *head_, smallSettings());
    Coverage c = measure(p);
    EXPECT_GT(c.fraction, 0.20);
    EXPECT_LT(c.fraction, 0.80);
    // A head-and-shoulders portrait: the top row is backdrop (headroom over the crown), the
    // shoulders reach the bottom row.
    size_t topCovered = 0, bottomCovered = 0;
    for (uint32_t x = 0; x < kWidth; ++x) {
        const uint8_t* t = &p.rgba[4 * size_t(x)];
        const uint8_t* b = &p.rgba[4 * (size_t(kHeight - 1) * kWidth + x)];
        glm::ivec3 bt = backdrop(smallSettings(), 0), bb = backdrop(smallSettings(), kHeight - 1);
        topCovered += std::abs(t[0] - bt.x) + std::abs(t[1] - bt.y) + std::abs(t[2] - bt.z) > 3 ? 1 : 0;
        bottomCovered += std::abs(b[0] - bb.x) + std::abs(b[1] - bb.y) + std::abs(b[2] - bb.z) > 3 ? 1 : 0;
    }
    EXPECT_EQ(topCovered, 0u) << "the head is not cut at the top";
    EXPECT_GT(bottomCovered, size_t(kWidth / 4)) << "the bust is cut at the shoulders, as a portrait is";
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST_F(HeadRender, LitOnTheLightsSide)
{
    vk::Context ctx(test::validatedOptions());
    RenderSettings s = smallSettings();
    s.fill.intensity = 0.0f; // the key alone (the fill lights the other side: test_studio_look.cpp)
    s.rim.intensity = 0.0f;
    s.light.azimuthDeg = 80.0f; // toward +x: the right of the picture from the default camera
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

TEST_F(HeadRender, AHeadInOtherUnitsRendersTheSamePicture)
{
    // The camera frames the head whatever its units; the near plane must scale with it too, or a
    // head in centimetres z-fights (the near plane was 5e-5 units whatever the units: a depth step
    // of about 10 cm at 1 m in 32-bit float depth). Real meshes have surfaces close behind others
    // (clothes over skin, eyes in sockets): here a second skin 0.5% inside the head, its normals
    // turned inward so that wherever it wins the depth test it shows dark. Hidden, the picture is
    // the plain head's, in metres, centimetres and hundredths of a millimetre.
    vk::Context ctx(test::validatedOptions());
    Picture plain = renderPicture(ctx, *head_, smallSettings());
    Bounds b = head_->mesh.bounds();
    for (float scale : {1.0f, 100.0f, 0.01f}) {
        Head layered = *head_;
        Mesh& m = layered.mesh;
        uint32_t n = uint32_t(m.positions.size());
        size_t triangles = m.indices.size();
        for (uint32_t v = 0; v < n; ++v) {
            m.positions.push_back(b.center() + 0.995f * (m.positions[v] - b.center()));
            m.normals.push_back(-m.normals[v]);
        }
        for (size_t i = 0; i < triangles; ++i) // drawn last: where depths tie, it wins (less or equal)
            m.indices.push_back(m.indices[i] + n);
        for (glm::vec3& p : m.positions)
            p *= scale;
        Picture other = renderPicture(ctx, layered, smallSettings());
        ASSERT_EQ(other.rgba.size(), plain.rgba.size());
        size_t differing = 0;
        double sum = 0.0;
        for (size_t i = 0; i < plain.rgba.size(); i += 4) {
            int d = 0;
            for (int k = 0; k < 3; ++k)
                d = std::max(d, std::abs(int(plain.rgba[i + k]) - int(other.rgba[i + k])));
            sum += d;
            differing += d > 24 ? 1 : 0;
        }
        double pixels = double(plain.rgba.size() / 4);
        EXPECT_LT(double(differing) / pixels, 0.002) << "scale " << scale << ": pixels that differ clearly";
        EXPECT_LT(sum / pixels, 0.5) << "scale " << scale << ": mean difference";
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}
