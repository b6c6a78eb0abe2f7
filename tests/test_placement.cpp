// tests/test_placement.cpp: a groom against a head: closest points on the mesh against brute force,
// the head's region, the roots' figures, placing grooms whose units, axes or position differ from
// the head's (made here by moving a groom grown on the default head: scaled 2.5 times, z-up,
// floating above, in centimetres), a fitted groom turned to face the way the head faces (or said to
// be ambiguous), refusing a groom whose roots cannot be put on the head, and the treatment of
// strands too short to simulate.
#include "assets/head.h"
#include "assets/placement.h"
#include "core/error.h"
#include "groom_files.h"
#include "physics/cpu_solver.h"
#include "physics/groomed_head.h"
#include "physics/hair_style.h"
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

// The groom as placement sees it: its roots and its strands, against a head facing +z.
GroomShape shapeOf(const Strands& strands)
{
    return {.roots = rootsOf(strands), .strands = strands, .headFront = glm::vec3(0.0f, 0.0f, 1.0f)};
}

// Long straight hair grown on the default head (which faces +z), each point moved by `transform`.
Strands longHair(glm::vec3 (*transform)(glm::vec3))
{
    GrowthSettings g;
    applyHairStyle(g, *findHairStyle("long"));
    g.guides = 300;
    g.verticesPerStrand = 12;
    GroomedHead scene = buildGrownHead(defaultHeadPath(), g);
    Strands out(scene.strands.strandCount());
    for (size_t s = 0; s < out.size(); ++s)
        for (uint32_t i = 0; i < g.verticesPerStrand; ++i)
            out[s].push_back(transform(scene.strands.rest[s * g.verticesPerStrand + i]));
    return out;
}

