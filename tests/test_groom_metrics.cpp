// tests/test_groom_metrics.cpp: the groom's figures (physics/groom_metrics.h) on hand-made cases:
// the side standoff of a box head with strands a known distance behind and before it (in metres
// and in centimetres, segments with no vertex in a row counted, rows without hair left out), and
// the tip lag meter against tips that turn with the head, stay behind, or follow half way.
#include "physics/groom_metrics.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace wisp;

namespace {

// A closed box from `lo` to `hi`, 12 triangles.
Mesh boxMesh(glm::vec3 lo, glm::vec3 hi)
{
    Mesh m;
    for (int k = 0; k < 8; ++k)
        m.positions.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
    m.normals.assign(8, glm::vec3(0.0f, 1.0f, 0.0f));
    const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads)
        for (uint32_t i : {q[0], q[1], q[2], q[0], q[2], q[3]})
            m.indices.push_back(i);
    return m;
}

// A head 20 cm tall (y 0 .. 0.2), 20 cm deep (z -0.1 .. 0.1), 16 cm wide, in metres times `scale`.
Mesh boxHead(float scale)
{
    return boxMesh(scale * glm::vec3(-0.08f, 0.0f, -0.1f), scale * glm::vec3(0.08f, 0.2f, 0.1f));
}

// A straight strand of `V` points from `a` to `b`.
void addStrand(std::vector<glm::vec3>& out, glm::vec3 a, glm::vec3 b, uint32_t V)
{
    for (uint32_t i = 0; i < V; ++i)
        out.push_back(glm::mix(a, b, float(i) / float(V - 1)));
}

} // namespace

TEST(GroomMetrics, SideStandoffOfHairBehindABoxHead)
{
    for (float scale : {1.0f, 100.0f}) { // metres and centimetres: the rows follow unitsPerMetre
        Mesh head = boxHead(scale);
        std::vector<glm::vec3> hair;
        // Down the back, 3 cm behind it, over every row (and past them: the rows end 12 cm down).
        addStrand(hair, scale * glm::vec3(0.0f, 0.21f, -0.13f), scale * glm::vec3(0.0f, 0.0f, -0.13f), 8);
        SideStandoff s = sideStandoff(head, hair, 8, scale);
        EXPECT_EQ(s.rows, kSideStandoffRows) << scale;
        EXPECT_NEAR(s.headWidth, 0.2 * scale, 1e-5 * scale);
        EXPECT_NEAR(s.meanBeyond, 0.03 * scale, 1e-5 * scale);
        EXPECT_NEAR(s.value, 0.15, 1e-4) << scale;

        // And 1 cm before the face: 3 + 1 cm beyond in every row.
        addStrand(hair, scale * glm::vec3(0.0f, 0.2f, 0.11f), scale * glm::vec3(0.0f, 0.05f, 0.11f), 8);
        EXPECT_NEAR(sideStandoff(head, hair, 8, scale).value, 0.2, 1e-4) << scale;
    }
}

TEST(GroomMetrics, SideStandoffCountsSegmentsNotJustVertices)
{
    Mesh head = boxHead(1.0f);
    // Two points, both outside the rows: one segment from above the head to below the rows, 2 cm
    // behind the head and slanting to 4 cm behind: 2 + 2 * (row's depth / 0.21 m) cm beyond.
    std::vector<glm::vec3> hair = {{0.0f, 0.21f, -0.12f}, {0.0f, 0.0f, -0.14f}};
    SideStandoff s = sideStandoff(head, hair, 2, 1.0f);
    EXPECT_EQ(s.rows, kSideStandoffRows);
    // Each row's hair reaches its deepest at the row's bottom, y = 0.2 - (k + 1) * 0.0025.
    double expected = 0.0;
    for (uint32_t k = 0; k < kSideStandoffRows; ++k) {
        double y = 0.2 - double(k + 1) * 0.0025;
        expected += 0.02 + 0.02 * (0.21 - y) / 0.21;
    }
    expected /= double(kSideStandoffRows);
    EXPECT_NEAR(s.meanBeyond, expected, 1e-6);
    EXPECT_NEAR(s.value, expected / 0.2, 1e-5);
}

TEST(GroomMetrics, SideStandoffOnlyOverRowsWithHair)
{
    Mesh head = boxHead(1.0f);
    std::vector<glm::vec3> hair;
    // Hair over the top 24 rows (6 cm) only, 4 cm behind: 0.04 / 0.2 over those rows.
    addStrand(hair, {0.0f, 0.2f, -0.14f}, {0.0f, 0.1412f, -0.14f}, 4);
    SideStandoff s = sideStandoff(head, hair, 4, 1.0f);
    EXPECT_EQ(s.rows, 24u);
    EXPECT_NEAR(s.value, 0.2, 1e-4);

    // Hair inside the silhouette stands off nothing; no hair at all gives no rows.
    std::vector<glm::vec3> inside;
    addStrand(inside, {0.0f, 0.2f, -0.09f}, {0.0f, 0.1f, 0.09f}, 6);
    SideStandoff in = sideStandoff(head, inside, 6, 1.0f);
    EXPECT_GT(in.rows, 0u);
    EXPECT_EQ(in.value, 0.0);
    EXPECT_EQ(sideStandoff(head, std::vector<glm::vec3>{}, 6, 1.0f).rows, 0u);
    // Hair wider than the head sideways (x) is not seen from the side.
    std::vector<glm::vec3> aside;
    addStrand(aside, {0.2f, 0.2f, 0.0f}, {0.2f, 0.1f, 0.0f}, 6);
    EXPECT_EQ(sideStandoff(head, aside, 6, 1.0f).value, 0.0);
}

