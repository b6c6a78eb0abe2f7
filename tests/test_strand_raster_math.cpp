// tests/test_strand_raster_math.cpp: the compute strand renderer's shared math on the CPU
// (shaders/shared/strand_raster.h): analytic coverage against exact polygon areas, seamless joints,
// the row spans holding everything covered, and the per-pixel fragment lists (the nearest k sorted, the rest blended)
// against a plain sort, in any arrival order. Also the compute meshes' triangles (shaders/shared/mesh_raster.h):
// coverage and depth against ray casts, and fans without gaps.
#include "shaders/shared/mesh_raster.h"
#include "shaders/shared/strand_raster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

namespace {

// The exact area of a convex polygon clipped to the unit pixel [x, x + 1] x [y, y + 1]
// (Sutherland-Hodgman against its four edges, then the shoelace formula).
double clippedArea(std::vector<glm::dvec2> poly, double x, double y)
{
    auto clip = [&](auto inside, auto cross) {
        std::vector<glm::dvec2> out;
        for (size_t i = 0; i < poly.size(); ++i) {
            glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
            bool ia = inside(a), ib = inside(b);
            if (ia)
                out.push_back(a);
            if (ia != ib)
                out.push_back(cross(a, b));
        }
        poly = out;
    };
    auto atX = [](double cx) {
        return [cx](glm::dvec2 a, glm::dvec2 b) { return a + (b - a) * ((cx - a.x) / (b.x - a.x)); };
    };
    auto atY = [](double cy) {
        return [cy](glm::dvec2 a, glm::dvec2 b) { return a + (b - a) * ((cy - a.y) / (b.y - a.y)); };
    };
    clip([&](glm::dvec2 p) { return p.x >= x; }, atX(x));
    clip([&](glm::dvec2 p) { return p.x <= x + 1; }, atX(x + 1));
    clip([&](glm::dvec2 p) { return p.y >= y; }, atY(y));
    clip([&](glm::dvec2 p) { return p.y <= y + 1; }, atY(y + 1));
    double area = 0.0;
    for (size_t i = 0; i < poly.size(); ++i) {
        glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        area += a.x * b.y - b.x * a.y;
    }
    return std::abs(area) * 0.5;
}

// The ribbon of a segment of constant half width h: a rectangle.
std::vector<glm::dvec2> ribbon(glm::dvec2 a, glm::dvec2 b, double h)
{
    glm::dvec2 d = glm::normalize(b - a);
    glm::dvec2 n(-d.y, d.x);
    return {a + h * n, b + h * n, b - h * n, a - h * n};
}

float coverage(glm::vec2 a, glm::vec2 b, float h, int x, int y)
{
    return gpu::segmentCoverage(gpu::makeRasterSegment(a, b, h, h), glm::vec2(float(x), float(y)) + 0.5f).x;
}

} // namespace

TEST(RasterCoverage, AxisAlignedRibbonsAreExact)
{
    struct Case {
        glm::vec2 a, b;
        float h;
    };
    for (Case c : {Case{{2.3f, 5.4f}, {9.7f, 5.4f}, 0.35f}, Case{{4.5f, 1.2f}, {4.5f, 8.9f}, 1.3f},
                   Case{{9.1f, 3.3f}, {1.6f, 3.3f}, 0.05f}}) {
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x) {
                double exact = clippedArea(ribbon(c.a, c.b, c.h), x, y);
                EXPECT_NEAR(coverage(c.a, c.b, c.h, x, y), exact, 1e-5) << "pixel " << x << ", " << y;
            }
    }
}

