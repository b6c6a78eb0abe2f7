// tests/test_growth.cpp: the groom generator (physics/scalp.h, physics/growth.h, physics/hair_style.h)
// step by step against its definitions on small cases, then whole grooms on the default head: roots
// only inside the scalp field and thinning across the hairline band, the flow's parting and
// tangency, determinism for a seed, every style, and the errors for contradictory parameters.
#include "assets/head.h"
#include "core/error.h"
#include "physics/colliders.h"
#include "physics/groomed_head.h"
#include "physics/growth.h"
#include "physics/hair_style.h"
#include "shaders/shared/strands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace wisp;

namespace {

constexpr float kPi = 3.14159265f;

const GroomedHead& defaultHeadOnly()
{
    static const GroomedHead scene = [] {
        GrowthSettings g;
        g.guides = 8;
        return buildGrownHead(defaultHeadPath(), g);
    }();
    return scene;
}

ScalpField defaultField(float band = 0.012f)
{
    const GroomedHead& scene = defaultHeadOnly();
    return makeScalpField(scene.scalp, scene.unitsPerMetre, band, 0.09f);
}

std::vector<glm::vec3> straightLine(glm::vec3 from, glm::vec3 step, int count)
{
    std::vector<glm::vec3> out;
    for (int i = 0; i < count; ++i)
        out.push_back(from + float(i) * step);
    return out;
}

// Distance of p from the line through a along unit d.
float fromAxis(glm::vec3 p, glm::vec3 a, glm::vec3 d)
{
    glm::vec3 v = p - a;
    return glm::length(v - glm::dot(v, d) * d);
}

} // namespace

// ---- 1. The scalp field and the roots ---------------------------------------------------------

TEST(ScalpField, IsASmoothSignedDistanceAcrossTheHairline)
{
    ScalpField f = defaultField();
    const ScalpRule& rule = f.rule;
    // Straight above the plane, facing away from the face: inside, density 1 deep in.
    glm::vec3 up = rule.planeNormal;
    glm::vec3 back = -rule.faceDirection;
    EXPECT_GT(f.distance(rule.planePoint + 0.05f * up, back), 0.0f);
    EXPECT_FLOAT_EQ(f.density(rule.planePoint + 0.05f * up, back), 1.0f);
    EXPECT_LT(f.distance(rule.planePoint - 0.05f * up, back), 0.0f);
    EXPECT_FLOAT_EQ(f.density(rule.planePoint - 0.05f * up, back), 0.0f);
    // Facing the face: outside however high.
    EXPECT_LT(f.distance(rule.planePoint + 0.05f * up, rule.faceDirection), 0.0f);
    // Across the band the density rises smoothly and monotonically; the paint leads it.
    float previous = -1.0f;
    for (int i = 0; i <= 40; ++i) {
        float h = -0.01f + 0.035f * float(i) / 40.0f;
        glm::vec3 p = rule.planePoint + h * up;
        float d = f.density(p, back);
        EXPECT_GE(d, previous);
        EXPECT_GE(f.paint(p, back), d);
        if (i > 0) {
            EXPECT_LT(d - previous, 0.15f) << "no jump at " << h;
        }
        previous = d;
    }
}

TEST(ScalpField, RootsLieInsideTheFieldAndThinAcrossTheBand)
{
    const GroomedHead& scene = defaultHeadOnly();
    const Mesh& mesh = scene.head.mesh;
    ScalpField f = defaultField();
    std::vector<RootSample> roots = sampleScalpRoots(mesh, f, 6000, true, 3);
    ASSERT_EQ(roots.size(), 6000u);
    // The area at each distance from the hairline, from plain uniform samples over the head.
    std::vector<uint32_t> all(mesh.triangleCount());
    for (uint32_t t = 0; t < all.size(); ++t)
        all[t] = t;
    std::vector<RootSample> uniform = sampleRoots(mesh, all, 200000, false, 5);
    auto bin = [&](const RootSample& r) {
        float d = f.distance(r.position, r.normal) / f.bandWidth;
        return d <= 0.0f ? -1 : d < 1.0f / 3.0f ? 0 : d < 2.0f / 3.0f ? 1 : d < 1.0f ? 2 : d < 3.0f ? 3 : -1;
    };
    double rootsIn[4] = {}, areaIn[4] = {};
    for (const RootSample& r : roots) {
        ASSERT_GT(f.distance(r.position, r.normal), 0.0f) << "a root outside the hairline";
        ASSERT_GT(r.density, 0.0f);
        if (int b = bin(r); b >= 0)
            rootsIn[b] += 1.0;
    }
    for (const RootSample& r : uniform)
        if (int b = bin(r); b >= 0)
            areaIn[b] += 1.0;
    double perArea[4];
    for (int b = 0; b < 4; ++b) {
        ASSERT_GT(areaIn[b], 100.0);
        perArea[b] = rootsIn[b] / areaIn[b];
    }
    // Relative to the full density just inside the band (a band's width in): the smoothstep's mean
    // over each third is 0.07, 0.5 and 0.93.
    EXPECT_LT(perArea[0] / perArea[3], 0.25);
    EXPECT_GT(perArea[1] / perArea[3], 0.3);
    EXPECT_LT(perArea[1] / perArea[3], 0.7);
    EXPECT_GT(perArea[2] / perArea[3], 0.75);
    EXPECT_LT(perArea[0], perArea[1]);
    EXPECT_LT(perArea[1], perArea[2]);
}

