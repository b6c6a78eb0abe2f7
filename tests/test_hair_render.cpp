// tests/test_hair_render.cpp: the strands renderer. The CPU twin of the tessellation math (Bezier
// C1 joints, interpolation weights, deterministic deviations); the pipeline-statistics counts the
// settings imply, across the 64 limits; rendered images: coverage of the scalp region, a
// horizontal strand visible, determinism, more strands covering more pixels.
#include "app/session/headless.h"
#include "gpu/frame.h"
#include "physics/colliders.h"
#include "physics/hair_scene.h"
#include "renderer/renderer.h"
#include "shaders/shared/strands.h"
#include "small_scene.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace wisp;

// ---- CPU twin of the tessellation math --------------------------------------------------------

TEST(StrandMath, BezierSegmentsJoinWithC1Continuity)
{
    std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0.2f, 0}, {2, -0.3f, 0.5f}, {2.5f, -1.0f, 1.0f}, {3, -2.5f, 1.0f}};
    auto segment = [&](int i) {
        int n = int(p.size());
        return gpu::catmullRomBezier(p[size_t(std::max(i - 1, 0))], p[size_t(i)], p[size_t(i + 1)],
                                     p[size_t(std::min(i + 2, n - 1))]);
    };
    for (int i = 0; i + 2 < int(p.size()); ++i) {
        gpu::Bezier a = segment(i), b = segment(i + 1);
        EXPECT_LT(glm::length(gpu::bezierPoint(a, 1.0f) - gpu::bezierPoint(b, 0.0f)), 1e-6f);     // C0
        EXPECT_LT(glm::length(gpu::bezierTangent(a, 1.0f) - gpu::bezierTangent(b, 0.0f)), 1e-5f); // C1
        EXPECT_LT(glm::length(gpu::bezierPoint(a, 0.0f) - p[size_t(i)]), 1e-6f);                  // interpolates
    }
    // Parameter mapping: t = 0 and 1 are the strand's ends, segments in order.
    EXPECT_EQ(gpu::curveSegment(0.0f, 5), 0u);
    EXPECT_EQ(gpu::curveSegment(1.0f, 5), 3u);
    EXPECT_NEAR(gpu::curveLocal(1.0f, 5, 3), 1.0f, 1e-6f);
    EXPECT_EQ(gpu::curveSegment(0.49f, 5), 1u);
}

TEST(StrandMath, InterpolationWeightsSumToOneAndDiscIsFilled)
{
    float maxR = 0.0f;
    for (uint32_t s = 1; s < 2000; ++s) {
        glm::vec3 w = gpu::triangleWeights(s % 97, s);
        EXPECT_NEAR(w.x + w.y + w.z, 1.0f, 1e-6f);
        EXPECT_GE(std::min({w.x, w.y, w.z}), 0.0f);
        glm::vec2 d = gpu::discOffset(s % 97, s);
        EXPECT_LE(glm::length(d), 1.0f + 1e-6f);
        maxR = std::max(maxR, glm::length(d));
    }
    EXPECT_GT(maxR, 0.95f);                            // reaches the rim
    EXPECT_EQ(gpu::discOffset(5, 0), glm::vec2(0.0f)); // strand 0 is the guide
    EXPECT_FALSE(gpu::strandIsMulti(gpu::kInterpolationMulti, 0));
    EXPECT_TRUE(gpu::strandIsMulti(gpu::kInterpolationMixed, 3));
    EXPECT_FALSE(gpu::strandIsMulti(gpu::kInterpolationMixed, 4));
}

// The frame the clump discs and deviations offset strands in is orthonormal and turns continuously
// with the tangent: over tangents swept through every direction but straight up, a step of 0.01
// radians in the tangent turns the frame by little (the frame it replaced switched its helper axis
// at |t.y| = 0.9 and jumped by up to 90 degrees there, drawing hanging strands' offsets as zigzags).
// A short guide's strands spread less: the clump disc at most a fifteenth of its length and the
// deviation at most a twelfth, so a crop's 5 cm strands are not drawn as fuzz; a long guide's take
// the settings whole.
TEST(StrandMath, AShortGuidesStrandsSpreadInProportionToItsLength)
{
    gpu::CurvePoint g;
    g.position = glm::vec3(0.0f);
    g.tangent = glm::vec3(0.0f, -1.0f, 0.0f);
    auto widest = [&](float length) {
        float out = 0.0f;
        for (uint32_t guide = 0; guide < 50; ++guide)
            for (uint32_t s = 1; s < 64; ++s)
                for (float t = 0.0f; t <= 1.0f; t += 0.05f) {
                    gpu::CurvePoint p = gpu::placeStrandPoint(g, g, g, guide, s, t, gpu::kInterpolationMixed, 0.01f,
                                                              0.012f, length, 0.0f, 0.0f, 24);
                    out = std::max(out, glm::length(p.position - g.position));
                }
        return out;
    };
    float shortest = widest(0.05f);
    EXPECT_LE(shortest, 0.05f / 15.0f + 0.05f / 12.0f + 1e-6f);
    EXPECT_GT(shortest, 0.5f * 0.05f / 12.0f);
    EXPECT_GT(widest(0.3f), 0.012f) << "a long guide's strands reach the whole deviation";
}