TEST(RasterCoverage, EveryAngleIsExactAcrossTheRibbonAndSumsToItsArea)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int trial = 0; trial < 60; ++trial) {
        float angle = 6.2831853f * unit(rng);
        float len = 4.0f + 20.0f * unit(rng);
        float h = trial % 3 == 0 ? 0.04f + 0.2f * unit(rng) : 0.3f + 2.0f * unit(rng); // thin and wide strands
        glm::vec2 a(32.0f + unit(rng), 32.0f + unit(rng)); // the whole ribbon inside the 64² pixels summed
        glm::vec2 b = a + len * glm::vec2(std::cos(angle), std::sin(angle));
        std::vector<glm::dvec2> rect = ribbon(a, b, h);
        double sum = 0.0, worstInside = 0.0;
        gpu::RasterSegment s = gpu::makeRasterSegment(a, b, h, h);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                float cov = coverage(a, b, h, x, y);
                ASSERT_GE(cov, 0.0f);
                ASSERT_LE(cov, 1.0f);
                sum += cov;
                // Away from the ends the along-overlap is whole and the coverage is the band's: exact.
                glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
                float u = glm::dot(centre - s.a, s.dir);
                if (u > 1.0f && u < len - 1.0f)
                    worstInside = std::max(worstInside, std::abs(double(cov) - clippedArea(rect, x, y)));
            }
        EXPECT_LT(worstInside, 1e-4) << "trial " << trial << ": across the ribbon the coverage is its exact area";
        EXPECT_NEAR(sum, 2.0 * h * len, 0.01 * 2.0 * h * len + 0.02) << "trial " << trial << ": thin strands add up";
    }
}

TEST(RasterCoverage, ConsecutiveSegmentsJoinWithoutSeamOrOverlap)
{
    // A strand's two straight segments cover the pixels at their joint as the one segment does.
    glm::vec2 a(2.2f, 3.1f), b(9.4f, 6.3f), c(16.6f, 9.5f);
    for (int y = 0; y < 14; ++y)
        for (int x = 0; x < 20; ++x) {
            float two = coverage(a, b, 0.4f, x, y) + coverage(b, c, 0.4f, x, y);
            EXPECT_NEAR(two, coverage(a, c, 0.4f, x, y), 2e-5f) << "pixel " << x << ", " << y;
        }
}

TEST(RasterReach, RowSpansHoldEveryCoveredPixelAndLittleElse)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> pos(-4.0f, 20.0f), width(0.02f, 2.5f);
    int spanned = 0, covered = 0;
    for (int trial = 0; trial < 400; ++trial) {
        glm::vec2 a(pos(rng), pos(rng)), b(pos(rng), pos(rng));
        if (trial % 5 == 0)
            b.y = a.y; // horizontal
        if (trial % 6 == 0)
            b.x = a.x; // vertical
        if (trial % 7 == 0)
            b = a + glm::vec2(0.3f, 0.2f); // shorter than a pixel
        gpu::RasterSegment s = gpu::makeRasterSegment(a, b, width(rng), width(rng));
        float reach = gpu::ribbonReach(s);
        for (int y = -8; y < 28; ++y) {
            glm::vec2 span = gpu::ribbonRowSpan(s, float(y) + 0.5f);
            bool rowReached =
                float(y) + 0.5f >= std::min(a.y, b.y) - reach && float(y) + 0.5f <= std::max(a.y, b.y) + reach;
            for (int x = -8; x < 28; ++x) {
                glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
                bool inSpan = span.x <= centre.x && centre.x <= span.y;
                spanned += inSpan ? 1 : 0;
                if (gpu::segmentCoverage(s, centre).x <= 0.0f)
                    continue;
                ++covered;
                EXPECT_TRUE(inSpan) << "trial " << trial << ": covered pixel " << x << ", " << y
                                    << " outside its row's span";
                EXPECT_TRUE(rowReached) << "trial " << trial << ": covered pixel " << x << ", " << y
                                        << " beyond the reach";
            }
        }
    }
    EXPECT_GT(covered, 1000);
    EXPECT_LT(spanned, covered + covered / 4) << "the spans hold little more than the covered pixels";
}

TEST(RasterWalk, ClumpOrderTakesEverySegmentOnce)
{
    // The walks' threads take the segments clump by clump (clumpOrderedSegment): every segment of
    // every strand exactly once, and neighbouring threads the same segment of neighbouring strands.
    for (uint32_t strandsPerGuide : {1u, 3u, 8u}) {
        for (uint32_t divisions : {1u, 5u, 24u}) {
            uint32_t guides = 7;
            uint32_t count = guides * strandsPerGuide * divisions;
            std::vector<uint32_t> taken(count, 0);
            for (uint32_t t = 0; t < count; ++t) {
                uint32_t segment = gpu::clumpOrderedSegment(t, divisions, strandsPerGuide);
                ASSERT_LT(segment, count) << "thread " << t;
                ++taken[segment];
                if (t + 1 < count && (t + 1) % strandsPerGuide != 0) { // the next strand, the same segment
                    EXPECT_EQ(gpu::clumpOrderedSegment(t + 1, divisions, strandsPerGuide), segment + divisions);
                }
            }
            EXPECT_TRUE(std::all_of(taken.begin(), taken.end(), [](uint32_t n) { return n == 1; }))
                << strandsPerGuide << " strands per guide, " << divisions << " divisions";
        }
    }
}