TEST(ScalpField, RootsAreInsideTrianglesNotOnTheirEdges)
{
    // Roots fall anywhere inside the scalp's triangles, not on whole triangles (a sawtooth along the
    // hairline), so a triangle cut by the hairline holds roots on its inner side only.
    const GroomedHead& scene = defaultHeadOnly();
    ScalpField f = defaultField();
    std::vector<RootSample> roots = sampleScalpRoots(scene.head.mesh, f, 3000, true, 9);
    size_t partial = 0;
    for (const RootSample& r : roots) {
        const Mesh& m = scene.head.mesh;
        uint32_t t = r.triangle;
        float lowest = 1e9f;
        for (int k = 0; k < 3; ++k)
            lowest = std::min(lowest, f.distance(m.positions[m.indices[3 * t + k]], m.normals[m.indices[3 * t + k]]));
        partial += lowest < 0.0f ? 1 : 0; // a triangle the hairline crosses
    }
    EXPECT_GT(partial, 0u) << "roots in triangles the hairline crosses";
}

TEST(ScalpField, AHeadWithNoScalpSaysSo)
{
    const GroomedHead& scene = defaultHeadOnly();
    ScalpRule above = scene.scalp;
    above.planePoint = glm::vec3(0.0f, 10.0f, 0.0f); // the plane far above the head
    above.planeNormal = glm::vec3(0.0f, 1.0f, 0.0f);
    ScalpField f = makeScalpField(above, 1.0f, 0.012f, 0.09f);
    try {
        sampleScalpRoots(scene.head.mesh, f, 10, true, 1);
        FAIL() << "no error";
    } catch (const UserError& e) {
        EXPECT_NE(std::string(e.what()).find("no usable scalp"), std::string::npos) << e.what();
    }
}

TEST(ScalpField, ABareMeshsAutomaticHairlineCoversTheHeadAsItsDescriptionDoes)
{
    // The default head's mesh given alone gets a rule from its fitted cranium
    // (defaultScalpRule): its scalp should be about the hand-written rule's, reaching as far over
    // the forehead (the first automatic rule left the front third of the top bald: its face rule
    // took in every normal within 70 degrees of the front).
    GrowthSettings g;
    g.guides = 400;
    GroomedHead described = buildGrownHead(defaultHeadPath(), g);
    GroomedHead bare = buildGrownHead(defaultHeadPath().parent_path() / "head.obj", g);
    ASSERT_TRUE(bare.collidersFitted);
    auto area = [](const GroomedHead& s) {
        return scalpArea(s.head.mesh, makeScalpField(s.scalp, s.unitsPerMetre, 0.012f, 0.09f));
    };
    double ratio = area(bare) / area(described);
    EXPECT_GT(ratio, 0.8) << "the automatic scalp is much smaller than the described one";
    EXPECT_LT(ratio, 1.25) << "the automatic scalp reaches over the face or the neck";
    auto frontmost = [](const GroomedHead& s) {
        float z = -1e30f;
        for (size_t k = 0; k < s.strands.strandCount(); ++k)
            z = std::max(z, s.strands.rest[k * s.strands.verticesPerStrand].z);
        return z;
    };
    EXPECT_NEAR(frontmost(bare), frontmost(described), 0.015f) << "the roots reach the forehead";
}

// ---- 2. Flow ----------------------------------------------------------------------------------

