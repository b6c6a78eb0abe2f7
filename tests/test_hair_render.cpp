// tests/test_hair_render.cpp: the strands renderer. The draws the tessellation is split into
// (renderer/graphics/hair_pass.h's hairDrawCounts) and the pipeline-statistics counts the settings
// imply, across the 64 limits; rendered images: coverage of the scalp region, a horizontal strand
// visible, determinism, more strands covering more pixels. (The strands' shared math, on the CPU, is
// tests/test_strand_math.cpp.)
#include "app/session/headless.h"
#include "gpu/frame.h"
#include "physics/colliders.h"
#include "physics/groomed_head.h"
#include "renderer/graphics/hair_pass.h"
#include "renderer/renderer.h"
#include "shaders/shared/strands.h"
#include "small_groomed_head.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace wisp;

// ---- The draws the tessellation is split into ---------------------------------------------

TEST(HairDrawCounts, SplitPastTheTessellationLimits)
{
    StrandSettings s;
    s.strandsPerGuide = 150;
    s.divisions = 130;
    HairDrawCounts c = hairDrawCounts(10, s);
    EXPECT_EQ(c.lengthChunks, 3u);    // 44 + 43 + 43 divisions
    EXPECT_EQ(c.strandsPerPatch, 2u); // 2 lines x 45 vertices <= 128
    EXPECT_EQ(c.strandChunks, 75u);   // 150 strands in instances of 2
    EXPECT_EQ(c.strands(), 1500u);    // nothing capped
    EXPECT_EQ(c.segments(), 1500u * 130u);
    s.strandsPerGuide = 100;
    s.divisions = 1;
    c = hairDrawCounts(10, s);
    EXPECT_EQ(c.strandsPerPatch, 64u); // the tessellation level bounds it first
    EXPECT_EQ(c.strandChunks, 2u);
}

TEST(HairDrawCounts, DrawsStayWithinTheTessellatedVerticesADrawMayHold)
{
    // Each instance of each draw tessellates at most kMaxTessVerticesPerDraw vertices (lavapipe
    // indexes them with 16 bits), whatever the groom and the patch size.
    for (uint32_t maxPatch : {26u, 128u, 1000u, 4160u})
        for (uint32_t divisions : {1u, 24u, 64u, 200u})
            for (uint32_t guides : {1u, 3000u, 100000u}) {
                StrandSettings s;
                s.strandsPerGuide = 32;
                s.divisions = divisions;
                s.maxPatchVertices = maxPatch;
                HairDrawCounts c = hairDrawCounts(guides, s);
                uint32_t divisionsPerPatch = (divisions + c.lengthChunks - 1) / c.lengthChunks;
                uint64_t perPatch = uint64_t(c.strandsPerPatch) * (divisionsPerPatch + 1);
                EXPECT_LE(c.patchesPerDraw * perPatch, uint64_t(gpu::kMaxTessVerticesPerDraw));
                EXPECT_GT((c.patchesPerDraw + 1) * perPatch, uint64_t(gpu::kMaxTessVerticesPerDraw))
                    << "no more draws than needed";
                EXPECT_EQ(c.draws(), (c.patches() + c.patchesPerDraw - 1) / c.patchesPerDraw);
            }
    StrandSettings s;
    s.strandsPerGuide = 5;
    HairDrawCounts c = hairDrawCounts(3000, s); // 3000 patches of 5 x 25 vertices
    EXPECT_EQ(c.patchesPerDraw, 524u);          // 524 x 125 = 65,500
    EXPECT_EQ(c.draws(), 6u);
}

// ---- On the device ------------------------------------------------------------------------------

namespace {

struct HairFrame {
    Picture picture;
    HairPass::Statistics stats; // the tessellation path's pipeline statistics
    // The segments drawn: the geometry shader's invocations, or the compute path's count.
    uint64_t segments() const
    {
        return picture.raster.capacity > 0 ? picture.raster.segments : stats.geometryInvocations;
    }
};

HairFrame renderHairFrame(const vk::Context& ctx, const GroomedHead& scene, const RenderSettings& settings,
                          float cameraDistanceScale = 1.0f)
{
    test::HairRenderer hair(ctx, scene, settings);
    Renderer& renderer = hair.renderer;
    Frame& frame = hair.frame;
    OrbitCamera camera = hair.camera;
    camera.distance *= cameraDistanceScale;
    camera.fitPlanes(); // the hair stays between the planes (as the window's zoom keeps it)
    Picture picture = renderFrame(ctx, renderer, frame, camera);
    bool graphics = renderer.hairRaster() == HairRaster::Graphics;
    return {picture, graphics ? renderer.hair()->statistics() : HairPass::Statistics{}};
}

GroomedHead smallScene(uint32_t guides)
{
    GrowthSettings g;
    g.guides = guides;
    return buildGrownHead(defaultHeadPath(), g);
}

} // namespace