TEST(RasterWalk, PixelBoundsHoldEveryCoveredPixelAndNoFragmentIsNearerThanItsSegment)
{
    // The walks skip a segment behind the meshes' coarse depth over the tiles its pixel bounds
    // reach (ribbonPixelBounds, depthCanPass): exact only if every pixel the ribbon covers lies
    // within the bounds, and no fragment's depth (mixed along the segment) is nearer than its
    // nearer end by more than depthCanPass allows.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    constexpr uint32_t kWidth = 64, kHeight = 48;
    size_t covered = 0;
    for (int trial = 0; trial < 400; ++trial) {
        glm::vec2 a(unit(rng) * 80.0f - 8.0f, unit(rng) * 64.0f - 8.0f);
        float length = trial % 4 == 0 ? unit(rng) * 0.5f : unit(rng) * 20.0f; // some shorter than a pixel
        float angle = unit(rng) * 6.2831853f;
        glm::vec2 b = a + length * glm::vec2(std::cos(angle), std::sin(angle));
        float ha = trial % 3 == 0 ? unit(rng) * 3.0f : unit(rng) * 0.3f, hb = unit(rng) * 0.3f;
        gpu::RasterSegment s = gpu::makeRasterSegment(a, b, ha, hb);
        glm::ivec4 bounds = gpu::ribbonPixelBounds(s, a, b, kWidth, kHeight);
        float za = unit(rng), zb = unit(rng);
        for (int y = 0; y < int(kHeight); ++y)
            for (int x = 0; x < int(kWidth); ++x) {
                glm::vec2 hit = gpu::segmentCoverage(s, glm::vec2(float(x), float(y)) + 0.5f);
                if (hit.x <= 0.0f)
                    continue;
                ++covered;
                ASSERT_TRUE(x >= bounds.x && x <= bounds.z && y >= bounds.y && y <= bounds.w)
                    << "trial " << trial << ": pixel " << x << ", " << y << " covered outside the bounds";
                ASSERT_TRUE(gpu::depthCanPass(std::min(za, zb), glm::mix(za, zb, hit.y)))
                    << "trial " << trial << ": a fragment nearer than its segment";
            }
    }
    EXPECT_GT(covered, 1000u);
}

TEST(RasterWalk, TheLightsWalkReachesEveryTexelItsRibbonHolds)
{
    // strands_light.comp walks only the texels whose centres lie within a sixteenth of a texel of
    // the ribbon (lightTexelBounds, lightRowCentres): every texel lightTexelHit takes must be among
    // them, far from the origin too (a map of 8192 texels, where a float's step is a thousandth).
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    size_t hits = 0, walked = 0;
    for (float origin : {0.0f, 8100.0f}) {
        for (int trial = 0; trial < 300; ++trial) {
            glm::vec2 a = glm::vec2(origin) + glm::vec2(unit(rng) * 40.0f + 4.0f, unit(rng) * 40.0f + 4.0f);
            float length = trial % 4 == 0 ? unit(rng) * 0.5f : unit(rng) * 20.0f;
            float angle = trial % 5 == 0 ? float(trial % 8) * 0.7853982f : unit(rng) * 6.2831853f; // some on the axes
            glm::vec2 b = a + length * glm::vec2(std::cos(angle), std::sin(angle));
            float ha = trial % 3 == 0 ? unit(rng) * 3.0f : unit(rng) * 0.6f, hb = unit(rng) * 0.6f;
            gpu::RasterSegment s = gpu::makeRasterSegment(a, b, ha, hb);
            gpu::RasterSegment reach = gpu::makeRasterSegment(a, b, std::max(ha, 0.5f), std::max(hb, 0.5f));
            glm::ivec4 bounds = gpu::lightTexelBounds(reach, a, b, 8192, 8192);
            for (int y = int(origin); y < int(origin) + 56; ++y) {
                glm::vec2 span = gpu::lightRowCentres(reach, float(y) + 0.5f);
                int x0 = int(std::ceil(span.x - 0.5f)), x1 = int(std::floor(span.y - 0.5f));
                if (y >= bounds.y && y <= bounds.w)
                    walked += size_t(std::max(x1 - x0 + 1, 0));
                for (int x = int(origin); x < int(origin) + 56; ++x) {
                    if (gpu::lightTexelHit(s, glm::vec2(float(x), float(y)) + 0.5f).x <= 0.0f)
                        continue;
                    ++hits;
                    ASSERT_TRUE(x >= bounds.x && x <= bounds.z && y >= bounds.y && y <= bounds.w)
                        << "trial " << trial << ": texel " << x << ", " << y << " outside the bounds";
                    ASSERT_TRUE(x >= x0 && x <= x1) << "trial " << trial << ": texel " << x << ", " << y
                                                    << " outside its row's walk " << x0 << " .. " << x1;
                }
            }
        }
    }
    EXPECT_GT(hits, 2000u);
    EXPECT_LT(double(walked), 1.5 * double(hits)) << "the walk keeps to the ribbon's texels";
}