TEST(GroomFlow, HairIsCombedAwayFromTheSideParting)
{
    const GroomedHead& scene = defaultHeadOnly();
    GrowthSettings s;
    s.parting = Parting::Side;
    s.partingOffsetMetres = 0.03f;
    s.crownWhorl = 0.0f;
    groom::HeadFrame head;
    head.centre = scene.gpuColliders.front().center;
    head.crown = head.centre + glm::vec3(0.0f, 0.08f, -0.06f);
    head.top = scene.head.mesh.bounds().max.y;
    ScalpField f = defaultField();
    std::vector<RootSample> roots = sampleScalpRoots(scene.head.mesh, f, 3000, true, 4);
    size_t left = 0, right = 0;
    for (const RootSample& r : roots) {
        glm::vec3 flow = groom::flowDirection(s, head, r.position, r.normal);
        ASSERT_NEAR(glm::length(flow), 1.0f, 1e-4f);
        ASSERT_LT(std::abs(glm::dot(flow, r.normal)), 1e-4f) << "the flow lies in the scalp's tangent plane";
        // On top, in front of the crown, more than a centimetre from the parting.
        if (r.position.y < head.centre.y + 0.07f || r.position.z < head.crown.z + 0.03f)
            continue;
        if (r.position.x > 0.03f + 0.01f) {
            EXPECT_GT(flow.x, 0.0f) << "left of the parting combs left";
            ++left;
        } else if (r.position.x < 0.03f - 0.01f) {
            EXPECT_LT(flow.x, 0.0f) << "right of the parting combs right";
            ++right;
        }
    }
    EXPECT_GT(left, 10u);
    EXPECT_GT(right, 3u * left / 2) << "the side parting leaves more hair on the far side";
}

// The parting's edges: rows of roots either side of its line leave the scalp showing as a thin line.
// Along the parting, in 5 mm slices, the nearest root on each side of the line is within 1.2 mm of it
// with the rows, and blue noise alone leaves a gap several times wider.
TEST(GroomFlow, ThePartingsEdgesAreRowsOfRootsCloseToItsLine)
{
    const GroomedHead& scene = defaultHeadOnly();
    GrowthSettings s; // the bob: a side parting
    groom::HeadFrame head;
    head.centre = scene.gpuColliders.front().center;
    head.crown = head.centre + glm::vec3(0.0f, 0.08f, -0.06f);
    head.skullRadius = 0.09f;
    head.top = scene.head.mesh.bounds().max.y;
    ScalpField f = defaultField();
    const uint32_t count = 2200;
    float offset = 0.35f * rootSpacing(scalpArea(scene.head.mesh, f), count);
    float line = groom::partingX(s, head);
    std::vector<RootRow> rows;
    for (float sign : {-1.0f, 1.0f})
        rows.push_back(planeRow(glm::vec3(line + sign * offset, 0.0f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f),
                                [&](const glm::vec3& p) { return groom::partingReach(head, p) > 0.5f; }));
    // The widest gap between the line and its nearest root on either side, over the slices.
    auto widestGap = [&](const std::vector<RootSample>& roots) {
        float widest = 0.0f;
        int slices = 0;
        for (float z = -0.1f; z < 0.15f; z += 0.005f) {
            float nearest[2] = {1e30f, 1e30f};
            bool reached = false;
            for (const RootSample& r : roots) {
                if (r.position.z < z || r.position.z >= z + 0.005f || std::abs(r.position.x - line) > 0.02f)
                    continue;
                reached = reached || groom::partingReach(head, r.position) > 0.9f;
                float d = r.position.x - line;
                nearest[d >= 0.0f] = std::min(nearest[d >= 0.0f], std::abs(d));
            }
            if (!reached || nearest[0] > 0.02f || nearest[1] > 0.02f)
                continue; // off the parting's reach, or past the scalp's edge
            widest = std::max({widest, nearest[0], nearest[1]});
            ++slices;
        }
        EXPECT_GT(slices, 10) << "the parting runs over the top of the head";
        return widest;
    };
    std::vector<RootSample> withRows = sampleScalpRoots(scene.head.mesh, f, count, true, 4, rows);
    std::vector<RootSample> without = sampleScalpRoots(scene.head.mesh, f, count, true, 4);
    ASSERT_EQ(withRows.size(), count);
    EXPECT_LT(widestGap(withRows), 0.0012f);
    EXPECT_GT(widestGap(without), 3.0f * widestGap(withRows));
    // A parting's rows take their share of the roots, not more: the rest is blue noise.
    size_t onRows = 0;
    for (const RootSample& r : withRows)
        onRows += std::abs(std::abs(r.position.x - line) - offset) < 1e-5f ? 1 : 0;
    EXPECT_GT(onRows, 40u);
    EXPECT_LT(onRows, count / 4);
}

