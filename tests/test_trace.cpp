// tests/test_trace.cpp: the path tracer's ray casting (shaders/shared/trace.h, trace_bvh.h, compiled
// as C++): capsules and triangles against analytic cases (the hit point, the normal and the offset
// across the fibre; grazing rays; origins inside the radius), and the hierarchy's walk
// (renderer/reference/bvh.h) against testing every primitive, on random scenes and rays.
#include "renderer/reference/bvh.h"
#include "shaders/shared/fiber_bsdf.h"
#include "shaders/shared/trace_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <random>
#include <vector>

using namespace wisp;

namespace {

// A capsule along y from (0, -1, 0) to (0, 1, 0), radius 0.5.
const glm::vec3 kA(0.0f, -1.0f, 0.0f), kB(0.0f, 1.0f, 0.0f);
constexpr float kR = 0.5f;

glm::vec2 entry(glm::vec3 o, glm::vec3 d, float tMax = 1e30f)
{
    return gpu::capsuleEntry(o, glm::normalize(d), kA, kB, kR, 1e-4f, tMax);
}

} // namespace

TEST(Trace, CapsuleHitAtAKnownPointNormalAndOffset)
{
    // Head on: the front of the cylinder, halfway along.
    glm::vec2 e = entry({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f});
    EXPECT_NEAR(e.x, 4.5f, 1e-5f);
    EXPECT_NEAR(e.y, 0.5f, 1e-6f);

    // Off the axis by 0.3 across: the surface at z = sqrt(0.5^2 - 0.3^2) = 0.4, normal (0.6, 0, 0.8).
    glm::vec3 o(0.3f, 0.2f, 5.0f), d(0.0f, 0.0f, -1.0f);
    e = entry(o, d);
    EXPECT_NEAR(e.x, 4.6f, 1e-5f);
    EXPECT_NEAR(e.y, 0.6f, 1e-5f); // y = 0.2 is 0.6 of the way from -1 to 1
    glm::vec3 p = o + e.x * d;
    glm::vec3 axis = glm::mix(kA, kB, e.y);
    glm::vec3 n = (p - axis) / kR;
    EXPECT_NEAR(glm::length(n - glm::vec3(0.6f, 0.0f, 0.8f)), 0.0f, 1e-5f);
    // The offset across the fibre, in the BSDF's frame (z toward the ray, y = z x t): h = -0.6, and the
    // viewer sits at gamma_o = asin(h) from the surface normal, as Chiang's geometry has it.
    gpu::FiberFrame f = gpu::makeFiberFrame(glm::normalize(kB - kA), d);
    float h = glm::dot(p - axis, f.y) / kR;
    EXPECT_NEAR(h, -0.6f, 1e-5f);
    glm::vec3 nLocal = gpu::fiberToLocal(f, n);
    EXPECT_NEAR(std::asin(h), 0.5f * std::numbers::pi_v<float> - std::atan2(nLocal.z, nLocal.y), 1e-5f);

    // Along the axis: the end sphere at b, t = 5 - 1 - 0.5.
    e = entry({0.0f, 5.0f, 0.0f}, {0.0f, -1.0f, 0.0f});
    EXPECT_NEAR(e.x, 3.5f, 1e-5f);
    EXPECT_EQ(e.y, 1.0f);
    // Slanting past the end of the body into the sphere at a: from below, at 45 degrees.
    e = entry({0.0f, -3.0f, 2.0f}, {0.0f, 1.0f, -1.0f});
    glm::vec3 q = glm::vec3(0.0f, -3.0f, 2.0f) + e.x * glm::normalize(glm::vec3(0.0f, 1.0f, -1.0f));
    EXPECT_GT(e.x, 0.0f);
    EXPECT_EQ(e.y, 0.0f);
    EXPECT_NEAR(glm::length(q - kA), kR, 1e-5f);
}