TEST(RasterFragments, TheNearestKAreSortedAndTheRestBlendedWhateverTheOrder)
{
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t k : {1u, 4u, 8u, 16u}) {
        for (int trial = 0; trial < 20; ++trial) {
            struct Fragment {
                float depth;
                uint32_t color;
            };
            std::vector<Fragment> fragments;
            int n = 1 + int(unit(rng) * 60.0f);
            for (int i = 0; i < n; ++i)
                fragments.push_back({unit(rng), gpu::packFragmentColor(glm::vec3(unit(rng), unit(rng), unit(rng)),
                                                                       0.05f + 0.9f * unit(rng))});
            gpu::PixelFragments f = gpu::emptyPixelFragments();
            for (const Fragment& x : fragments)
                gpu::insertFragment(f, k, x.depth, x.color);
            glm::vec4 result = gpu::resolveFragments(f, k);
            std::shuffle(fragments.begin(), fragments.end(), rng);
            gpu::PixelFragments g = gpu::emptyPixelFragments();
            for (const Fragment& x : fragments)
                gpu::insertFragment(g, k, x.depth, x.color);
            EXPECT_EQ(gpu::resolveFragments(g, k), result) << "k " << k << ": the arrival order changed the pixel";

            // The definition, in double precision: sort, composite the nearest k front to back,
            // then the rest as one layer (alpha-weighted mean colour, 1 - prod(1 - alpha)).
            std::sort(fragments.begin(), fragments.end(), [](const Fragment& a, const Fragment& b) {
                return gpu::fragmentFarther(b.depth, b.color, a.depth, a.color);
            });
            glm::dvec3 color(0.0);
            double transmittance = 1.0, tailWeight = 0.0, tailClear = 1.0;
            glm::dvec3 tailColor(0.0);
            for (size_t i = 0; i < fragments.size(); ++i) {
                glm::vec4 c = gpu::unpackFragmentColor(fragments[i].color);
                if (i < k) {
                    color += transmittance * double(c.w) * glm::dvec3(glm::vec3(c));
                    transmittance *= 1.0 - double(c.w);
                } else {
                    tailColor += double(c.w) * glm::dvec3(glm::vec3(c));
                    tailWeight += c.w;
                    tailClear *= 1.0 - std::min(double(c.w), 0.999);
                }
            }
            if (tailWeight > 0.0) {
                color += transmittance * (1.0 - tailClear) * tailColor / tailWeight;
                transmittance *= tailClear;
            }
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_NEAR(result[ch], color[ch], 3e-3) << "k " << k << " channel " << ch;
            EXPECT_NEAR(result.w, 1.0 - transmittance, 3e-3) << "k " << k;
        }
    }
}