TEST(StrandMath, TheOffsetFrameTurnsContinuouslyWithTheTangent)
{
    auto frameAt = [](float polar, float azimuth) {
        // polar 0: straight down (-y); pi: straight up.
        glm::vec3 t(std::sin(polar) * std::cos(azimuth), -std::cos(polar), std::sin(polar) * std::sin(azimuth));
        return gpu::strandFrame(t);
    };
    float worst = 0.0f;
    for (float azimuth = 0.0f; azimuth < 6.28f; azimuth += 0.1f)
        for (float polar = 0.0f; polar < 2.8f; polar += 0.01f) {
            glm::mat3 a = frameAt(polar, azimuth), b = frameAt(polar + 0.01f, azimuth);
            for (int k = 1; k < 3; ++k) {
                ASSERT_NEAR(glm::length(a[k]), 1.0f, 1e-4f);
                ASSERT_NEAR(glm::dot(a[k], a[0]), 0.0f, 1e-4f);
            }
            ASSERT_NEAR(glm::dot(a[1], a[2]), 0.0f, 1e-4f);
            worst = std::max({worst, glm::length(a[1] - b[1]), glm::length(a[2] - b[2])});
        }
    // A least rotation turns the frame by about the tangent's own step far from straight up.
    EXPECT_LT(worst, 0.1f);
}

TEST(StrandMath, DeviationsAreDeterministicAndAboutHalfTheStrands)
{
    uint32_t deviating = 0;
    for (uint32_t s = 0; s < 4000; ++s) {
        float a = gpu::deviationProfile(s / 40, s % 40, 0.75f);
        EXPECT_EQ(a, gpu::deviationProfile(s / 40, s % 40, 0.75f)); // same guide and strand, same value
        bool any = false;
        for (float t = 0.0f; t <= 1.0f; t += 0.05f)
            any = any || gpu::deviationProfile(s / 40, s % 40, t) > 1e-3f;
        deviating += any ? 1u : 0u;
    }
    EXPECT_NEAR(double(deviating) / 4000.0, 0.5, 0.04);
    // Every profile is smooth at the drawn resolution: between two points of the default 24
    // divisions it changes by at most a third of its peak, so no bump is drawn as a triangle.
    for (uint32_t s = 0; s < 4000; ++s)
        for (int k = 0; k < 24; ++k) {
            float a = gpu::deviationProfile(s / 40, s % 40, float(k) / 24.0f);
            float b = gpu::deviationProfile(s / 40, s % 40, float(k + 1) / 24.0f);
            ASSERT_LE(std::abs(b - a), 0.34f) << "strand " << s << ", division " << k;
        }
    // Roots stay where interpolation puts them.
    for (uint32_t s = 0; s < 4000; ++s)
        ASSERT_LT(gpu::deviationProfile(s / 40, s % 40, 0.0f), 0.07f);
}