// The bangs' edge, where the front combed forward meets the rest combed back: a row of roots each
// side of it leaves a thin line there too (blue noise alone left a bald band across the head, the
// two sides' strands leaving it in opposite directions). Around the edge, in slices of its angle
// about the bangs' axis, the nearest root on each side is within 1.5 mm of it (blue noise alone:
// farther in most slices).
TEST(GroomFlow, TheBangsEdgeIsRowsOfRootsCloseToIt)
{
    const GroomedHead& scene = defaultHeadOnly();
    groom::HeadFrame head;
    head.centre = scene.gpuColliders.front().center;
    head.skullRadius = 0.09f;
    ScalpField f = defaultField();
    const uint32_t count = 2200;
    float offset = 0.35f * rootSpacing(scalpArea(scene.head.mesh, f), count);
    glm::vec3 axis = glm::normalize(glm::vec3(0.0f, 0.45f, 1.0f));
    std::vector<RootRow> rows;
    for (float sign : {-1.0f, 1.0f}) {
        RootRow row;
        row.level = [&, sign](const glm::vec3& p) { return groom::bangsEdgeDistance(head, p) - sign * offset; };
        row.axis = axis;
        rows.push_back(std::move(row));
    }
    glm::vec3 e1 = glm::normalize(glm::vec3(0.0f, 1.0f, 0.0f) - axis.y * axis);
    glm::vec3 e2 = glm::cross(axis, e1);
    // Each slice's gap: the farther of the nearest roots either side of the edge.
    auto gaps = [&](const std::vector<RootSample>& roots) {
        std::vector<float> out;
        for (float a = -1.5f; a < 1.5f; a += 0.1f) {
            float nearest[2] = {1e30f, 1e30f};
            for (const RootSample& r : roots) {
                glm::vec3 d = r.position - head.centre;
                float angle = std::atan2(glm::dot(d, e2), glm::dot(d, e1));
                float edge = groom::bangsEdgeDistance(head, r.position);
                if (angle < a || angle >= a + 0.1f || std::abs(edge) > 0.02f || r.density < 0.9f)
                    continue;
                nearest[edge >= 0.0f] = std::min(nearest[edge >= 0.0f], std::abs(edge));
            }
            if (nearest[0] <= 0.02f && nearest[1] <= 0.02f) // else past the scalp's edge
                out.push_back(std::max(nearest[0], nearest[1]));
        }
        EXPECT_GT(out.size(), 8u) << "the edge runs across the top of the head";
        return out;
    };
    auto wide = [](const std::vector<float>& g) {
        return std::count_if(g.begin(), g.end(), [](float x) { return x > 0.0015f; });
    };
    std::vector<float> withRows = gaps(sampleScalpRoots(scene.head.mesh, f, count, true, 4, rows));
    std::vector<float> without = gaps(sampleScalpRoots(scene.head.mesh, f, count, true, 4));
    // (At most the two slices where the edge meets the hairline, and the rows thin out with the density.)
    EXPECT_LE(wide(withRows), 2);
    EXPECT_GT(wide(without), long(without.size() / 2));
    // And the grown bangs style combs the two sides apart: forward in front of the edge, back behind.
    GrowthSettings s;
    applyHairStyle(s, *findHairStyle("bangs"));
    int forward = 0, back = 0, front = 0, behind = 0;
    for (const RootSample& r : sampleScalpRoots(scene.head.mesh, f, count, true, 4, rows)) {
        float edge = groom::bangsEdgeDistance(head, r.position);
        if (std::abs(edge) > 0.004f || std::abs(edge) < 0.002f)
            continue;
        head.crown = head.centre + glm::vec3(0.0f, 0.08f, -0.06f);
        head.top = scene.head.mesh.bounds().max.y;
        float z = groom::flowDirection(s, head, r.position, r.normal).z;
        (edge > 0.0f ? front : behind) += 1;
        (edge > 0.0f ? forward : back) += (edge > 0.0f ? z > 0.3f : z < 0.3f) ? 1 : 0;
    }
    EXPECT_GT(front, 5);
    EXPECT_GT(behind, 5);
    EXPECT_EQ(forward, front) << "every strand just in front of the edge is combed forward";
    EXPECT_EQ(back, behind) << "no strand just behind it is";
}

