// tests/test_signed_distance.cpp: the exact signed distance to a mesh (assets/signed_distance.h)
// against analytic shapes: a box (its mesh is the box: exact), a sphere (within the tessellation's
// gap), the box open at its bottom (a bust cut at the chest), a plate thinner than a hundredth of
// its size, the same box in centimetres, and the default head against the brute-force sign.
#include "assets/head.h"
#include "assets/signed_distance.h"
#include "sdf_meshes.h"
#include "shaders/shared/sim.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace wisp;

namespace {

using test::sdfBoxDistance;

Mesh boxMesh(glm::vec3 h, glm::vec3 c = glm::vec3(0.0f), bool open = false)
{
    return test::sdfBoxMesh(h, c, open);
}

float boxDistance(glm::vec3 p, glm::vec3 h, glm::vec3 c = glm::vec3(0.0f))
{
    return sdfBoxDistance(p, h, c);
}

struct Points {
    uint32_t state = 7;
    float next() { return gpu::hashToUnit(state++); }
    glm::vec3 in(glm::vec3 lo, glm::vec3 hi) { return lo + (hi - lo) * glm::vec3(next(), next(), next()); }
};

} // namespace

TEST(SignedDistance, BoxIsExactEverywhere)
{
    glm::vec3 h(0.3f, 0.5f, 0.2f), c(0.1f, -0.2f, 0.05f);
    Mesh box = boxMesh(h, c);
    MeshSignedDistance sdf(box);
    Points pts;
    int inside = 0;
    for (int k = 0; k < 4000; ++k) {
        glm::vec3 p = pts.in(c - 2.0f * h, c + 2.0f * h);
        float expected = boxDistance(p, h, c);
        EXPECT_NEAR(sdf(p), expected, 1e-5f) << p.x << " " << p.y << " " << p.z;
        inside += expected < 0.0f;
    }
    EXPECT_GT(inside, 200) << "the points reach inside";
    // Off the corners and edges, where a face's normal alone gives the wrong sign: the vertex's and
    // the edge's pseudonormals give the right one.
    for (glm::vec3 dir : {glm::vec3(1, 1, 1), glm::vec3(-1, 1, -1), glm::vec3(1, -1, 1), glm::vec3(1, 1, 0),
                          glm::vec3(0, -1, 1), glm::vec3(-1, 0, -1)}) {
        glm::vec3 p = c + h * glm::sign(dir) * glm::abs(dir) + 0.01f * dir;
        EXPECT_NEAR(sdf(p), boxDistance(p, h, c), 1e-5f);
        EXPECT_GT(sdf(p), 0.0f);
        glm::vec3 q = c + h * dir - 0.01f * dir; // just inside the corner or edge
        EXPECT_LT(sdf(q), 0.0f);
    }
    // The closest point lies on the surface and the triangle holds it.
    MeshSignedDistance::Result r = sdf.query(c + glm::vec3(0.0f, 2.0f * h.y, 0.0f));
    EXPECT_NEAR(r.point.y, c.y + h.y, 1e-6f);
    EXPECT_LT(r.triangle, box.triangleCount());
}

TEST(SignedDistance, KeepsItsShapeInAnyUnits)
{
    // The same box in centimetres: every distance a hundred times the metres'.
    glm::vec3 h(0.3f, 0.5f, 0.2f);
    static const Mesh m = boxMesh(h), cm = boxMesh(100.0f * h);
    MeshSignedDistance a(m), b(cm);
    Points pts;
    for (int k = 0; k < 500; ++k) {
        glm::vec3 p = pts.in(-2.0f * h, 2.0f * h);
        EXPECT_NEAR(b(100.0f * p), 100.0f * a(p), 2e-3f);
    }
}

TEST(SignedDistance, SphereWithinItsTessellation)
{
    // A latitude-longitude sphere: its poles hold triangles of no area and its seam duplicated
    // vertices, both welded away. The polyhedron lies inside the unit sphere, at most its largest
    // facet's sagitta below it.
    Mesh sphere = makeSphereMesh(24, 48);
    MeshSignedDistance sdf(sphere);
    float gap = 1.0f - std::cos(3.14159265f / 24.0f); // a facet's half diagonal subtends less than pi/24
    Points pts;
    int inside = 0, outside = 0;
    for (int k = 0; k < 3000; ++k) {
        glm::vec3 p = pts.in(glm::vec3(-2.0f), glm::vec3(2.0f));
        float expected = glm::length(p) - 1.0f;
        float d = sdf(p);
        EXPECT_LE(d, expected + gap + 1e-5f);
        EXPECT_GE(d, expected - 1e-5f);
        if (std::abs(expected) > gap) {
            EXPECT_EQ(d < 0.0f, expected < 0.0f) << p.x << " " << p.y << " " << p.z;
            (expected < 0.0f ? inside : outside)++;
        }
    }
    EXPECT_GT(inside, 100);
    EXPECT_GT(outside, 1000);
    // Straight above and below the poles (the closest feature the pole: a vertex of 48 triangles and
    // 48 slivers, its copies a float rounding apart), and inside.
    EXPECT_NEAR(sdf(glm::vec3(0.0f, 1.5f, 0.0f)), 0.5f, 1e-5f);
    EXPECT_NEAR(sdf(glm::vec3(0.0f, -0.5f, 0.0f)), -0.5f, gap);
    EXPECT_NEAR(sdf(glm::vec3(0.0f, -1.25f, 0.0f)), 0.25f, 1e-5f);
}