// The render-time coil (shaders/shared/strands.h coilAt): a helix about the strand, its radius and
// turns as set, each strand at its own phase, shaded along its own turn, and faded out when the
// divisions are too few to draw a turn.
TEST(StrandMath, TheRenderTimeCoilTurnsAtItsFrequencyAndRadius)
{
    // A straight guide 0.2 long hanging down (-y: the strand's frame is x and z), no clump and no
    // deviation; the coil 3 mm around at 50 turns per unit length, 10 turns, drawn with 80 divisions.
    const float length = 0.2f, radius = 0.003f, frequency = 50.0f;
    const uint32_t divisions = 80;
    auto point = [&](uint32_t s, float t, uint32_t d) {
        gpu::CurvePoint g{glm::vec3(0.0f, -length * t, 0.0f), glm::vec3(0.0f, -length, 0.0f)};
        gpu::CurvePoint p = gpu::placeStrandPoint(g, g, g, 5, s, t, gpu::kInterpolationSingle, 0.0f, 0.0f, length,
                                                  radius, frequency, d);
        return std::make_pair(p, p.position - g.position);
    };
    std::vector<float> startAngles;
    for (uint32_t s : {0u, 3u, 17u}) {
        float unwrapped = 0.0f, previous = 0.0f;
        for (uint32_t i = 0; i <= divisions; ++i) {
            float t = float(i) / float(divisions);
            auto [p, offset] = point(s, t, divisions);
            ASSERT_NEAR(offset.y, 0.0f, 1e-6f) << "the coil lies across the strand";
            if (t * frequency * length >= 1.0f) // past the first turn, where it grows in
                ASSERT_NEAR(glm::length(offset), radius, 1e-5f) << "strand " << s << ", point " << i;
            else
                ASSERT_LE(glm::length(offset), radius + 1e-6f);
            float angle = std::atan2(offset.z, offset.x);
            if (i == divisions / 2)
                startAngles.push_back(angle);
            if (i > divisions / 8) { // the phase is defined once the radius is
                float step = angle - previous;
                step -= 6.2831853f * std::round(step / 6.2831853f);
                EXPECT_NEAR(step, 6.2831853f * frequency * length / float(divisions), 1e-3f);
                unwrapped += step;
            }
            previous = angle;
            // The tangent turns with the helix: along the drawn points' own direction.
            if (i > 0 && i < divisions) {
                glm::vec3 chord = point(s, float(i + 1) / float(divisions), divisions).first.position -
                                  point(s, float(i - 1) / float(divisions), divisions).first.position;
                EXPECT_GT(glm::dot(p.tangent, glm::normalize(chord)), 0.97f) << "strand " << s << ", point " << i;
                EXPECT_NEAR(glm::length(p.tangent), 1.0f, 1e-5f);
            }
        }
        // The turns as set over the points measured (all but the first eighth).
        EXPECT_NEAR(unwrapped / 6.2831853f, frequency * length * float(divisions - divisions / 8) / float(divisions),
                    0.01f);
    }
    EXPECT_GT(std::abs(startAngles[0] - startAngles[1]), 0.05f) << "strands coil at phases of their own";
    EXPECT_GT(std::abs(startAngles[1] - startAngles[2]), 0.05f);
    // Ten turns in 30 divisions are 3 points a turn: a zigzag, so no coil at all; nor at radius 0.
    for (float t = 0.0f; t <= 1.0f; t += 0.05f) {
        EXPECT_EQ(glm::length(point(3, t, 30).second), 0.0f);
        gpu::CurvePoint g{glm::vec3(0.0f, -length * t, 0.0f), glm::vec3(0.0f, -length, 0.0f)};
        EXPECT_EQ(gpu::placeStrandPoint(g, g, g, 5, 3, t, gpu::kInterpolationSingle, 0.0f, 0.0f, length, 0.0f,
                                        frequency, divisions)
                      .position,
                  g.position);
    }
    // At the root the strand leaves its follicle: no offset.
    EXPECT_EQ(glm::length(point(3, 0.0f, divisions).second), 0.0f);
}

TEST(StrandMath, LodFadesTheLastStrandInstead)
{
    EXPECT_EQ(gpu::lodAlpha(3, 8.0f), 1.0f);
    EXPECT_NEAR(gpu::lodAlpha(8, 8.4f), 0.4f, 1e-6f);
    EXPECT_EQ(gpu::lodAlpha(9, 8.4f), 0.0f);
}

TEST(StrandMath, DrawCountsSplitPastTheTessellationLimits)
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

TEST(StrandMath, GuideNeighboursOfFewGuidesOnALine)
{
    // Two guides whose roots differ along x only: the search grid is one cell thick and about a
    // thousand long, and the second neighbour never exists. The search grew its ring to the whole
    // grid through every cell of a cube (hours); now it ends once every other guide was seen.
    StrandSet set;
    set.verticesPerStrand = 4;
    for (int s = 0; s < 2; ++s)
        set.add({glm::vec3(0.2f * float(s), 1.5f, -1.0f), glm::vec3(0.2f * float(s), 1.0f, -1.0f),
                 glm::vec3(0.2f * float(s), 0.5f, -1.0f), glm::vec3(0.2f * float(s), 0.0f, -1.0f)},
                0, 1, false);
    set.parts.push_back({});
    std::vector<glm::uvec4> tri = guideTriangles(set);
    ASSERT_EQ(tri.size(), 2u);
    EXPECT_EQ(tri[0], glm::uvec4(0, 1, 0, gpu::packGuideShape(1.5f, 1.0f)));
    EXPECT_EQ(tri[1], glm::uvec4(1, 0, 1, gpu::packGuideShape(1.5f, 1.0f)));
    EXPECT_EQ(gpu::guideLength(tri[0].w), 1.5f);
    EXPECT_EQ(gpu::guideWidthScale(tri[0].w), 1.0f);
    for (uint32_t s = 2; s < 7; ++s) // and a few more on the line: the two nearest
        set.add({glm::vec3(0.2f * float(s), 1.5f, -1.0f), glm::vec3(0.2f * float(s), 1.0f, -1.0f),
                 glm::vec3(0.2f * float(s), 0.5f, -1.0f), glm::vec3(0.2f * float(s), 0.0f, -1.0f)},
                0, 1, false);
    tri = guideTriangles(set);
    EXPECT_EQ(tri[3].x, 3u);
    EXPECT_EQ(std::min(tri[3].y, tri[3].z), 2u);
    EXPECT_EQ(std::max(tri[3].y, tri[3].z), 4u);
}