TEST(GroomFlow, StrandsLeaveTheScalpNearTangentAtTheRootLiftLowerAtTheHairline)
{
    const GroomedHead& scene = defaultHeadOnly();
    for (float lift : {5.0f, 12.0f, 30.0f}) {
        GrowthSettings s;
        s.rootLiftDeg = lift;
        groom::HeadFrame head;
        head.centre = scene.gpuColliders.front().center;
        head.crown = head.centre + glm::vec3(0.0f, 0.08f, -0.06f);
        head.top = scene.head.mesh.bounds().max.y;
        std::vector<RootSample> roots = sampleScalpRoots(scene.head.mesh, defaultField(), 200, true, 2);
        std::vector<float> angles;
        for (const RootSample& r : roots) {
            std::vector<glm::vec3> line = groom::growCentreline(s, head, scene.gpuColliders, r, 0.05f, 0.00025f);
            glm::vec3 first = glm::normalize(line[1] - line[0]);
            // At the hairline the lift falls to 0.35 of the setting with the roots' density.
            float expected = lift * (0.35f + 0.65f * r.density);
            angles.push_back(glm::degrees(std::asin(std::clamp(glm::dot(first, r.normal), -1.0f, 1.0f))) - expected);
            EXPECT_NEAR(groom::polylineLength(line), 0.05f, 1e-4f);
        }
        // The first step leaves at the root lift, but for the few roots where the head's mesh and its
        // colliders disagree by a fraction of a millimetre (the push-out tilts a quarter-millimetre step).
        std::sort(angles.begin(), angles.end());
        EXPECT_NEAR(angles[angles.size() / 2], 0.0f, 2.0f);
        EXPECT_GT(angles[angles.size() / 10], -5.0f);
        EXPECT_LT(angles[angles.size() * 9 / 10], 12.0f);
    }
}

// ---- 3-6. The shaping steps against their definitions -----------------------------------------

TEST(GroomSteps, TrimCutsWhereTheStrandFallsBelowTheLine)
{
    GrowthSettings s;
    s.trimLevelMetres = 0.1f;
    s.trimSlope = 0.0f;
    groom::HeadFrame head;
    head.top = 0.25f;
    std::vector<glm::vec3> line = straightLine({0, 0.25f, 0}, {0, -0.005f, 0}, 61); // 0.3 long, straight down
    groom::trim(line, s, head, 0.0f, 0.03f);
    EXPECT_NEAR(line.back().y, 0.15f, 0.0051f);
    // A slope lowers the line toward the face.
    s.trimSlope = 0.5f;
    std::vector<glm::vec3> front = straightLine({0, 0.25f, 0.1f}, {0, -0.005f, 0}, 61);
    groom::trim(front, s, head, 0.0f, 0.03f);
    EXPECT_NEAR(front.back().y, 0.10f, 0.0051f);
}

TEST(GroomSteps, TrimJitterIsASlowWaveAlongTheHemAndEachStrandsOwn)
{
    GrowthSettings s;
    s.trimJitterMetres = 0.016f;
    groom::HeadFrame head;
    head.centre = {0.0f, 0.14f, 0.0f};
    // Roots around the back of the head, with no strand's own share: the wave alone, within half
    // the spread, the same for the same root and seed, slow (neighbours a degree apart differ by
    // little) but not constant along the hem (a ruled line).
    float lowest = 1.0f, highest = -1.0f, steepest = 0.0f, previous = 0.0f;
    for (int i = 0; i <= 180; ++i) {
        float a = glm::radians(90.0f + float(i)); // from the head's left round the back to its right
        glm::vec3 root = head.centre + 0.09f * glm::vec3(std::cos(a), 0.0f, std::sin(a));
        float j = groom::trimJitter(s, head, root, 0.0f);
        EXPECT_LE(std::abs(j), 0.5f * s.trimJitterMetres + 1e-6f);
        EXPECT_EQ(j, groom::trimJitter(s, head, root, 0.0f));
        if (i > 0)
            steepest = std::max(steepest, std::abs(j - previous));
        previous = j;
        lowest = std::min(lowest, j);
        highest = std::max(highest, j);
    }
    EXPECT_GT(highest - lowest, 0.3f * s.trimJitterMetres) << "the hem is not ruled";
    EXPECT_LT(steepest, 0.05f * s.trimJitterMetres) << "a slow wave, not noise";
    // Each strand's own share adds up to the other half; none at all without a spread.
    glm::vec3 back = head.centre + glm::vec3(0.0f, 0.0f, -0.09f);
    EXPECT_NEAR(groom::trimJitter(s, head, back, 1.0f) - groom::trimJitter(s, head, back, -1.0f), s.trimJitterMetres,
                1e-6f);
    s.trimJitterMetres = 0.0f;
    EXPECT_EQ(groom::trimJitter(s, head, back, 1.0f), 0.0f);
}