TEST(RasterFragments, TheUnguardedTailEqualsTheGuardedOneBelowItsBound)
{
    // The bound: kTailExactFragments of the largest additions stay below the saturation point.
    uint32_t mostClear = 0, mostColor = 0;
    for (uint32_t a = 0; a < 256; ++a) {
        mostClear = std::max(mostClear, gpu::tailClearUnits(a));
        mostColor = std::max(mostColor, gpu::tailUnits(a * 255u * 255u));
    }
    EXPECT_EQ(mostClear, gpu::tailClearUnits(255u));
    EXPECT_LE(uint64_t(gpu::kTailExactFragments) * mostClear, uint64_t(gpu::kTailSaturate));
    EXPECT_LE(uint64_t(gpu::kTailExactFragments) * mostColor, uint64_t(gpu::kTailSaturate));
    uint64_t tenthMore = gpu::kTailExactFragments + gpu::kTailExactFragments / 10;
    EXPECT_GT(tenthMore * mostClear, uint64_t(gpu::kTailSaturate)) << "the bound is far below what saturates";

    // Below it, the two ways of summing keep the same pixel, field by field.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t k : {1u, 8u}) {
        gpu::PixelFragments guarded = gpu::emptyPixelFragments(), plain = gpu::emptyPixelFragments();
        for (int i = 0; i < 5000; ++i) {
            float depth = unit(rng);
            uint32_t color = gpu::packFragmentColor(glm::vec3(unit(rng), unit(rng), unit(rng)), unit(rng));
            gpu::insertFragmentSummed(guarded, k, depth, color, true);
            gpu::insertFragmentSummed(plain, k, depth, color, false);
        }
        EXPECT_EQ(std::memcmp(&guarded, &plain, sizeof(guarded)), 0) << "k " << k;
        EXPECT_GT(plain.tailClear, 0u);
    }

    // Past it the guard holds the sums at the saturation point.
    gpu::PixelFragments f = gpu::emptyPixelFragments();
    f.tailClear = gpu::kTailSaturate - 10u;
    gpu::insertFragmentSummed(f, 1, 0.5f, gpu::packFragmentColor(glm::vec3(1.0f), 1.0f), true); // kept
    gpu::insertFragmentSummed(f, 1, 0.6f, gpu::packFragmentColor(glm::vec3(1.0f), 1.0f), true); // to the tail
    EXPECT_EQ(f.tailClear, gpu::kTailSaturate);
}

// The compute meshes' triangle setup (shared/mesh_raster.h): which samples a triangle covers and
// the depth there, against the geometry itself.
namespace {

// A perspective camera at the origin looking down -z (Vulkan's clip space: y down, depth 0..1).
glm::mat4 testProjection(float aspect)
{
    float f = 1.0f / std::tan(0.5f * 0.9f), n = 0.1f, far = 10.0f;
    glm::mat4 p(0.0f);
    p[0][0] = f / aspect;
    p[1][1] = -f;
    p[2][2] = far / (n - far);
    p[2][3] = -1.0f;
    p[3][2] = far * n / (n - far);
    return p;
}

} // namespace