TEST(GroomMetrics, TipLagAgainstAHeadTurn)
{
    // Four strands of 3 vertices around a head centred at (0, 1, 0.5); their tips at radius 0.2.
    StrandSet strands;
    strands.verticesPerStrand = 3;
    glm::vec3 pivot(0.0f, 1.0f, 0.5f);
    for (int s = 0; s < 4; ++s) {
        float a = 1.5707963f * float(s) + 0.3f;
        glm::vec3 out(std::sin(a), 0.0f, std::cos(a));
        strands.add({pivot + 0.1f * out, pivot + 0.15f * out, pivot + 0.2f * out - glm::vec3(0, 0.1f, 0)}, 0, 1, false);
    }
    // A rigid strand (every vertex pinned) is no tip: it would turn with the head whatever the hair does.
    strands.add({pivot, pivot + glm::vec3(0.0f, 0.0f, 0.3f), pivot + glm::vec3(0.0f, 0.0f, 0.4f)}, 0, 3, false);

    auto yaw = [&](float degrees) {
        glm::mat4 m = glm::translate(glm::mat4(1.0f), pivot);
        m = glm::rotate(m, glm::radians(degrees), glm::vec3(0.0f, 1.0f, 0.0f));
        return glm::translate(m, -pivot);
    };
    auto posed = [&](const glm::mat4& m) {
        std::vector<glm::vec4> out;
        for (const glm::vec3& p : strands.rest)
            out.push_back(m * glm::vec4(p, 1.0f));
        return out;
    };
    // The head turns to 200 degrees and back to 150 (past 180: unwrapped), in 5-degree samples.
    std::vector<float> turn;
    for (float d = 0.0f; d <= 200.0f; d += 5.0f)
        turn.push_back(d);
    for (float d = 195.0f; d >= 150.0f; d -= 5.0f)
        turn.push_back(d);

    TipLagMeter rigid(strands, pivot), still(strands, pivot), half(strands, pivot);
    for (size_t k = 0; k < turn.size(); ++k) {
        rigid.sample(0.1 * double(k), posed(yaw(turn[k])), yaw(turn[k]));
        still.sample(0.1 * double(k), posed(glm::mat4(1.0f)), yaw(turn[k]));
        half.sample(0.1 * double(k), posed(yaw(0.5f * turn[k])), yaw(turn[k]));
    }
    EXPECT_EQ(rigid.result().tips, 4u);
    EXPECT_EQ(rigid.result().samples, turn.size());
    EXPECT_NEAR(rigid.result().peakDeg, 0.0, 1e-3);
    EXPECT_NEAR(rigid.result().largestHeadYawDeg, 200.0, 1e-3);
    EXPECT_NEAR(still.result().peakDeg, 200.0, 1e-3);
    EXPECT_NEAR(still.result().peakAtSeconds, 4.0, 1e-9);
    EXPECT_NEAR(still.result().finalDeg, 150.0, 1e-3);
    EXPECT_NEAR(half.result().peakDeg, 100.0, 1e-3);
    EXPECT_NEAR(half.result().finalDeg, 75.0, 1e-3);
}

TEST(GroomMetrics, InsideTheMeshPastTheRootsAndDeeperThanTheThreshold)
{
    // On the box head (diagonal 0.325 m): one strand outside, one dipping 3 cm into the top at its
    // third vertex, one whose second vertex dips 1 cm (a root's, not counted) and whose tip dips
    // 1 mm (less than 0.5% of the diagonal: not counted, but the deepest of its strand). In
    // centimetres the shares and the depth as a fraction of the diagonal are the same.
    for (float scale : {1.0f, 100.0f}) {
        Mesh head = boxHead(scale);
        float diagonal = head.bounds().diagonal();
        MeshSignedDistance sdf(head);
        std::vector<glm::vec3> p;
        auto strand = [&](std::initializer_list<float> ys) {
            for (float y : ys)
                p.push_back(scale * glm::vec3(0.01f * float(p.size() / 4), y, 0.0f));
        };
        strand({0.2f, 0.23f, 0.26f, 0.3f});
        strand({0.2f, 0.19f, 0.17f, 0.25f});
        strand({0.2f, 0.19f, 0.22f, 0.199f});
        InsideMesh m = insideMesh(sdf, diagonal, p, 4);
        EXPECT_EQ(m.strands, 3u);
        EXPECT_EQ(m.vertices, 6u);
        EXPECT_EQ(m.strandsInside, 1u);
        EXPECT_EQ(m.verticesInside, 1u);
        EXPECT_NEAR(m.strandShare(), 1.0 / 3.0, 1e-9);
        EXPECT_NEAR(m.vertexShare(), 1.0 / 6.0, 1e-9);
        EXPECT_NEAR(m.deepest, 0.03 / (diagonal / scale), 1e-4);
        // The tip 1 mm inside is below the threshold, 0.31% of the diagonal.
        std::vector<glm::vec3> shallow(p.begin() + 8, p.end());
        InsideMesh s = insideMesh(sdf, diagonal, shallow, 4);
        EXPECT_EQ(s.strandsInside, 0u);
        EXPECT_NEAR(s.deepest, 0.001 / (diagonal / scale), 1e-4);
    }
}