TEST(Trace, GrazingRaysHitOrMissByTheRadius)
{
    // Tangent planes at x = +-0.5: just inside hits near z = sqrt(0.25 - 0.4999^2) = 0.01, just outside misses.
    glm::vec2 in = entry({0.4999f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f});
    EXPECT_NEAR(in.x, 5.0f - std::sqrt(0.25f - 0.4999f * 0.4999f), 1e-4f);
    EXPECT_LT(entry({0.5001f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f}).x, 0.0f);
    // Parallel to the axis, within the radius: the end sphere; beyond it: nothing.
    EXPECT_GT(entry({0.49f, -5.0f, 0.0f}, {0.0f, 1.0f, 0.0f}).x, 0.0f);
    EXPECT_LT(entry({0.51f, -5.0f, 0.0f}, {0.0f, 1.0f, 0.0f}).x, 0.0f);
    // A hit beyond tMax, or behind the origin, is none.
    EXPECT_LT(entry({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f}, 4.4f).x, 0.0f);
    EXPECT_LT(entry({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 1.0f}).x, 0.0f);
}

// A path leaves a fibre from inside its radius (its axis): the fibre it leaves is no hit, in any
// direction, but a fibre beside it is.
TEST(Trace, OriginInsideTheRadiusPassesOutUnhit)
{
    for (glm::vec3 d : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(0.3f, 0.2f, -0.9f)}) {
        EXPECT_LT(entry({0.0f, 0.3f, 0.0f}, d).x, 0.0f);
        EXPECT_LT(entry({0.2f, 1.2f, 0.0f}, d).x, 0.0f); // in the end sphere
    }
    std::vector<gpu::TraceSegment> segments = {{kA, kR, kB, 0u},
                                               {kA + glm::vec3(2.0f, 0, 0), kR, kB + glm::vec3(2.0f, 0, 0), 1u}};
    reference::Bvh bvh = reference::buildBvh(segments, {});
    gpu::TraceBuffers scene = reference::traceBuffers(bvh, segments, {});
    gpu::TraceHit hit = gpu::traceScene(scene, glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), 0.0f, 1e30f, false);
    EXPECT_EQ(hit.prim, 1u);
    EXPECT_NEAR(hit.t, 1.5f, 1e-5f);
}

TEST(Trace, TriangleHitBarycentricsAndEdges)
{
    glm::vec3 p0(0, 0, 0), p1(2, 0, 0), p2(0, 2, 0);
    glm::vec3 e = gpu::triangleEntry({0.5f, 0.5f, 3.0f}, {0, 0, -1}, p0, p1, p2, 1e-4f, 1e30f);
    EXPECT_NEAR(e.x, 3.0f, 1e-6f);
    EXPECT_NEAR(e.y, 0.25f, 1e-6f);
    EXPECT_NEAR(e.z, 0.25f, 1e-6f);
    // Two-sided: from below too.
    EXPECT_NEAR(gpu::triangleEntry({0.5f, 0.5f, -3.0f}, {0, 0, 1}, p0, p1, p2, 1e-4f, 1e30f).x, 3.0f, 1e-6f);
    // Just inside and just outside the hypotenuse; parallel to the plane; behind.
    EXPECT_GT(gpu::triangleEntry({0.999f, 0.999f, 1.0f}, {0, 0, -1}, p0, p1, p2, 1e-4f, 1e30f).x, 0.0f);
    EXPECT_LT(gpu::triangleEntry({1.001f, 1.001f, 1.0f}, {0, 0, -1}, p0, p1, p2, 1e-4f, 1e30f).x, 0.0f);
    EXPECT_LT(gpu::triangleEntry({0.5f, 0.5f, 1.0f}, {1, 0, 0}, p0, p1, p2, 1e-4f, 1e30f).x, 0.0f);
    EXPECT_LT(gpu::triangleEntry({0.5f, 0.5f, 1.0f}, {0, 0, 1}, p0, p1, p2, 1e-4f, 1e30f).x, 0.0f);
}