TEST(GroomSteps, ClumpRadiusShrinksTowardTheTips)
{
    // Strands 1 cm around a straight centre: each point moves strength * t^shape of the way.
    std::vector<glm::vec3> centre = straightLine({0, 0, 0}, {0, -0.01f, 0}, 31);
    for (float shape : {1.0f, 2.0f}) {
        float previous = 1e9f;
        for (int k = 0; k < 8; ++k) {
            float a = 2.0f * kPi * float(k) / 8.0f;
            glm::vec3 offset(0.01f * std::cos(a), 0.0f, 0.01f * std::sin(a));
            std::vector<glm::vec3> strand = straightLine(offset, {0, -0.01f, 0}, 31);
            groom::clump(strand, centre, 0.6f, shape);
            for (int i = 0; i <= 30; i += 10) {
                float t = float(i) / 30.0f;
                float expected = 0.01f * (1.0f - 0.6f * std::pow(t, shape));
                EXPECT_NEAR(fromAxis(strand[i], {0, 0, 0}, {0, -1, 0}), expected, 1e-5f);
            }
            previous = std::min(previous, fromAxis(strand.back(), {0, 0, 0}, {0, -1, 0}));
        }
        EXPECT_NEAR(previous, 0.004f, 1e-5f) << "the tips gather to 40% of the radius";
    }
}

TEST(GroomSteps, CurlHasTheRadiusAndTurnsAsSet)
{
    for (float turns : {1.0f, 3.0f, 7.5f}) {
        std::vector<glm::vec3> line = straightLine({0, 0, 0}, {0, -0.001f, 0}, 201); // 0.2 long
        groom::curl(line, 0.006f, turns, 0.3f, 0.015f);
        // Past the ramp every point is the radius from the axis.
        for (size_t i = 20; i < line.size(); ++i)
            ASSERT_NEAR(fromAxis(line[i], {0, 0, 0}, {0, -1, 0}), 0.006f, 1e-5f);
        // The winding angle around the axis, past the ramp, is 2 pi turns over that length.
        double wound = 0.0;
        for (size_t i = 21; i < line.size(); ++i) {
            glm::vec2 a(line[i - 1].x, line[i - 1].z), b(line[i].x, line[i].z);
            wound += std::atan2(double(a.x * b.y - a.y * b.x), double(glm::dot(a, b)));
        }
        double expected = 2.0 * 3.14159265 * turns * (200.0 - 20.0) / 200.0;
        EXPECT_NEAR(std::abs(wound), expected, 0.02 * expected);
    }
}

TEST(GroomSteps, WaveAndFrizzStayWithinTheirAmplitudes)
{
    std::vector<glm::vec3> line = straightLine({0, 0, 0}, {0, -0.001f, 0}, 301);
    std::vector<glm::vec3> waved = line;
    groom::wave(waved, {1, 0, 0}, 0.01f, 0.05f, 0.0f);
    float most = 0.0f;
    for (size_t i = 0; i < line.size(); ++i) {
        EXPECT_NEAR(waved[i].z, 0.0f, 1e-6f) << "the wave stays in its plane";
        most = std::max(most, std::abs(waved[i].x));
    }
    EXPECT_NEAR(most, 0.01f, 2e-4f);
    std::vector<glm::vec3> frizzed = line;
    groom::frizz(frizzed, 0.004f, 0.02f, 7);
    float nearRoot = 0.0f, nearTip = 0.0f;
    for (size_t i = 0; i < line.size(); ++i) {
        float d = glm::length(frizzed[i] - line[i]);
        float t = float(i) / 300.0f;
        EXPECT_LE(d, 0.004f * t * t * std::sqrt(3.0f) + 1e-6f);
        (t < 0.3f ? nearRoot : nearTip) = std::max(t < 0.3f ? nearRoot : nearTip, d);
    }
    EXPECT_GT(nearTip, 4.0f * nearRoot) << "frizz grows toward the tips";
}