// The compute path's frames build no tessellation pipeline (no HairPass); switching hair_raster to
// graphics, as the window's panel does, builds it for the next frame, which draws every line.
TEST(HairRender, TheComputePathBuildsNoTessellationPipelines)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallScene(7);
    RenderSettings s;
    s.hairRaster = HairRaster::Compute;
    s.width = 96;
    s.height = 64;
    s.shadows.mapSize = 256;
    s.strands.strandsPerGuide = 3;
    s.strands.divisions = 5;
    s.strands.lod = false;
    test::HairRenderer hair(ctx, scene, s);
    Picture compute = renderFrame(ctx, hair.renderer, hair.frame, hair.camera);
    EXPECT_EQ(hair.renderer.hairRaster(), HairRaster::Compute);
    EXPECT_EQ(hair.renderer.hair(), nullptr);
    EXPECT_GT(compute.raster.segments, 0u); // the compute path drew the strands
    EXPECT_NE(hair.renderer.describeHairDraw().find("compute"), std::string::npos);

    hair.renderer.settings().hairRaster = HairRaster::Graphics;
    Picture graphics = renderFrame(ctx, hair.renderer, hair.frame, hair.camera);
    ASSERT_NE(hair.renderer.hair(), nullptr);
    EXPECT_EQ(graphics.raster.capacity, 0u); // drawn by the tessellation now
    EXPECT_NE(hair.renderer.describeHairDraw().find("patches"), std::string::npos);
    if (ctx.report().pipelineStatisticsQuery) {
        EXPECT_EQ(hair.renderer.hair()->statistics().geometryInvocations, 7ull * 3 * 5);
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(HairRender, PipelineStatisticsCountWhatTheSettingsAsk)
{
    vk::Context ctx(test::validatedOptions());
    if (!ctx.report().pipelineStatisticsQuery)
        GTEST_SKIP() << "the device has no pipeline statistics queries";
    GroomedHead scene = smallScene(7);
    struct Case {
        uint32_t strands, divisions;
    };
    for (Case c : {Case{3, 5}, Case{1, 1}, Case{70, 9}, Case{5, 100}}) {
        RenderSettings s;
        s.hairRaster = HairRaster::Graphics; // what the tessellation stages count
        s.width = 96;
        s.height = 64;
        s.strands.strandsPerGuide = c.strands;
        s.strands.divisions = c.divisions;
        s.strands.lod = false;
        HairFrame f = renderHairFrame(ctx, scene, s);
        uint64_t lines = 7ull * c.strands * c.divisions;
        std::fprintf(stderr, "S=%u D=%u: GS invocations %s primitives %s TES %s (expected lines %s)\n", c.strands,
                     c.divisions, std::to_string(f.stats.geometryInvocations).c_str(),
                     std::to_string(f.stats.geometryPrimitives).c_str(),
                     std::to_string(f.stats.tessEvaluations).c_str(), std::to_string(lines).c_str());
        EXPECT_EQ(f.stats.geometryInvocations, lines) << "S=" << c.strands << " D=" << c.divisions;
        EXPECT_EQ(f.stats.geometryPrimitives, 2 * lines); // a two-triangle ribbon per line (all in front of the camera)
        EXPECT_GE(f.stats.tessEvaluations, 7ull * c.strands * (c.divisions + 1) / 2);
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

namespace {

// How much the hair changes the picture: the summed colour difference from the bald render
// (thin strands change pixels partly, so counting changed pixels saturates where hair overlaps).
double ink(const Picture& a, const Picture& b)
{
    double sum = 0.0;
    for (size_t i = 0; i < a.rgba.size(); i += 4)
        sum += std::abs(a.rgba[i] - b.rgba[i]) + std::abs(a.rgba[i + 1] - b.rgba[i + 1]) +
               std::abs(a.rgba[i + 2] - b.rgba[i + 2]);
    return sum;
}

// Pixels that differ from the same render without hair.
size_t changedPixels(const Picture& a, const Picture& b)
{
    size_t n = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4)
        if (std::abs(a.rgba[i] - b.rgba[i]) + std::abs(a.rgba[i + 1] - b.rgba[i + 1]) +
                std::abs(a.rgba[i + 2] - b.rgba[i + 2]) >
            12)
            ++n;
    return n;
}

// The rendering tests that hold for both ways of drawing the strands run on each.
class HairRenderBoth : public ::testing::TestWithParam<HairRaster> {};
INSTANTIATE_TEST_SUITE_P(Paths, HairRenderBoth, ::testing::Values(HairRaster::Graphics, HairRaster::Compute),
                         [](const ::testing::TestParamInfo<HairRaster>& p) {
                             return std::string(p.param == HairRaster::Graphics ? "graphics" : "compute");
                         });

RenderSettings imageSettings()
{
    RenderSettings s;
    s.width = 240;
    s.height = 180;
    return s;
}

} // namespace

TEST_P(HairRenderBoth, HairCoversTheScalpAndMoreStrandsCoverMore)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallScene(300);
    RenderSettings s = imageSettings();
    s.hairRaster = GetParam();
    s.scalpPaint = 0.0f; // the strands' own coverage against the bare head (the paint is under every count)
    Picture bald = renderPicture(ctx, scene.head, s);
    s.strands.strandsPerGuide = 8;
    HairFrame fewer = renderHairFrame(ctx, scene, s);
    s.strands.strandsPerGuide = 16;
    HairFrame more = renderHairFrame(ctx, scene, s);
    HairFrame again = renderHairFrame(ctx, scene, s);
    size_t covered8 = changedPixels(fewer.picture, bald), covered16 = changedPixels(more.picture, bald);
    double ink8 = ink(fewer.picture, bald), ink16 = ink(more.picture, bald);
    std::fprintf(stderr, "changed pixels: 8 strands %zu, 16 strands %zu of %u; ink %g, %g\n", covered8, covered16,
                 s.width * s.height, ink8, ink16);
    EXPECT_GT(covered8, size_t(s.width * s.height) / 50); // the hair is on screen
    EXPECT_GE(covered16, covered8);                       // doubling the strands covers more pixels
    EXPECT_GT(ink16, 1.15 * ink8);                        // and covers them more
    EXPECT_TRUE(more.picture.rgba == again.picture.rgba); // and the same settings give the same image
    // The hair sits on the upper half of the picture, where the scalp is.
    size_t upper = 0, lower = 0;
    for (uint32_t y = 0; y < s.height; ++y)
        for (uint32_t x = 0; x < s.width; ++x) {
            size_t i = 4 * (size_t(y) * s.width + x);
            bool changed = std::abs(more.picture.rgba[i] - bald.rgba[i]) > 12;
            (y < s.height / 2 ? upper : lower) += changed ? 1 : 0;
        }
    EXPECT_GT(upper, lower);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST_P(HairRenderBoth, AHorizontalStrandKeepsItsWidth)
{
    // One guide lying horizontally across the view (the seed offset ribbons along screen x, so
    // such a strand collapsed to nothing): its ribbon must cover pixels in a band, not a line.
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallScene(1);
    std::vector<glm::vec3> points(scene.strands.verticesPerStrand);
    for (uint32_t i = 0; i < points.size(); ++i)
        points[i] = glm::vec3(-0.15f + 0.3f * float(i) / float(points.size() - 1), 0.3f, 0.2f); // above the head
    scene.strands.rest.assign(points.begin(), points.end());
    scene.strands.strands.resize(1);
    scene.strands.strands[0].pinnedRoot = 1;
    scene.gpuColliders.clear();
    RenderSettings s = imageSettings();
    s.hairRaster = GetParam();
    s.strands.strandsPerGuide = 1;
    s.strands.widthMetres = 0.004f; // a few pixels wide at this distance
    s.strands.lod = false;
    Picture bald = renderPicture(ctx, scene.head, s);
    HairFrame f = renderHairFrame(ctx, scene, s);
    // Count, per column, the rows the strand covers.
    uint32_t columns = 0, maxRows = 0;
    for (uint32_t x = 0; x < s.width; ++x) {
        uint32_t rows = 0;
        for (uint32_t y = 0; y < s.height; ++y) {
            size_t i = 4 * (size_t(y) * s.width + x);
            rows += std::abs(f.picture.rgba[i] - bald.rgba[i]) + std::abs(f.picture.rgba[i + 1] - bald.rgba[i + 1]) > 12
                        ? 1
                        : 0;
        }
        columns += rows > 0 ? 1 : 0;
        maxRows = std::max(maxRows, rows);
    }
    EXPECT_GT(columns, s.width / 4); // it spans the view horizontally
    EXPECT_GE(maxRows, 2u);          // and has width
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST_P(HairRenderBoth, LodDrawsFewerStrandsFarAwayAndAllNearby)
{
    vk::Context ctx(test::validatedOptions());
    if (GetParam() == HairRaster::Graphics && !ctx.report().pipelineStatisticsQuery)
        GTEST_SKIP() << "the device has no pipeline statistics queries";
    GroomedHead scene = smallScene(20);
    RenderSettings s;
    s.hairRaster = GetParam();
    s.width = 96;
    s.height = 64;
    s.strands.strandsPerGuide = 40;
    s.strands.divisions = 4;
    uint64_t all = 20ull * 40 * 4;
    EXPECT_EQ(renderHairFrame(ctx, scene, s, 1.0f).segments(), all);  // at the framing distance
    EXPECT_EQ(renderHairFrame(ctx, scene, s, 0.5f).segments(), all);  // nearer: never more
    uint64_t twice = renderHairFrame(ctx, scene, s, 2.0f).segments(); // (1/2)² = 25% of the strands
    EXPECT_EQ(twice, 20ull * 10 * 4);
    uint64_t far = renderHairFrame(ctx, scene, s, 10.0f).segments(); // floor: lodMinFraction (20%)
    EXPECT_EQ(far, 20ull * 8 * 4);
    s.strands.lodMinFraction = 0.5f;
    EXPECT_EQ(renderHairFrame(ctx, scene, s, 10.0f).segments(), 20ull * 20 * 4); // a higher floor
    s.strands.lod = false;
    EXPECT_EQ(renderHairFrame(ctx, scene, s, 10.0f).segments(), all); // off: always all
    EXPECT_EQ(ctx.validationMessages(), 0u);
}