TEST(MeshRasterMath, CoverageAndDepthFollowTheTriangle)
{
    // Random triangles in front of the eye, across it and behind it: every sample of a 64 x 48
    // target is covered exactly where the ray through it hits the triangle in front of the near
    // plane (Moller-Trumbore), but for samples within a hair of an edge; and the depth there is the
    // hit's depth.
    const glm::vec2 size(64.0f, 48.0f);
    glm::mat4 projection = testProjection(size.x / size.y);
    glm::mat4 inverse = glm::inverse(projection);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> xy(-3.0f, 3.0f), z(-6.0f, 1.5f);
    size_t samples = 0, covered = 0, disagreements = 0, nearEdge = 0;
    double worstDepth = 0.0;
    for (int trial = 0; trial < 60; ++trial) {
        glm::vec3 v[3];
        for (glm::vec3& p : v)
            p = {xy(rng), xy(rng), z(rng)};
        gpu::MeshTriangle t =
            gpu::setupMeshTriangle(projection * glm::vec4(v[0], 1.0f), projection * glm::vec4(v[1], 1.0f),
                                   projection * glm::vec4(v[2], 1.0f), size);
        if (t.det == 0.0f)
            continue;
        for (int y = 0; y < int(size.y); ++y)
            for (int x = 0; x < int(size.x); ++x)
                for (uint32_t s = 0; s < 4; ++s) {
                    glm::vec2 pixel = glm::vec2(x, y) + gpu::meshSamplePosition(s, 4);
                    float depth = gpu::meshSampleDepth(t, pixel, size);
                    // The ray through the sample: from the eye through the point at depth 0.5.
                    glm::vec2 ndc = pixel / size * 2.0f - 1.0f;
                    glm::vec4 far = inverse * glm::vec4(ndc, 0.5f, 1.0f);
                    glm::vec3 dir = glm::normalize(glm::vec3(far) / far.w);
                    glm::vec3 e1 = v[1] - v[0], e2 = v[2] - v[0], pv = glm::cross(dir, e2);
                    float det = glm::dot(e1, pv);
                    glm::vec3 tv = -v[0];
                    float u = glm::dot(tv, pv) / det;
                    glm::vec3 qv = glm::cross(tv, e1);
                    float w = glm::dot(dir, qv) / det, along = glm::dot(e2, qv) / det;
                    glm::vec3 hit = along * dir;
                    bool inside = u >= 0.0f && w >= 0.0f && u + w <= 1.0f && along > 0.0f;
                    float hitDepth = 2.0f;
                    if (inside) {
                        glm::vec4 c = projection * glm::vec4(hit, 1.0f);
                        hitDepth = c.z / c.w;
                        inside = hitDepth >= 0.0f && hitDepth <= 1.0f;
                    }
                    float edge = std::min({std::abs(u), std::abs(w), std::abs(1.0f - u - w)});
                    ++samples;
                    if (inside != (depth <= 1.0f)) {
                        if (edge < 1e-3f || std::abs(hitDepth) < 1e-4f)
                            ++nearEdge;
                        else
                            ++disagreements;
                        continue;
                    }
                    if (inside) {
                        ++covered;
                        worstDepth = std::max(worstDepth, double(std::abs(depth - hitDepth)));
                    }
                }
    }
    EXPECT_GT(covered, samples / 20) << "the triangles cover part of the target";
    EXPECT_EQ(disagreements, 0u);
    EXPECT_LT(nearEdge, samples / 10000 + 1);
    EXPECT_LT(worstDepth, 1e-4);
}

TEST(MeshRasterMath, SharedEdgesLeaveNoGapAndNoOverlap)
{
    // A fan of triangles around a point covers every sample of the polygon once (the edge rows of
    // two neighbours are exact negatives): no sample is missed or drawn twice inside.
    const glm::vec2 size(80.0f, 60.0f);
    glm::mat4 projection = testProjection(size.x / size.y);
    const int n = 13;
    glm::vec3 centre(0.1f, -0.05f, -3.0f);
    std::vector<glm::vec4> rim;
    for (int i = 0; i < n; ++i) {
        float a = 6.2831853f * float(i) / float(n);
        rim.push_back(
            projection *
            glm::vec4(centre + glm::vec3(1.7f * std::cos(a), 1.2f * std::sin(a), 0.3f * std::sin(3.0f * a)), 1.0f));
    }
    glm::vec4 c = projection * glm::vec4(centre, 1.0f);
    auto screen = [&](glm::vec4 q) { return (glm::vec2(q) / q.w * 0.5f + 0.5f) * size; };
    // The reference: the projected fan in 2D, a sample well inside one of its triangles (a
    // thousandth of a pixel from every edge).
    auto wellInside = [&](glm::vec2 p) {
        for (int i = 0; i < n; ++i) {
            glm::vec2 a = screen(c), b = screen(rim[size_t(i)]), d = screen(rim[size_t((i + 1) % n)]);
            auto side = [&](glm::vec2 u, glm::vec2 v) { // signed distance of p from the edge u -> v
                glm::vec2 e = v - u;
                return (e.x * (p.y - u.y) - e.y * (p.x - u.x)) / glm::length(e);
            };
            float s0 = side(a, b), s1 = side(b, d), s2 = side(d, a);
            if ((s0 > 1e-3f && s1 > 1e-3f && s2 > 1e-3f) || (s0 < -1e-3f && s1 < -1e-3f && s2 < -1e-3f))
                return true;
        }
        return false;
    };
    size_t twice = 0, inside = 0, gaps = 0;
    for (int y = 0; y < int(size.y); ++y)
        for (int x = 0; x < int(size.x); ++x) {
            glm::vec2 pixel = glm::vec2(x, y) + 0.5f;
            int hits = 0;
            for (int i = 0; i < n; ++i) {
                gpu::MeshTriangle t = gpu::setupMeshTriangle(c, rim[size_t(i)], rim[size_t((i + 1) % n)], size);
                hits += gpu::meshSampleDepth(t, pixel, size) <= 1.0f ? 1 : 0;
            }
            inside += hits > 0 ? 1 : 0;
            twice += hits > 1 ? 1 : 0;
            gaps += hits == 0 && wellInside(pixel) ? 1 : 0;
        }
    EXPECT_EQ(gaps, 0u) << "samples inside the fan that no triangle covered";
    EXPECT_GT(inside, size_t(size.x * size.y) / 5);
    EXPECT_LE(twice, inside / 500) << "samples exactly on an edge count for both sides, nothing more";
}