TEST(GroomSteps, ResampleSpacesPointsEvenlyAlongTheCurve)
{
    std::vector<glm::vec3> line = straightLine({0, 0, 0}, {0, -0.001f, 0}, 101);
    groom::curl(line, 0.01f, 2.0f, 0.0f, 0.01f);
    std::vector<glm::vec3> out = groom::resample(line, 16);
    ASSERT_EQ(out.size(), 16u);
    EXPECT_EQ(out.front(), line.front());
    EXPECT_NEAR(glm::length(out.back() - line.back()), 0.0f, 1e-6f);
    float total = groom::polylineLength(line);
    for (size_t i = 1; i < out.size(); ++i)
        EXPECT_LE(glm::length(out[i] - out[i - 1]), total / 15.0f + 1e-6f);
}

// ---- Whole grooms -----------------------------------------------------------------------------

TEST(Groom, DeterministicForASeedAndDifferentForAnother)
{
    for (const HairStyle& style : hairStyles()) {
        GrowthSettings g;
        applyHairStyle(g, style);
        g.guides = 60;
        StrandSet a = buildGrownHead(defaultHeadPath(), g).strands;
        StrandSet b = buildGrownHead(defaultHeadPath(), g).strands;
        ASSERT_EQ(a.rest, b.rest) << style.name;
        g.seed = 2;
        StrandSet c = buildGrownHead(defaultHeadPath(), g).strands;
        EXPECT_NE(a.rest, c.rest) << style.name;
        EXPECT_EQ(a.strandCount(), 60u);
        EXPECT_EQ(a.verticesPerStrand, style.growth.verticesPerStrand);
    }
}

TEST(Groom, GrownStrandsStayOutsideTheCollidersAndThePaintFollowsTheField)
{
    GrowthSettings g;
    g.guides = 400;
    GroomedHead scene = buildGrownHead(defaultHeadPath(), g);
    const StrandSet& s = scene.strands;
    uint32_t V = s.verticesPerStrand;
    size_t inside = 0, free = 0;
    for (size_t k = 0; k < s.strandCount(); ++k) {
        float run = 0.0f;
        for (uint32_t i = 1; i < V; ++i) {
            run += glm::length(s.rest[k * V + i] - s.rest[k * V + i - 1]);
            if (run < 0.04f)
                continue; // within the root's reach, as deep as the root may be
            ++free;
            for (const gpu::Ellipsoid& e : scene.gpuColliders)
                inside += gpu::ellipsoidContact(e, s.rest[k * V + i], 0.0f).depth > 0.001f ? 1 : 0;
        }
    }
    EXPECT_LT(double(inside) / double(free), 0.01);
    // The painted scalp: every head vertex, 0..1, with a soft border (values strictly between).
    ASSERT_EQ(s.scalpPaint.size(), scene.head.mesh.positions.size());
    size_t soft = 0, full = 0;
    for (float p : s.scalpPaint) {
        ASSERT_GE(p, 0.0f);
        ASSERT_LE(p, 1.0f);
        soft += p > 0.05f && p < 0.95f ? 1 : 0;
        full += p >= 0.95f ? 1 : 0;
    }
    EXPECT_GT(soft, full / 20) << "a gradient at the hairline, not a hard border";
}

TEST(Groom, HairlineHairsAreFinerAsTheyAreShorter)
{
    // Each grown strand's width share is hairline_width at the field's zero and 1 inside the band:
    // the share follows the root's density (read back from the field at the root), and the roots
    // across the band make a spread of widths, not two values.
    GrowthSettings g;
    g.guides = 600;
    g.hairlineWidth = 0.3f;
    GroomedHead scene = buildGrownHead(defaultHeadPath(), g);
    const StrandSet& s = scene.strands;
    ASSERT_EQ(s.widthScale.size(), s.strandCount());
    ScalpField field = defaultField(g.hairlineBandMetres);
    size_t fine = 0;
    for (size_t k = 0; k < s.strandCount(); ++k) {
        glm::vec3 root = s.rest[k * s.verticesPerStrand];
        float density = field.density(root, glm::normalize(root - scene.gpuColliders.front().center));
        EXPECT_GE(s.widthScale[k], 0.3f - 1e-6f) << k;
        EXPECT_LE(s.widthScale[k], 1.0f) << k;
        EXPECT_NEAR(s.widthScale[k], 0.3f + 0.7f * density, 0.12f) << k;
        fine += s.widthScale[k] < 0.8f ? 1 : 0;
    }
    EXPECT_GT(fine, s.strandCount() / 100) << "some hairs at the hairline are finer";
    EXPECT_LT(fine, s.strandCount() / 4) << "most hairs are of full width";
    // The renderer reads the share from the guide's triangle, beside its length.
    std::vector<glm::uvec4> tri = guideTriangles(s);
    for (size_t k = 0; k < s.strandCount(); k += 37)
        EXPECT_NEAR(gpu::guideWidthScale(tri[k].w), s.widthScale[k], 1e-3f) << k;
}

