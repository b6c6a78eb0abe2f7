// tests/test_placement.cpp: a groom against a head: closest points on the mesh against brute force,
// the head's region, the roots' figures, placing grooms whose units, axes or position differ from
// the head's (made here by moving a groom grown on the default head: scaled 2.5 times, z-up,
// floating above, in centimetres), refusing a groom whose roots cannot be put on the head, and the
// treatment of strands too short to simulate.
#include "assets/head.h"
#include "assets/placement.h"
#include "core/error.h"
#include "groom_files.h"
#include "physics/cpu_solver.h"
#include "physics/hair_scene.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace wisp;
using wisp::test::Strands;
using wisp::test::TempDir;

namespace {

const Head& defaultHead()
{
    static const Head head = loadHead(defaultHeadPath());
    return head;
}

std::vector<glm::vec3> rootsOf(const Strands& strands)
{
    std::vector<glm::vec3> out;
    for (const auto& s : strands)
        out.push_back(s.front());
    return out;
}

Bounds boundsOf(const Strands& strands)
{
    Bounds b{strands[0][0], strands[0][0]};
    for (const auto& s : strands)
        for (const glm::vec3& p : s) {
            b.min = glm::min(b.min, p);
            b.max = glm::max(b.max, p);
        }
    return b;
}

std::string errorOf(const std::function<void()>& f)
{
    try {
        f();
    } catch (const UserError& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(MeshDistance, ClosestPointsMatchBruteForce)
{
    const Mesh& mesh = defaultHead().mesh;
    MeshDistance distance(mesh);
    Bounds b = mesh.bounds();
    uint32_t state = 12345;
    auto next = [&] { return gpu::hashToUnit(state++); };
    for (int k = 0; k < 60; ++k) {
        glm::vec3 p = b.min - 0.3f * b.size() + 1.6f * b.size() * glm::vec3(next(), next(), next());
        float brute = INFINITY;
        for (size_t t = 0; t < mesh.triangleCount(); ++t) {
            // Distance to a triangle by dense sampling is not exact; compare with vertices and the
            // BVH's answer: it is never farther than the nearest vertex, and never nearer than what
            // the triangles' planes allow.
            for (int c = 0; c < 3; ++c)
                brute = std::min(brute, glm::length(mesh.positions[mesh.indices[3 * t + c]] - p));
        }
        MeshDistance::Closest c = distance.closest(p);
        EXPECT_LE(c.distance, brute + 1e-6f);
        EXPECT_NEAR(glm::length(c.point - p), c.distance, 1e-5f);
        EXPECT_GT(c.distance, brute - 0.02f * b.diagonal()) << "the mesh's edges are short: a vertex is near";
    }
    // Points on the surface are at distance 0.
    for (size_t v = 0; v < mesh.positions.size(); v += 997)
        EXPECT_LT(distance.closest(mesh.positions[v]).distance, 1e-6f);
}

TEST(Placement, TheHeadRegionFindsTheNeckOfABust)
{
    const Mesh& mesh = defaultHead().mesh;
    HeadRegion r = headRegion(mesh);
    Bounds b = mesh.bounds();
    EXPECT_EQ(r.top, b.max.y);
    // The mannequin's neck lies between its chin and its shoulders: a third to two thirds down.
    EXPECT_LT(r.neck, b.max.y - 0.3f * b.size().y);
    EXPECT_GT(r.neck, b.max.y - 0.7f * b.size().y);
}

TEST(Placement, AGroomMadeForTheHeadStaysAsInTheFile)
{
    Strands groom = test::grownStrands(300, 8, [](glm::vec3 p) { return p; });
    GroomPlacement g = placeGroom(rootsOf(groom), boundsOf(groom), HairPlacement{}, defaultHead().mesh);
    EXPECT_EQ(g.method, GroomPlacement::Method::File);
    EXPECT_EQ(g.placement.scale, 1.0f);
    EXPECT_EQ(g.placement.offset, glm::vec3(0.0f));
    EXPECT_TRUE(g.fit.onHead());
    EXPECT_LT(g.fit.median, 1e-3f);
    EXPECT_EQ(g.fit.roots, 300u);
}

TEST(Placement, AGroomInOtherUnitsAxesAndPlaceIsFittedToTheScalp)
{
    const Mesh& head = defaultHead().mesh;
    struct Case {
        const char* name;
        glm::vec3 (*transform)(glm::vec3);
        HairPlacement defaults;
        float scale; // what recovers the head's units
    };
    std::vector<Case> cases = {
        // A cyHair groom 2.5 times too large (not a power of ten) and z-up.
        {"2.5x, z-up", [](glm::vec3 p) { return 2.5f * glm::vec3(p.x, -p.z, p.y); }, HairPlacement{.zUpToYUp = true},
         0.4f},
        // A mohawk made for a head 0.3 above this one.
        {"floating", [](glm::vec3 p) { return p + glm::vec3(0.0f, 0.3f, 0.0f); }, HairPlacement{}, 1.0f},
        // In centimetres, for a head standing on the origin 1.6 m lower.
        {"centimetres", [](glm::vec3 p) { return 100.0f * p + glm::vec3(3.0f, 160.0f, -2.0f); }, HairPlacement{},
         0.01f},
    };
    for (const Case& c : cases) {
        Strands groom = test::grownStrands(400, 8, c.transform);
        GroomPlacement g = placeGroom(rootsOf(groom), boundsOf(groom), c.defaults, head);
        EXPECT_EQ(g.method, GroomPlacement::Method::Fitted) << c.name;
        EXPECT_NEAR(g.placement.scale / c.scale, 1.0f, 0.1f) << c.name;
        EXPECT_EQ(g.placement.zUpToYUp, c.defaults.zUpToYUp) << c.name;
        EXPECT_TRUE(g.fit.onHead()) << c.name << ": " << g.fit.onSurface;
        EXPECT_LT(g.fit.median, 0.01f) << c.name;
        // The roots land where they grew, within a few percent of the head.
        Strands original = test::grownStrands(400, 8, [](glm::vec3 p) { return p; });
        float worst = 0.0f;
        for (size_t s = 0; s < groom.size(); s += 7)
            worst = std::max(worst, glm::length(applyPlacement(g.placement, groom[s][0]) - original[s][0]));
        EXPECT_LT(worst, 0.05f * head.bounds().diagonal()) << c.name;
    }
}

TEST(Placement, RootsThatFitNowhereAreRefusedNamingTheOptions)
{
    // Roots on a flat disc far wider than the head: no scale, axis or offset puts them on it.
    TempDir dir;
    Strands plate;
    for (int k = 0; k < 200; ++k) {
        float a = 0.1f * float(k), r = 3.0f * std::sqrt(float(k) / 200.0f);
        glm::vec3 root(r * std::cos(a), 5.0f, r * std::sin(a));
        plate.push_back(
            {root, root + glm::vec3(0, -0.1f, 0), root + glm::vec3(0, -0.2f, 0), root + glm::vec3(0, -0.3f, 0)});
    }
    test::writeTfx4(dir / "plate.tfx", plate);
    std::string e = errorOf([&] {
        buildLoadedScene(defaultHeadPath(), {{.file = dir / "plate.tfx", .placement = std::nullopt, .settings = {}}},
                         4);
    });
    EXPECT_NE(e.find("plate.tfx: the groom's roots are not on the head"), std::string::npos) << e;
    EXPECT_NE(e.find("--hair-scale"), std::string::npos) << e;
    EXPECT_NE(e.find("--hair-offset"), std::string::npos) << e;
    EXPECT_NE(e.find("--hair-z-up"), std::string::npos) << e;
    // Placed by hand, the same groom loads, with a warning that says where the roots are.
    HairScene scene =
        buildLoadedScene(defaultHeadPath(), {{.file = dir / "plate.tfx", .placement = std::nullopt, .settings = {}}}, 4,
                         PlacementRequest{.scale = 1.0f, .offset = glm::vec3(0.0f)});
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_NE(scene.warnings[0].find("not on the head: as given"), std::string::npos) << scene.warnings[0];
    EXPECT_EQ(scene.placement->method, GroomPlacement::Method::Given);
    EXPECT_TRUE(scene.placement->fit.offHead());
}

TEST(ShortStrands, AreKeptRigidAndStrandsOfNoLengthDropped)
{
    // A fur-like groom: most strands 12 cm, some a tenth of a millimetre, one of no length at all.
    // The short ones reset and stretched the simulation (a fur groom with 278 of 48,113 strands
    // under 0.05 units: 100 resets and stretch 0.92 in 50 steps); kept rigid, they follow the
    // head, and the rest simulates cleanly.
    TempDir dir;
    Strands fur = test::grownStrands(120, 6, [](glm::vec3 p) { return p; });
    size_t shortOnes = 0;
    for (size_t s = 0; s < fur.size(); s += 5, ++shortOnes) {
        glm::vec3 root = fur[s][0], dir3 = glm::normalize(fur[s][1] - root);
        for (size_t i = 0; i < fur[s].size(); ++i)
            fur[s][i] = root + 2e-5f * float(i) * dir3;
    }
    fur[1].assign(fur[1].size(), fur[1][0]); // no length
    test::writeTfx4(dir / "fur.tfx", fur);
    HairScene scene =
        buildLoadedScene(defaultHeadPath(), {{.file = dir / "fur.tfx", .placement = std::nullopt, .settings = {}}}, 16);
    EXPECT_EQ(scene.loaded.dropped, 1u);
    EXPECT_EQ(scene.loaded.rigid, shortOnes);
    EXPECT_EQ(scene.strands.strandCount(), fur.size() - 1);
    EXPECT_NEAR(scene.loaded.shortThreshold, 15e-3f * scene.head.mesh.bounds().diagonal(), 1e-6f);
    size_t rigid = 0;
    for (const gpu::StrandInfo& info : scene.strands.strands)
        rigid += info.pinnedRoot == 16u ? 1 : 0;
    EXPECT_EQ(rigid, shortOnes);

    SimSettings settings;
    settings.wind = glm::vec3(5.0f, 0.0f, 2.0f);
    settings.gridResolution = 16;
    SimSetup setup = makeSimSetup(settings, scene.strands, scene.gpuColliders, scene.unitsPerMetre);
    CpuSolver cpu(scene.strands, setup, glm::mat4(1.0f));
    std::vector<glm::vec4> previous;
    gpu::SimStep step{};
    for (uint32_t k = 0; k < 50; ++k) {
        previous = cpu.state().positions;
        step = makeStep(setup, glm::mat4(1.0f), glm::vec4(0.0f), float(k) / settings.stepHz);
        cpu.step(step);
    }
    SimMetrics m = measure(cpu.state(), previous, 1.0f / settings.stepHz, scene.strands, setup, step);
    EXPECT_EQ(cpu.state().nonfiniteResets, 0u);
    EXPECT_LT(m.maxStretch, 1e-4f);
    EXPECT_EQ(m.rootDrift, 0.0f);
    // Every file of only strands of no length is refused.
    Strands none(3, std::vector<glm::vec3>(4, glm::vec3(0.0f, 0.2f, 0.0f)));
    test::writeTfx4(dir / "none.tfx", none);
    std::string e = errorOf([&] {
        buildLoadedScene(defaultHeadPath(), {{.file = dir / "none.tfx", .placement = std::nullopt, .settings = {}}}, 4);
    });
    EXPECT_NE(e.find("none.tfx"), std::string::npos) << e;
}
