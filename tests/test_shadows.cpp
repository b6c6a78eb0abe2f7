// tests/test_shadows.cpp: the light's side of the picture on the device (the shared math of PCF taps
// and deep opacity layers is tests/test_shadow_math.cpp): shadows darken the head and never brighten anything, the side
// away from the light is darker, the deep opacity layers hold the hair and their transmittance
// falls with depth, the OIT result does not depend on draw order, and a full pool is counted.
#include "app/session/headless.h"
#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "physics/groomed_head.h"
#include "renderer/renderer.h"
#include "shaders/shared/shadows.h"
#include "small_groomed_head.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

using namespace wisp;

// ---- On the device ------------------------------------------------------------------------------

namespace {

using test::renderHair;
using test::smallGroomedHead;
using test::smallRenderSettings;

double luminance(const Picture& p, size_t pixel)
{
    return 0.2126 * p.rgba[pixel * 4] + 0.7152 * p.rgba[pixel * 4 + 1] + 0.0722 * p.rgba[pixel * 4 + 2];
}

// Copies the light's hair depth and opacity layers to the host within the frame that made them.
class LightMapsReadback : public Pass {
public:
    LightMapsReadback(const vk::Context& ctx, LightMaps& maps) : maps_(maps)
    {
        size_t texels = size_t(maps.size()) * maps.size();
        depth_ = ctx.createBuffer(
            {.size = texels * 4, .usage = vk::kTransferDst, .memory = vk::Memory::Readback, .name = "test.hair_depth"});
        opacity_ = ctx.createBuffer(
            {.size = texels * 8, .usage = vk::kTransferDst, .memory = vk::Memory::Readback, .name = "test.opacity"});
    }
    const char* name() const override { return "test.readback"; }
    // The hair's depth as the opacity lookups sample it: the depth image, or the compute path's
    // values (LightMaps::useHairDepthValues).
    void declare(PassIo& io) override
    {
        io.use(maps_.hairDepthValuesUsed() ? maps_.hairDepthValues() : maps_.hairDepth(), Access::TransferSrc);
        io.use(maps_.opacity(), Access::TransferSrc);
    }
    void record(VkCommandBuffer cmd, FrameContext&) override
    {
        uint32_t n = maps_.size();
        bool values = maps_.hairDepthValuesUsed();
        VkBufferImageCopy depth{
            .imageSubresource = {values ? VK_IMAGE_ASPECT_COLOR_BIT : VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1},
            .imageExtent = {n, n, 1}};
        vkCmdCopyImageToBuffer(cmd, values ? maps_.hairDepthValuesImage().get() : maps_.hairDepthImage().get(),
                               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, depth_, 1, &depth);
        VkBufferImageCopy color{.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {n, n, 1}};
        vkCmdCopyImageToBuffer(cmd, maps_.opacityImage().get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, opacity_, 1,
                               &color);
        vk::transferToHostBarrier(cmd);
    }
    float depth(size_t texel) const
    {
        float v;
        std::memcpy(&v, static_cast<const char*>(depth_.mapped()) + texel * 4, 4);
        return v;
    }
    glm::vec4 opacity(size_t texel) const
    {
        uint16_t h[4];
        std::memcpy(h, static_cast<const char*>(opacity_.mapped()) + texel * 8, 8);
        glm::vec4 v;
        for (int c = 0; c < 4; ++c)
            v[c] = halfToFloat(h[c]);
        return v;
    }

private:
    static float halfToFloat(uint16_t h)
    {
        int e = (h >> 10) & 31, m = h & 1023;
        float v = e == 0 ? std::ldexp(float(m), -24) : std::ldexp(float(m | 1024), e - 25);
        return (h & 0x8000) ? -v : v;
    }
    LightMaps& maps_;
    vk::Buffer depth_, opacity_;
};

} // namespace

// The light's maps and their use hold for both ways of drawing the strands (the compute path
// draws the hair's maps in compute too).
class ShadowsBoth : public ::testing::TestWithParam<HairRaster> {};
INSTANTIATE_TEST_SUITE_P(Paths, ShadowsBoth, ::testing::Values(HairRaster::Graphics, HairRaster::Compute),
                         [](const ::testing::TestParamInfo<HairRaster>& p) {
                             return std::string(p.param == HairRaster::Graphics ? "graphics" : "compute");
                         });