TEST(Groom, StylesAreSettingsAndTheDefaultIsTheBob)
{
    ASSERT_NE(findHairStyle("bob"), nullptr);
    EXPECT_TRUE(isHairStyle(GrowthSettings{}, *findHairStyle("bob")));
    for (const char* name : {"long", "wavy", "crop", "bangs", "afro"}) {
        const HairStyle* style = findHairStyle(name);
        ASSERT_NE(style, nullptr) << name;
        GrowthSettings g;
        g.seed = 42;
        applyHairStyle(g, *style);
        EXPECT_EQ(g.seed, 42u) << "a style keeps the seed";
        EXPECT_TRUE(isHairStyle(g, *style));
        EXPECT_FALSE(isHairStyle(g, *findHairStyle("bob")));
        g.frizzMetres += 0.001f;
        EXPECT_FALSE(isHairStyle(g, *style)) << "a changed parameter makes it custom";
    }
    EXPECT_EQ(findHairStyle("mohawk"), nullptr);
    // The afro coils: its strands wind around their own course.
    GrowthSettings afro;
    applyHairStyle(afro, *findHairStyle("afro"));
    EXPECT_GT(afro.curlRadiusMetres, 0.0f);
    EXPECT_GE(afro.verticesPerStrand, 4.0f * afro.curlTurns);
}

TEST(Groom, ContradictoryParametersAreRefused)
{
    GrowthSettings g;
    g.curlRadiusMetres = 0.005f;
    g.curlTurns = 10.0f;
    g.verticesPerStrand = 16;
    try {
        checkGrowth(g);
        FAIL() << "no error";
    } catch (const UserError& e) {
        EXPECT_NE(std::string(e.what()).find("vertices_per_strand"), std::string::npos) << e.what();
    }
    g.verticesPerStrand = 64;
    EXPECT_NO_THROW(checkGrowth(g));
    GrowthSettings t;
    t.trimLevelMetres = 0.01f;
    EXPECT_THROW(checkGrowth(t), UserError);
}

TEST(Groom, BangsAreShortAndInFront)
{
    GrowthSettings g;
    applyHairStyle(g, *findHairStyle("bangs"));
    g.guides = 800;
    GroomedHead scene = buildGrownHead(defaultHeadPath(), g);
    const StrandSet& s = scene.strands;
    uint32_t V = s.verticesPerStrand;
    glm::vec3 centre = scene.gpuColliders.front().center;
    size_t forward = 0;
    for (size_t k = 0; k < s.strandCount(); ++k) {
        glm::vec3 root = s.rest[k * V], tip = s.rest[k * V + V - 1];
        if (root.z - centre.z > 0.06f && root.y > centre.y + 0.02f) { // roots at the front hairline
            forward += tip.z > root.z - 0.01f ? 1 : 0;
            float length = 0.0f;
            for (uint32_t i = 1; i < V; ++i)
                length += glm::length(s.rest[k * V + i] - s.rest[k * V + i - 1]);
            EXPECT_LT(length, 0.2f);
        }
    }
    EXPECT_GT(forward, 10u) << "the front's hair falls forward over the forehead";
}

TEST(Groom, InterpolationDoesNotBridgeAParting)
{
    // Two rows of guides 4 mm apart, combed away from each other (a parting): a guide's neighbours
    // for multi-strand interpolation are on its own side, so no strand is drawn across the gap.
    StrandSet set;
    set.verticesPerStrand = 7;
    set.parts.push_back({});
    for (int side = -1; side <= 1; side += 2)
        for (int k = 0; k < 6; ++k) {
            glm::vec3 root(0.002f * float(side), 0.0f, 0.005f * float(k));
            std::vector<glm::vec3> points;
            for (int i = 0; i < 7; ++i)
                points.push_back(root + float(i) * glm::vec3(0.02f * float(side), -0.01f, 0.0f));
            set.add(points, 0, 1, false);
        }
    std::vector<glm::uvec4> tri = guideTriangles(set);
    for (uint32_t s = 0; s < tri.size(); ++s) {
        bool left = s < 6;
        EXPECT_EQ(tri[s].y < 6, left) << s;
        EXPECT_EQ(tri[s].z < 6, left) << s;
    }
}