glm::vec3 turnedRound(glm::vec3 p)
{
    return glm::vec3(-p.x, p.y, -p.z);
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
    GroomPlacement g = placeGroom({.roots = rootsOf(groom)}, boundsOf(groom), HairPlacement{}, defaultHead().mesh);
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
        GroomPlacement g = placeGroom({.roots = rootsOf(groom)}, boundsOf(groom), c.defaults, head);
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

TEST(Placement, AGroomFittedTurnedRoundIsTurnedToFaceTheWayTheHeadFaces)
{
    // Long straight hair, floating above the head (so it is fitted), turned round or not: root
    // distance fits it either way round (the cranium is nearly symmetric front to back); the hair
    // over the face and the long strands at the back say which.
    const Mesh& head = defaultHead().mesh;
    Strands original = longHair([](glm::vec3 p) { return p; });
    Strands turned = longHair([](glm::vec3 p) { return turnedRound(p) + glm::vec3(0.0f, 0.3f, 0.0f); });
    Strands straight = longHair([](glm::vec3 p) { return p + glm::vec3(0.0f, 0.3f, 0.0f); });
    GroomPlacement t = placeGroom(shapeOf(turned), boundsOf(turned), HairPlacement{}, head);
    GroomPlacement s = placeGroom(shapeOf(straight), boundsOf(straight), HairPlacement{}, head);
    ASSERT_EQ(t.method, GroomPlacement::Method::Fitted);
    ASSERT_EQ(s.method, GroomPlacement::Method::Fitted);
    EXPECT_TRUE(t.placement.halfTurn) << "the turned groom is turned back";
    EXPECT_FALSE(s.placement.halfTurn);
    for (const GroomPlacement* g : {&t, &s}) {
        EXPECT_TRUE(g->fit.onHead()) << g->fit.onSurface;
        EXPECT_NE(g->front, GroomPlacement::Front::Ambiguous);
        EXPECT_NE(g->front, GroomPlacement::Front::AsPlaced);
        ASSERT_TRUE(g->turned.has_value());
        EXPECT_LT(g->facing.overFace, g->turned->overFace) << "less hair over the face than the other way";
        EXPECT_GT(g->facing.longAtBack, 0.0f) << "the long strands at the back";
        EXPECT_NE(g->describe().find("(its front by "), std::string::npos) << g->describe();
    }
    EXPECT_NE(t.describe().find(", turned round"), std::string::npos) << t.describe();
    // The turned groom's roots land where they grew, within a few percent of the head.
    float worst = 0.0f;
    for (size_t k = 0; k < turned.size(); k += 5)
        worst = std::max(worst, glm::length(applyPlacement(t.placement, turned[k][0]) - original[k][0]));
    EXPECT_LT(worst, 0.05f * head.bounds().diagonal());
    // Asked for, the turn is the user's: kept, nothing weighed.
    GroomPlacement kept =
        placeGroom(shapeOf(turned), boundsOf(turned), HairPlacement{}, head, PlacementRequest{.halfTurn = false});
    EXPECT_FALSE(kept.placement.halfTurn);
    EXPECT_EQ(kept.front, GroomPlacement::Front::AsPlaced);
    EXPECT_GT(kept.facing.overFace, t.facing.overFace);
}

TEST(Placement, ATressFxGroomInPartsTurnedRoundOnItsHeadIsTurnedBack)
{
    // The TressFX 2 sample: a fringe and a long ponytail on their bust, turned round about the up
    // axis: placed, the ponytail hangs at the back again and each root lands where it was.
    WISP_REQUIRE_DATA(front, "tressfx-text/hair_front_16_guide.tfx");
    WISP_REQUIRE_DATA(tail, "tressfx-text/hair_tail_16_guide.tfx");
    WISP_REQUIRE_DATA(headFile, "tressfx-text/head_max4.obj");
    std::vector<HairPartSource> parts = {{.file = front, .placement = std::nullopt, .settings = {}},
                                         {.file = tail, .placement = std::nullopt, .settings = {}}};
    GroomedHead asMade = buildLoadedHead(headFile, parts, 16);
    ASSERT_FALSE(asMade.placement->placement.halfTurn);
    uint32_t v = asMade.strands.verticesPerStrand;
    TempDir dir;
    std::vector<Strands> turned(2);
    Strands original;
    for (size_t s = 0; s < asMade.strands.strandCount(); ++s) {
        Strands& part = turned[asMade.strands.strands[s].part];
        part.emplace_back();
        for (uint32_t i = 0; i < v; ++i)
            part.back().push_back(turnedRound(asMade.strands.rest[s * v + i]));
        original.push_back({asMade.strands.rest[s * v]});
    }
    test::writeTfx4(dir / "front.tfx", turned[0]);
    test::writeTfx4(dir / "tail.tfx", turned[1]);
    GroomedHead back = buildLoadedHead(headFile,
                                       {{.file = dir / "front.tfx", .placement = std::nullopt, .settings = {}},
                                        {.file = dir / "tail.tfx", .placement = std::nullopt, .settings = {}}},
                                       16);
    const GroomPlacement& g = *back.placement;
    EXPECT_TRUE(g.placement.halfTurn) << g.describe();
    EXPECT_FALSE(g.placement.mirrorZ) << g.describe();
    EXPECT_NE(g.front, GroomPlacement::Front::Ambiguous) << g.describe();
    EXPECT_TRUE(g.fit.onHead()) << g.fit.onSurface;
    EXPECT_GT(g.facing.longAtBack, 0.0f) << "the ponytail at the back";
    ASSERT_EQ(back.strands.strandCount(), original.size());
    float worst = 0.0f;
    for (size_t s = 0; s < original.size(); ++s)
        worst = std::max(worst, glm::length(back.strands.rest[s * v] - original[s][0]));
    EXPECT_LT(worst, 0.05f * back.head.mesh.bounds().diagonal()) << g.describe();
}

TEST(Placement, SintelsGroomTurnedRoundOnHerHeadIsTurnedBack)
{
    WISP_REQUIRE_DATA(hair, "sintel-lite/sintel_hair_228x32.tfx");
    WISP_REQUIRE_DATA(headFile, "sintel-lite/sintel_lite.obj");
    GroomedHead asMade = buildLoadedHead(headFile, {{.file = hair, .placement = std::nullopt, .settings = {}}}, 16);
    ASSERT_EQ(asMade.placement->method, GroomPlacement::Method::File);
    uint32_t v = asMade.strands.verticesPerStrand;
    Strands original(asMade.strands.strandCount()), turned(original.size());
    for (size_t s = 0; s < original.size(); ++s)
        for (uint32_t i = 0; i < v; ++i) {
            original[s].push_back(asMade.strands.rest[s * v + i]);
            turned[s].push_back(turnedRound(original[s].back()));
        }
    TempDir dir;
    test::writeTfx4(dir / "turned.tfx", turned);
    GroomedHead back =
        buildLoadedHead(headFile, {{.file = dir / "turned.tfx", .placement = std::nullopt, .settings = {}}}, 16);
    const GroomPlacement& g = *back.placement;
    EXPECT_NE(g.method, GroomPlacement::Method::Given);
    EXPECT_TRUE(g.placement.halfTurn) << g.describe();
    EXPECT_EQ(g.placement.mirrorZ, asMade.placement->placement.mirrorZ) << g.describe();
    EXPECT_TRUE(g.fit.onHead()) << g.fit.onSurface;
    float worst = 0.0f;
    for (size_t k = 0; k < turned.size(); ++k)
        worst = std::max(worst, glm::length(applyPlacement(g.placement, turned[k][0]) - original[k][0]));
    EXPECT_LT(worst, 0.05f * back.head.mesh.bounds().diagonal()) << g.describe();
}

TEST(Placement, AGroomThatLooksTheSameBothWaysRoundIsSaidToBeAmbiguous)
{
    // Every strand beside its twin turned round: no root, face or length tells front from back.
    Strands grown = test::grownStrands(150, 8, [](glm::vec3 p) { return p + glm::vec3(0.0f, 0.3f, 0.0f); });
    Strands both = grown;
    for (const auto& s : grown) {
        both.push_back({});
        for (const glm::vec3& p : s)
            both.back().push_back(turnedRound(p - glm::vec3(0.0f, 0.3f, 0.0f)) + glm::vec3(0.0f, 0.3f, 0.0f));
    }
    GroomPlacement g = placeGroom(shapeOf(both), boundsOf(both), HairPlacement{}, defaultHead().mesh);
    ASSERT_EQ(g.method, GroomPlacement::Method::Fitted);
    EXPECT_EQ(g.front, GroomPlacement::Front::Ambiguous);
    EXPECT_FALSE(g.placement.halfTurn) << "kept as the file faces";
    std::string said = g.ambiguity();
    EXPECT_NE(said.find("which way round the groom goes is ambiguous"), std::string::npos) << said;
    EXPECT_NE(said.find("--hair-half-turn true turns it the other way"), std::string::npos) << said;
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
        buildLoadedHead(defaultHeadPath(), {{.file = dir / "plate.tfx", .placement = std::nullopt, .settings = {}}}, 4);
    });
    EXPECT_NE(e.find("plate.tfx: the groom's roots are not on the head"), std::string::npos) << e;
    EXPECT_NE(e.find("--hair-scale"), std::string::npos) << e;
    EXPECT_NE(e.find("--hair-offset"), std::string::npos) << e;
    EXPECT_NE(e.find("--hair-z-up"), std::string::npos) << e;
    // Placed by hand, the same groom loads, with a warning that says where the roots are.
    GroomedHead scene =
        buildLoadedHead(defaultHeadPath(), {{.file = dir / "plate.tfx", .placement = std::nullopt, .settings = {}}}, 4,
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
    GroomedHead scene =
        buildLoadedHead(defaultHeadPath(), {{.file = dir / "fur.tfx", .placement = std::nullopt, .settings = {}}}, 16);
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
        buildLoadedHead(defaultHeadPath(), {{.file = dir / "none.tfx", .placement = std::nullopt, .settings = {}}}, 4);
    });
    EXPECT_NE(e.find("none.tfx"), std::string::npos) << e;
}