TEST(StrandMath, DrawsStayWithinTheTessellatedVerticesADrawMayHold)
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

HairFrame renderHairFrame(const vk::Context& ctx, const HairScene& scene, const RenderSettings& settings,
                          float cameraDistanceScale = 1.0f)
{
    test::HairRenderer hair(ctx, scene, settings);
    Renderer& renderer = hair.renderer;
    Frame frame(ctx, 1);
    OrbitCamera camera = OrbitCamera::framing(renderer.sceneBounds(), float(settings.width) / float(settings.height));
    camera.distance *= cameraDistanceScale;
    camera.fitPlanes(); // the hair stays between the planes (as the window's zoom keeps it)
    Picture picture = renderFrame(ctx, renderer, frame, camera);
    bool graphics = renderer.hairRaster() == HairRaster::Graphics;
    return {picture, graphics ? renderer.hair()->statistics() : HairPass::Statistics{}};
}

HairScene smallScene(uint32_t guides)
{
    GrowthSettings g;
    g.guides = guides;
    return buildGrownScene(defaultHeadPath(), g);
}

} // namespace

TEST(HairRender, PipelineStatisticsCountWhatTheSettingsAsk)
{
    vk::Context ctx(test::validatedOptions());
    if (!ctx.report().pipelineStatisticsQuery)
        GTEST_SKIP() << "the device has no pipeline statistics queries";
    HairScene scene = smallScene(7);
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
    HairScene scene = smallScene(300);
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
    HairScene scene = smallScene(1);
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
    HairScene scene = smallScene(20);
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

TEST(StrandMath, MultiStrandPointsNeverInsideACollider)
{
    // The hair pass's multi-strand placement, on the CPU: the guide and its two nearest neighbours
    // (guideTriangles) blended with the strand's barycentric weights along their C1 curves, then
    // pushed out of every collider in turn, exactly as hair.tese does.
    GrowthSettings g;
    g.guides = 400;
    HairScene scene = buildGrownScene(defaultHeadPath(), g);
    std::vector<glm::uvec4> tri = guideTriangles(scene.strands);
    uint32_t V = scene.strands.verticesPerStrand;
    auto curve = [&](uint32_t guide, float t) {
        uint32_t seg = gpu::curveSegment(t, V);
        auto p = [&](uint32_t i) { return scene.strands.rest[size_t(guide) * V + i]; };
        gpu::Bezier b =
            gpu::catmullRomBezier(p(seg == 0 ? 0 : seg - 1), p(seg), p(seg + 1), p(std::min(seg + 2, V - 1)));
        return gpu::bezierPoint(b, gpu::curveLocal(t, V, seg));
    };
    float diagonal = scene.head.mesh.bounds().diagonal();
    float deepest = 0.0f, deepestBefore = 0.0f;
    for (uint32_t guide = 0; guide < g.guides; ++guide) {
        EXPECT_NE(tri[guide].y, guide); // every guide has neighbours
        for (uint32_t s = 1; s < 16; ++s)
            for (float t = 0.05f; t <= 1.0f; t += 0.1f) {
                glm::vec3 w = gpu::triangleWeights(guide, s);
                glm::vec3 p = w.x * curve(guide, t) + w.y * curve(tri[guide].y, t) + w.z * curve(tri[guide].z, t);
                deepestBefore = std::max(deepestBefore, penetrationDepth(scene.gpuColliders, p));
                for (const gpu::Ellipsoid& e : scene.gpuColliders)
                    p = gpu::pushOutOfCollider(e, glm::mat4(1.0f), p);
                deepest = std::max(deepest, penetrationDepth(scene.gpuColliders, p));
            }
    }
    std::fprintf(stderr, "deepest before %g, after %g (diagonal %g)\n", double(deepestBefore), double(deepest),
                 double(diagonal));
    EXPECT_GT(deepestBefore, 0.0f);       // blending does cut into the head: the correction matters
    EXPECT_LT(deepest, 1e-4f * diagonal); // and afterwards no point is inside any collider
}
