// tests/test_strand_math.cpp: the strands' shared math (shaders/shared/strands.h) on the CPU, as the
// tessellation and the compute strands run it: Bezier C1 joints, interpolation weights and the clump
// disc, the offset frame, deterministic deviations, the drawn strands' own lengths, level of
// detail, the guides' neighbours (physics' guideTriangles) and multi-strand points kept out of the
// colliders.
#include "physics/colliders.h"
#include "physics/groomed_head.h"
#include "shaders/shared/strands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

using namespace wisp;

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

// Drawn strands' own lengths (strand_length_jitter, shaders/shared/strands.h strandLengthFraction):
// each strand of a guide is drawn along the first 1 - cut of its guide's curve, the cut uniform in
// [0, jitter] from the strand's own hash, the same every time; 0 keeps every strand whole. The
// compute path finds the trimmed strand's points between the guide's samples at t = k / D
// (curveBetweenSamples), close to the curve the tessellation path evaluates, and the drawn strand's
// length is its fraction of the guide's.
TEST(StrandMath, DrawnStrandsEndAtLengthsOfTheirOwn)
{
    const float jitter = 0.3f;
    double sum = 0.0, below = 0.0;
    size_t n = 0;
    float lo = 1.0f, hi = 0.0f;
    for (uint32_t guide = 0; guide < 200; ++guide)
        for (uint32_t s = 0; s < 46; ++s) {
            float f = gpu::strandLengthFraction(guide, s, jitter);
            ASSERT_GE(f, 1.0f - jitter);
            ASSERT_LE(f, 1.0f);
            ASSERT_EQ(f, gpu::strandLengthFraction(guide, s, jitter));  // deterministic
            ASSERT_EQ(gpu::strandLengthFraction(guide, s, 0.0f), 1.0f); // 0: every strand whole
            sum += f;
            below += f < 1.0f - jitter / 2.0f ? 1.0 : 0.0;
            lo = std::min(lo, f);
            hi = std::max(hi, f);
            ++n;
        }
    EXPECT_NEAR(sum / double(n), 1.0 - jitter / 2.0, 0.005) << "uniform in [0, jitter]: the mean cut is half";
    EXPECT_NEAR(below / double(n), 0.5, 0.02);
    EXPECT_LT(lo, 1.0f - 0.99f * jitter); // the whole range is used
    EXPECT_GT(hi, 1.0f - 0.01f * jitter);
    EXPECT_NE(gpu::strandLengthFraction(3, 1, jitter), gpu::strandLengthFraction(3, 2, jitter));
    EXPECT_NE(gpu::strandLengthFraction(3, 1, jitter), gpu::strandLengthFraction(4, 1, jitter));
    EXPECT_EQ(gpu::strandGuideParameter(1.0f, 0.8f), 0.8f);
    EXPECT_EQ(gpu::strandGuideParameter(0.0f, 0.8f), 0.0f);

    // A bent guide of 16 vertices 2 cm apart (as the solver keeps them), sampled at D = 24 as
    // strands_curves.comp samples it.
    const uint32_t V = 16, D = 24;
    std::vector<glm::vec3> guide(V);
    for (uint32_t i = 1; i < V; ++i) {
        float a = 0.15f * float(i), b = 0.3f * std::sin(0.4f * float(i));
        guide[i] = guide[i - 1] + 0.02f * glm::vec3(std::sin(a) * std::cos(b), -std::cos(a) * std::cos(b), std::sin(b));
    }
    auto exact = [&](float t) {
        uint32_t seg = gpu::curveSegment(t, V);
        return gpu::guideCurvePoint(guide[seg == 0 ? 0 : seg - 1], guide[seg], guide[seg + 1],
                                    guide[std::min(seg + 2, V - 1)], gpu::curveLocal(t, V, seg));
    };
    std::vector<gpu::CurvePoint> samples(D + 1);
    for (uint32_t k = 0; k <= D; ++k)
        samples[k] = exact(float(k) / float(D));
    float spacing = float(V - 1) / float(D);
    auto between = [&](float x) {
        uint32_t k = gpu::curveSampleBelow(x, D);
        return gpu::curveBetweenSamples(samples[k], samples[k + 1], x - float(k), spacing);
    };
    float guideLength = 0.0f;
    for (uint32_t i = 0; i + 1 < V; ++i)
        guideLength += glm::length(guide[i + 1] - guide[i]);
    float worst = 0.0f, worstTangent = 0.0f;
    for (uint32_t j = 0; j <= 2400; ++j) {
        float x = float(j) / 100.0f;
        gpu::CurvePoint a = between(x), b = exact(x / float(D));
        worst = std::max(worst, glm::length(a.position - b.position));
        worstTangent = std::max(worstTangent, glm::length(glm::normalize(a.tangent) - glm::normalize(b.tangent)));
    }
    // (Within 0.1% of the strand's length, 0.3 mm over 30 cm; here 0.15 mm: the guide's Bezier
    // segments join with C1, not C2, so a cubic across a joint differs from them a little.)
    EXPECT_LT(worst, 1e-3f * guideLength) << "the Hermite between samples follows the curve";
    EXPECT_GT(worst, 0.0f);
    EXPECT_LT(worstTangent, 0.04f);
    for (uint32_t k = 0; k <= D; ++k) { // on a sample: the sample itself, bit for bit (jitter 0 is today)
        EXPECT_EQ(between(float(k)).position, samples[k].position);
        EXPECT_EQ(between(float(k)).tangent, samples[k].tangent);
    }
    // The drawn strand's length (its curve, measured finely): its fraction of the guide's, within
    // the curve's own unevenness (its speed along t falls a little in the end segments).
    auto drawnLength = [&](float fraction) {
        float length = 0.0f;
        glm::vec3 previous = between(0.0f).position;
        for (uint32_t i = 1; i <= 10 * D; ++i) {
            glm::vec3 p = between(float(i) * fraction / 10.0f).position;
            length += glm::length(p - previous);
            previous = p;
        }
        return length;
    };
    float whole = drawnLength(1.0f);
    for (uint32_t s = 0; s < 46; ++s) {
        float f = gpu::strandLengthFraction(7, s, jitter);
        EXPECT_NEAR(drawnLength(f) / whole, f, 0.01f) << "strand " << s;
    }
}

TEST(StrandMath, LodFadesTheLastStrandInstead)
{
    EXPECT_EQ(gpu::lodAlpha(3, 8.0f), 1.0f);
    EXPECT_NEAR(gpu::lodAlpha(8, 8.4f), 0.4f, 1e-6f);
    EXPECT_EQ(gpu::lodAlpha(9, 8.4f), 0.0f);
}

TEST(StrandMath, GuideNeighboursOfFewGuidesOnALine)
{
    // Two guides whose roots differ along x only: the search grid is one cell thick and about a
    // thousand long, and the second neighbour never exists. The search must end once every other
    // guide was seen, not grow its ring to the whole grid through every cell of a cube (hours).
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

TEST(StrandMath, MultiStrandPointsNeverInsideACollider)
{
    // The hair pass's multi-strand placement, on the CPU: the guide and its two nearest neighbours
    // (guideTriangles) blended with the strand's barycentric weights along their C1 curves, then
    // pushed out of every collider in turn, exactly as hair.tese does.
    GrowthSettings g;
    g.guides = 400;
    GroomedHead scene = buildGrownHead(defaultHeadPath(), g);
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