TEST_P(ShadowsBoth, DarkenTheHeadAndNeverBrightenAnything)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(150);
    RenderSettings s = smallRenderSettings();
    s.hairRaster = GetParam();
    s.transparency.mode = Transparency::Msaa;
    Picture lit = [&] {
        RenderSettings o = s;
        o.shadows.enabled = false;
        return renderHair(ctx, scene, o);
    }();
    Picture shadowed = renderHair(ctx, scene, s);
    size_t darker = 0, brighter = 0;
    for (size_t i = 0; i < size_t(s.width) * s.height; ++i) {
        double d = luminance(shadowed, i) - luminance(lit, i);
        darker += d < -6.0 ? 1u : 0u;
        brighter += d > 3.0 ? 1u : 0u;
    }
    // (Measured at this size: 328 pixels drawn by tessellation, 268 in compute, whose hair, blended
    // as the lists blend it, lets some of the head show through.)
    EXPECT_GT(darker, size_t(s.width) * s.height / 150) << "the chin shades the neck, the hair the head and itself";
    EXPECT_EQ(brighter, 0u);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST_P(ShadowsBoth, TheSideAwayFromTheLightIsDarker)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(150);
    RenderSettings s = smallRenderSettings();
    s.hairRaster = GetParam();
    s.light.elevationDeg = 10.0f;
    double side[2] = {0.0, 0.0};
    for (int k = 0; k < 2; ++k) {
        s.light.azimuthDeg = k == 0 ? 90.0f : -90.0f; // from the image's right (+x), then its left
        Picture p = renderHair(ctx, scene, s);
        double right = 0.0, left = 0.0;
        for (uint32_t y = 0; y < s.height; ++y)
            for (uint32_t x = 0; x < s.width; ++x)
                (x >= s.width / 2 ? right : left) += luminance(p, size_t(y) * s.width + x);
        side[k] = right - left;
    }
    EXPECT_GT(side[0], 0.0) << "lit from the right, the right half is brighter";
    EXPECT_LT(side[1], 0.0) << "lit from the left, the left half is brighter";
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST_P(ShadowsBoth, DeepOpacityLayersHoldTheHairAndTransmittanceFallsWithDepth)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(200);
    RenderSettings s = smallRenderSettings();
    s.hairRaster = GetParam();
    s.shadows.mapSize = 256;
    s.light.elevationDeg = 80.0f; // from above: light crosses the whole thickness of the hair
    test::HairRenderer hair(ctx, scene, s);
    Renderer& renderer = hair.renderer;
    Frame& frame = hair.frame;
    OrbitCamera camera = hair.camera;
    LightMapsReadback readback(ctx, renderer.lightMaps());
    FrameContext& fc = frame.begin(renderer.transientImages());
    renderer.prepare(fc, camera, 0.0f);
    std::vector<Pass*> passes = renderer.passes();
    passes.push_back(&readback);
    frame.run(fc, passes);
    frame.submit(fc);
    frame.waitIdle();

    // The same spacing pack() gives the shaders, in light depth units.
    gpu::FrameParams params =
        pack(s, camera, {s.width, s.height}, 0.0f, LightFit{renderer.sceneBounds(), scene.unitsPerMetre});
    size_t hairTexels = 0, dense = 0;
    size_t texels = size_t(s.shadows.mapSize) * s.shadows.mapSize;
    for (size_t t = 0; t < texels; ++t) {
        float z0 = readback.depth(t);
        glm::vec4 layers = readback.opacity(t);
        for (int c = 0; c < 4; ++c)
            ASSERT_TRUE(std::isfinite(layers[c]) && layers[c] >= 0.0f);
        if (z0 >= 1.0f) {
            EXPECT_EQ(layers, glm::vec4(0.0f)) << "texel " << t << ": opacity where no hair is";
            continue;
        }
        ++hairTexels;
        EXPECT_GT(layers.x, 0.0f) << "texel " << t << ": the first hair adds to the first layer";
        float previous = 1.0f;
        float spacing = params.domSpacing;
        for (int k = 0; k <= 40; ++k) {
            float z = z0 + float(k) * spacing * 0.25f;
            float transmittance = gpu::domTransmittance(gpu::domOpacity(layers, z, z0, spacing, 4), s.shadows.domKappa);
            EXPECT_LE(transmittance, previous + 1e-6f);
            previous = transmittance;
        }
        dense += previous < 0.5f ? 1u : 0u;
    }
    EXPECT_GT(hairTexels, texels / 50) << "the hair seen from above covers part of the map";
    EXPECT_GT(dense, 0u) << "somewhere the hair is thick enough to let less than half the light through";
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(Oit, TheResultDoesNotDependOnDrawOrder)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(120);
    RenderSettings s = smallRenderSettings();
    s.hairRaster = HairRaster::Graphics; // the linked lists (the compute path's order: TwoRendersAreIdentical)
    s.transparency.mode = Transparency::Oit;
    s.transparency.oitNodesPerPixel = 64;
    Picture forward = renderHair(ctx, scene, s);
    s.strands.reverseOrder = true;
    Picture reverse = renderHair(ctx, scene, s);
    EXPECT_GT(forward.oit.fragments, 1000u);
    EXPECT_EQ(forward.oit.overflow, 0u);
    EXPECT_EQ(reverse.oit.fragments, forward.oit.fragments) << "the same strands, in the other order";
    int maxDiff = 0;
    for (size_t i = 0; i < forward.rgba.size(); ++i)
        maxDiff = std::max(maxDiff, std::abs(int(forward.rgba[i]) - int(reverse.rgba[i])));
    EXPECT_LE(maxDiff, 2) << "only the rounding of the unsorted tail's sums may differ";
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(Oit, AGroomPastOneDrawsTessellationLimitDrawsEveryStrandInEitherOrder)
{
    // 600 guides x 5 strands x 25 vertices are 75,000 tessellated vertices: more than one draw may
    // produce on lavapipe (it indexes them with 16 bits). Drawn as one draw, patches were lost by
    // draw order (the count and the picture changed with reverse_order); split, every strand is
    // there in either order, and the picture equals that of one strand per patch (other patches,
    // other draws, the same strands).
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(600);
    RenderSettings s = smallRenderSettings();
    s.hairRaster = HairRaster::Graphics; // the tessellation path's draws and its lists
    s.transparency.oitNodesPerPixel = 64;
    s.strands.strandsPerGuide = 5;
    s.strands.divisions = 24;
    s.strands.lod = false;
    Picture forward = renderHair(ctx, scene, s);
    s.strands.reverseOrder = true;
    Picture reverse = renderHair(ctx, scene, s);
    s.strands.reverseOrder = false;
    s.strands.maxPatchVertices = 25; // one strand per patch, five instances
    Picture single = renderHair(ctx, scene, s);
    EXPECT_GT(forward.oit.fragments, 10000u);
    EXPECT_EQ(forward.oit.overflow, 0u);
    EXPECT_EQ(reverse.oit.fragments, forward.oit.fragments) << "the same strands, in the other order";
    EXPECT_EQ(single.oit.fragments, forward.oit.fragments) << "the same strands, from smaller patches";
    int maxDiff = 0;
    for (size_t i = 0; i < forward.rgba.size(); ++i)
        maxDiff = std::max({maxDiff, std::abs(int(forward.rgba[i]) - int(reverse.rgba[i])),
                            std::abs(int(forward.rgba[i]) - int(single.rgba[i]))});
    EXPECT_LE(maxDiff, 2) << "only the rounding of the unsorted tail's sums may differ";
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(Oit, AnAutomaticPoolThatOverflowsGrowsAndTheFrameIsDrawnAgain)
{
    // The default demo dropped 5,046 fragments at 1280 x 720. The automatic pool (started here at
    // 2,000 nodes, far too few) grows when a frame overflows and the frame is drawn again: nothing
    // dropped, and the picture of a pool large from the start.
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(150);
    RenderSettings s = smallRenderSettings();
    s.hairRaster = HairRaster::Graphics; // the linked lists' pool
    s.transparency.oitNodesPerPixel = 64;
    Picture roomy = renderHair(ctx, scene, s);
    s.transparency.oitNodesPerPixel = 0;
    s.transparency.oitAutoNodes = 2000;
    Picture grown = renderHair(ctx, scene, s);
    EXPECT_GT(roomy.oit.fragments, 10000u);
    EXPECT_EQ(roomy.oit.overflow, 0u);
    EXPECT_EQ(grown.oit.overflow, 0u);
    EXPECT_EQ(grown.oit.fragments, roomy.oit.fragments);
    EXPECT_GE(grown.oit.capacity, grown.oit.fragments);
    EXPECT_TRUE(grown.oit.automatic);
    EXPECT_EQ(grown.rgba, roomy.rgba);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(Oit, OverflowAdviceOffersWhatCanHelp)
{
    // A pool of the person's own that the device can make large enough: the value to ask for.
    OitStats own{.fragments = 90000, .overflow = 30000, .capacity = 60000, .limit = 1u << 26, .automatic = false};
    std::string a = oitOverflowAdvice(own, 100, 100);
    EXPECT_NE(a.find("30000 of 90000 hair fragments were dropped"), std::string::npos) << a;
    EXPECT_NE(a.find("raise oit_nodes_per_pixel to 11"), std::string::npos) << a;
    // One the device cannot hold (or the automatic pool at its limit): raising it cannot help.
    OitStats capped{.fragments = 90000, .overflow = 30000, .capacity = 60000, .limit = 60000, .automatic = false};
    a = oitOverflowAdvice(capped, 100, 100);
    EXPECT_EQ(a.find("raise"), std::string::npos) << a;
    EXPECT_NE(a.find("at most 60000 nodes (6 per pixel here)"), std::string::npos) << a;
    EXPECT_NE(a.find("transparency=msaa"), std::string::npos) << a;
    capped.automatic = true;
    EXPECT_NE(oitOverflowAdvice(capped, 100, 100).find("transparency=msaa"), std::string::npos);
}

TEST(Oit, AFullPoolIsCountedAndTheFrameStillCompletes)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(150);
    RenderSettings s = smallRenderSettings();
    s.hairRaster =
        HairRaster::Graphics; // the linked lists (the compute path's buffer: StrandRaster.AFullFragmentBuffer...)
    s.transparency.oitNodesPerPixel = 1;
    Picture p = renderHair(ctx, scene, s);
    EXPECT_EQ(p.oit.capacity, uint64_t(s.width) * s.height);
    EXPECT_GT(p.oit.fragments, p.oit.capacity);
    EXPECT_EQ(p.oit.overflow, p.oit.fragments - p.oit.capacity);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}