TEST(SignedDistance, OpenMeshGoesOnPastItsCut)
{
    // The box without its bottom face: above and beside it reads as the closed box; below the
    // opening, inside its outline, reads as inside (the body goes on past the cut), beside it outside.
    glm::vec3 h(0.3f, 0.5f, 0.2f);
    Mesh closed = boxMesh(h), open = boxMesh(h, glm::vec3(0.0f), true);
    MeshSignedDistance a(closed), b(open);
    Points pts;
    for (int k = 0; k < 2000; ++k) {
        glm::vec3 p = pts.in(-2.0f * h, 2.0f * h);
        if (a.query(p).point.y > -h.y + 1e-4f) { // the closed box's nearest is not the bottom face
            EXPECT_NEAR(b(p), a(p), 1e-5f) << "above the cut: " << p.x << " " << p.y << " " << p.z;
        }
        if (p.y < -h.y - 0.01f) {
            bool under = std::abs(p.x) < h.x - 0.01f && std::abs(p.z) < h.z - 0.01f;
            bool beside = std::abs(p.x) > h.x + 0.01f || std::abs(p.z) > h.z + 0.01f;
            if (under) {
                EXPECT_LT(b(p), 0.0f) << "under the opening: " << p.x << " " << p.y << " " << p.z;
            }
            if (beside) {
                EXPECT_GT(b(p), 0.0f) << "beside the cut: " << p.x << " " << p.y << " " << p.z;
            }
        }
    }
}

TEST(SignedDistance, ThinPlateHasTwoOutsides)
{
    // A plate 2 mm thick and 1 m wide (armour, an ear): both faces' sides are outside, its middle inside.
    glm::vec3 h(0.5f, 0.001f, 0.5f);
    Mesh plate = boxMesh(h);
    MeshSignedDistance sdf(plate);
    Points pts;
    for (int k = 0; k < 500; ++k) {
        glm::vec3 p = pts.in(glm::vec3(-0.45f, -0.01f, -0.45f), glm::vec3(0.45f, 0.01f, 0.45f));
        EXPECT_NEAR(sdf(p), boxDistance(p, h), 1e-6f);
    }
    EXPECT_LT(sdf(glm::vec3(0.1f, 0.0f, 0.2f)), 0.0f);
    EXPECT_GT(sdf(glm::vec3(0.1f, 0.0015f, 0.2f)), 0.0f);
    EXPECT_GT(sdf(glm::vec3(0.1f, -0.0015f, 0.2f)), 0.0f);
}

TEST(SignedDistance, DefaultHeadAgreesWithBruteForceNearItsSurface)
{
    // Near the default head (a closed surface-nets mesh) the sign agrees with the brute force's:
    // the nearest triangle over all of them, signed by its pseudonormal.
    Head head = loadHead(defaultHeadPath());
    MeshSignedDistance sdf(head.mesh);
    const std::vector<gpu::SdfTriangle>& tris = sdf.triangles();
    Bounds b = head.mesh.bounds();
    Points pts;
    int inside = 0;
    for (int k = 0; k < 40; ++k) {
        glm::vec3 v = head.mesh.positions[(size_t(k) * 7919u) % head.mesh.positions.size()];
        glm::vec3 p =
            v + (pts.next() - 0.5f) * 0.04f * b.diagonal() * glm::normalize(pts.in(glm::vec3(-1), glm::vec3(1)));
        float best = INFINITY, signedBest = 0.0f;
        for (const gpu::SdfTriangle& t : tris) {
            float d = gpu::sdfSignedDistance(p, t);
            if (std::abs(d) < best) {
                best = std::abs(d);
                signedBest = d;
            }
        }
        float d = sdf(p);
        EXPECT_NEAR(std::abs(d), best, 1e-6f * b.diagonal());
        if (best > 1e-4f * b.diagonal()) {
            EXPECT_EQ(d < 0.0f, signedBest < 0.0f);
        }
        inside += d < 0.0f;
    }
    EXPECT_GT(inside, 5);
    EXPECT_LT(inside, 35);
}