namespace {

struct RandomScene {
    std::vector<gpu::TraceSegment> segments;
    std::vector<gpu::TraceTriangle> triangles;
};

// Strand-like chains of short segments and scattered triangles in the unit box.
RandomScene randomScene(int strands, int triangles, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), s(-1.0f, 1.0f);
    RandomScene scene;
    for (int k = 0; k < strands; ++k) {
        glm::vec3 p(u(rng), u(rng), u(rng));
        glm::vec3 dir = glm::normalize(glm::vec3(s(rng), s(rng), s(rng)));
        for (int i = 0; i < 8; ++i) {
            dir = glm::normalize(dir + 0.3f * glm::vec3(s(rng), s(rng), s(rng)));
            glm::vec3 q = p + 0.03f * dir;
            scene.segments.push_back({p, 0.002f + 0.004f * u(rng), q, uint32_t(k)});
            p = q;
        }
    }
    for (int k = 0; k < triangles; ++k) {
        glm::vec3 c(u(rng), u(rng), u(rng));
        auto corner = [&] { return glm::vec4(c + 0.1f * glm::vec3(s(rng), s(rng), s(rng)), 0.0f); };
        scene.triangles.push_back({corner(), corner(), corner(), {}, {}, {}});
    }
    return scene;
}

gpu::TraceHit bruteForce(const gpu::TraceBuffers& b, uint32_t primitives, glm::vec3 o, glm::vec3 d, float tMin)
{
    gpu::TraceHit hit = gpu::traceMiss();
    for (uint32_t p = 0; p < primitives; ++p) {
        glm::vec3 e = gpu::tracePrimitive(b, p, o, d, tMin, hit.t);
        if (e.x > 0.0f)
            hit = {e.x, p, e.y, e.z};
    }
    return hit;
}

} // namespace

// The walk finds what testing every primitive finds: the same closest primitive at the same t, and
// a hit for any-hit queries exactly when there is one; origins inside the scene and outside it.
TEST(Trace, HierarchyWalkEqualsBruteForceOnRandomRays)
{
    RandomScene rs = randomScene(400, 150, 17);
    reference::Bvh bvh = reference::buildBvh(rs.segments, rs.triangles);
    ASSERT_LE(bvh.depth, reference::kBvhMaxDepth);
    ASSERT_EQ(bvh.prims.size(), rs.segments.size() + rs.triangles.size());
    gpu::TraceBuffers scene = reference::traceBuffers(bvh, rs.segments, rs.triangles);
    uint32_t primitives = uint32_t(bvh.prims.size());
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> u(-0.5f, 1.5f), s(-1.0f, 1.0f);
    int hits = 0;
    for (int i = 0; i < 3000; ++i) {
        glm::vec3 o(u(rng), u(rng), u(rng));
        glm::vec3 d = glm::normalize(glm::vec3(s(rng), s(rng), s(rng)));
        gpu::TraceHit want = bruteForce(scene, primitives, o, d, 1e-5f);
        gpu::TraceHit got = gpu::traceScene(scene, o, d, 1e-5f, gpu::kTraceInfinity, false);
        ASSERT_EQ(got.prim, want.prim) << "ray " << i;
        ASSERT_EQ(got.t, want.t) << "ray " << i;
        gpu::TraceHit any = gpu::traceScene(scene, o, d, 1e-5f, gpu::kTraceInfinity, true);
        EXPECT_EQ(any.prim != gpu::kTraceNoHit, want.prim != gpu::kTraceNoHit) << "ray " << i;
        hits += want.prim != gpu::kTraceNoHit;
    }
    EXPECT_GT(hits, 200); // the rays do meet the scene (the comparison is not of misses alone)
}

// Degenerate input: every primitive in one place (no plane separates them) still builds a tree
// within the walk's depth, with every primitive in one leaf or another; no primitives, no tree.
TEST(Trace, HierarchyOfCoincidentPrimitivesStaysShallow)
{
    std::vector<gpu::TraceSegment> same(5000, {glm::vec3(0.0f), 0.01f, glm::vec3(0.0f, 0.1f, 0.0f), 0u});
    reference::Bvh bvh = reference::buildBvh(same, {});
    EXPECT_LE(bvh.depth, 16u);
    std::vector<uint32_t> prims = bvh.prims;
    std::sort(prims.begin(), prims.end());
    for (uint32_t i = 0; i < prims.size(); ++i)
        ASSERT_EQ(prims[i], i);
    gpu::TraceBuffers scene = reference::traceBuffers(bvh, same, {});
    EXPECT_NE(gpu::traceScene(scene, glm::vec3(0.0f, 0.05f, 1.0f), glm::vec3(0, 0, -1), 0.0f, 1e30f, false).prim,
              gpu::kTraceNoHit);
    EXPECT_TRUE(reference::buildBvh({}, {}).nodes.empty());
}