TEST(RasterPieces, EveryPieceFitsTheBufferAndEveryPixelIsWholeInOne)
{
    // Pixels' fragment counts (mostly few, some many, runs of none), scanned as strands_scan.comp
    // scans them, split into pieces for buffers from ample to a few times the largest pixel, and
    // below it (a pixel holding more than half the buffer keeps what fits).
    std::mt19937 rng(7);
    for (int trial = 0; trial < 40; ++trial) {
        std::vector<uint32_t> counts(1 + rng() % 3000);
        for (uint32_t& c : counts) {
            uint32_t kind = uint32_t(rng() % 10);
            c = uint32_t(kind < 4 ? 0 : kind < 9 ? rng() % 12 : rng() % 400);
        }
        std::vector<uint32_t> offsets(counts.size() + 1, 0);
        std::partial_sum(counts.begin(), counts.end(), offsets.begin() + 1);
        uint32_t total = offsets.back();
        uint32_t most = *std::max_element(counts.begin(), counts.end());
        for (uint32_t capacity : {total + 5, total, std::max(total / 3, 1u), std::max(2 * most + 1, 2u),
                                  std::max(most, 2u), std::max(most / 2, 2u)}) {
            uint32_t stride = gpu::rasterPieceStride(total, capacity, most);
            uint32_t pieces = gpu::rasterPieces(total, stride);
            uint32_t cap = gpu::rasterPixelCap(capacity, stride);
            SCOPED_TRACE("trial " + std::to_string(trial) + ", capacity " + std::to_string(capacity));
            if (total <= capacity) {
                EXPECT_EQ(pieces, 1u) << "a frame that fits is one piece";
                EXPECT_EQ(cap, capacity);
            } else {
                EXPECT_GE(pieces, 2u);
                EXPECT_LE(uint64_t(pieces - 1) * stride, total) << "no piece past the last pixel's offset";
            }
            if (2 * most <= capacity) {
                EXPECT_GE(cap, most) << "no pixel loses fragments unless it holds more than half the buffer";
            }
            // Each piece's slots: inside the buffer, one fragment each.
            std::vector<std::vector<bool>> used(pieces, std::vector<bool>(capacity, false));
            for (size_t p = 0; p < counts.size(); ++p) {
                uint32_t piece = stride == gpu::kRasterOnePiece ? 0u : offsets[p] / stride;
                ASSERT_LT(piece, pieces) << "pixel " << p;
                uint32_t base = piece * (stride == gpu::kRasterOnePiece ? 0u : stride);
                for (uint32_t i = 0; i < std::min(counts[p], cap); ++i) {
                    uint32_t slot = offsets[p] + i - base;
                    ASSERT_LT(slot, capacity) << "pixel " << p << " fragment " << i;
                    ASSERT_FALSE(used[piece][slot]) << "pixel " << p << " fragment " << i;
                    used[piece][slot] = true;
                }
            }
        }
    }
}

TEST(RasterPieces, LinearGroupsCoverEveryItemWithinTheDispatchLimit)
{
    for (uint32_t items : {0u, 1u, 64u, 65u, 65535u * 64u, 65535u * 64u + 1u, 123456789u, 0xffffffffu}) {
        glm::uvec2 g = gpu::rasterLinearGroups(items, 64);
        EXPECT_LE(g.x, 65535u) << items;
        EXPECT_GE(uint64_t(g.x) * g.y * 64, items) << items;
        EXPECT_LT(uint64_t(g.x) * (g.y > 0 ? g.y - 1 : 0) * 64, std::max<uint64_t>(items, 1))
            << "no empty row " << items;
        EXPECT_EQ(items == 0, g.x == 0 && g.y == 0) << items;
    }
}
