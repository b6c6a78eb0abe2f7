// tests/test_placement.cpp: a groom against a head: closest points on the mesh against brute force,
// the head's region, the roots' figures, placing grooms whose units, axes or position differ from
// the head's (made here by moving a groom grown on the default head: scaled 2.5 times, z-up,
// floating above, in centimetres), a fitted groom turned to face the way the head faces (or said to
// be ambiguous), refusing a groom whose roots cannot be put on the head, and the treatment of
// strands too short to simulate.
#include "assets/head.h"
#include "assets/placement.h"
#include "assets/signed_distance.h"
#include "core/error.h"
#include "groom_files.h"
#include "physics/cpu_solver.h"
#include "physics/groomed_head.h"
#include "physics/hair_style.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <functional>

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

// The box [-1, 1]^3, wound counter-clockwise seen from outside: with each face's own four corners
// (split, each with its face's normal) or with its eight corners shared.
Mesh boxMesh(bool split)
{
    Mesh m;
    for (int axis = 0; axis < 3; ++axis)
        for (float side : {-1.0f, 1.0f}) {
            glm::vec3 n(0.0f), u(0.0f), v(0.0f);
            n[axis] = side;
            u[(axis + 1) % 3] = 1.0f;
            v[(axis + 2) % 3] = 1.0f;
            if (side < 0.0f)
                std::swap(u, v);
            uint32_t first = uint32_t(m.positions.size());
            for (glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
                m.positions.push_back(n + c.x * u + c.y * v);
                m.normals.push_back(n);
            }
            for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u})
                m.indices.push_back(first + k);
        }
    if (!split) { // one vertex per corner
        std::vector<glm::vec3> corners;
        for (uint32_t& index : m.indices) {
            glm::vec3 p = m.positions[index];
            auto it = std::find(corners.begin(), corners.end(), p);
            index = uint32_t(it - corners.begin());
            if (it == corners.end())
                corners.push_back(p);
        }
        m.positions = corners;
        m.normals = computeVertexNormals(m.positions, m.indices);
    }
    m.sourceVertices = m.positions.size();
    return m;
}

// The signed distance to the box [-1, 1]^3.
float boxDistance(glm::vec3 p)
{
    glm::vec3 q = glm::abs(p) - glm::vec3(1.0f);
    return glm::length(glm::max(q, glm::vec3(0.0f))) + std::min(std::max({q.x, q.y, q.z}), 0.0f);
}

} // namespace

TEST(MeshDistance, SignedDistanceAgreesWithAnAnalyticBoxAndSphereOnSplitAndSharedVertices)
{
    // Points everywhere around and inside, the box's edges and corners included: the pseudonormal
    // tells inside from outside where a face's or a vertex's normal alone would not.
    uint32_t state = 777;
    auto next = [&] { return gpu::hashToUnit(state++); };
    for (bool split : {true, false}) {
        Mesh box = boxMesh(split);
        MeshSignedDistance distance(box);
        for (int k = 0; k < 400; ++k) {
            glm::vec3 p = -2.0f + 4.0f * glm::vec3(next(), next(), next());
            EXPECT_NEAR(distance(p), boxDistance(p), 1e-5f) << p.x << " " << p.y << " " << p.z;
        }
        // Beyond each corner and edge, and just inside them.
        for (glm::vec3 p : {glm::vec3(1.5f, 1.5f, 1.5f), glm::vec3(-1.2f, 1.3f, 0.0f), glm::vec3(0.99f, 0.99f, 0.99f),
                            glm::vec3(0.0f, -0.999f, 0.999f)})
            EXPECT_NEAR(distance(p), boxDistance(p), 1e-5f) << p.x << " " << p.y << " " << p.z;
    }
    // A latitude-longitude sphere: its seam's vertices are split, its poles' triangles have no area.
    Mesh sphere = makeSphereMesh(24, 48);
    MeshSignedDistance distance(sphere);
    MeshDistance closest(sphere);
    for (int k = 0; k < 400; ++k) {
        glm::vec3 d = glm::normalize(glm::vec3(next(), next(), next()) - 0.5f);
        float radius = 0.2f + 1.6f * next();
        if (std::abs(radius - 1.0f) < 0.02f)
            continue;
        float sd = distance(radius * d);
        EXPECT_NEAR(sd, radius - 1.0f, 0.01f) << "radius " << radius;
        EXPECT_EQ(sd < 0.0f, radius < 1.0f) << "radius " << radius;
    }
    // Above and below the top pole, where 48 triangles meet (the bottom pole's ring is not one
    // point in floats: sin(pi) rounds to -8.7e-8, which winds its slivers inward).
    EXPECT_NEAR(distance(glm::vec3(0.0f, 1.05f, 0.0f)), 0.05f, 1e-6f);
    EXPECT_NEAR(distance(glm::vec3(0.0f, 0.95f, 0.0f)), -0.05f, 1e-3f); // to the facets below
    EXPECT_NEAR(glm::length(closest.normal(closest.closest(glm::vec3(0.0f, 2.0f, 0.0f))) - glm::vec3(0, 1, 0)), 0.0f,
                1e-5f);
    // A subset's distances are to its triangles alone.
    MeshDistance top(sphere, {0u, 1u, 2u});
    EXPECT_GT(top.closest(glm::vec3(0.0f, -1.0f, 0.0f)).distance, 1.9f);
    EXPECT_LT(top.closest(glm::vec3(0.0f, 1.0f, 0.0f)).distance, 1e-6f);
}

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

namespace {

// The default head's grown groom stretched unevenly (wider, shorter, deeper) and moved up and
// aside: a groom of a head of another shape, which no scale, turn and offset lands root by root.
glm::vec3 stretched(glm::vec3 p)
{
    return glm::vec3(1.15f * p.x, 0.88f * p.y, 1.08f * p.z) + glm::vec3(0.01f, 0.25f, -0.02f);
}

// Every root within `rootsWithin` of the head's diagonal of its surface, and no vertex past the
// root deeper inside it than kStrandInside (of the strands `checked` takes; all without it).
void expectOnAndOutOfTheHead(const GroomedHead& scene, float rootsWithin, const std::string& name,
                             const std::function<bool(size_t)>& checked = {})
{
    const Mesh& mesh = scene.head.mesh;
    MeshDistance surface(mesh);
    MeshSignedDistance signedSurface(mesh);
    float diagonal = mesh.bounds().diagonal();
    uint32_t v = scene.strands.verticesPerStrand;
    float worstRoot = 0.0f, deepest = 0.0f;
    for (size_t s = 0; s < scene.strands.strandCount(); ++s) {
        worstRoot = std::max(worstRoot, surface.closest(scene.strands.rest[s * v]).distance / diagonal);
        for (uint32_t i = 1; i < v && (!checked || checked(s)); ++i)
            deepest = std::max(deepest, -signedSurface(scene.strands.rest[s * v + i]) / diagonal);
    }
    EXPECT_LE(worstRoot, rootsWithin) << name;
    EXPECT_LE(deepest, kStrandInside * 1.001f) << name;
}

} // namespace

TEST(Transfer, AGroomOfAnotherShapeIsMovedOntoTheScalpKeepingEverySegment)
{
    const uint32_t v = 12;
    Strands groom = test::grownStrands(400, v, stretched);
    TempDir dir;
    test::writeTfx4(dir / "stretched.tfx", groom);
    GroomedHead scene = buildLoadedHead(
        defaultHeadPath(), {{.file = dir / "stretched.tfx", .placement = std::nullopt, .settings = {}}}, v);
    const GroomPlacement& g = *scene.placement;
    ASSERT_EQ(g.method, GroomPlacement::Method::Fitted) << g.describe();
    EXPECT_GT(g.fit.max, 0.01f) << "the rigid fit leaves roots off the head";
    ASSERT_TRUE(scene.transfer.has_value());
    const GroomTransfer& t = *scene.transfer;
    EXPECT_EQ(t.roots, groom.size());
    EXPECT_GT(t.moved, groom.size() / 10);
    EXPECT_LT(t.moved, groom.size());
    EXPECT_GT(t.median, kRootMoved);
    EXPECT_FLOAT_EQ(t.beyond, kRootMoved);
    EXPECT_GE(t.max, t.median);
    EXPECT_GE(t.max, g.fit.max * 0.9f) << "the farthest root moved about as far as it lay";
    expectOnAndOutOfTheHead(scene, 0.005f, "stretched");
    // Each strand's segments keep their lengths: those of the file's strand placed (and resampled
    // where it has another vertex count; these have the count asked for, so they keep their points).
    ASSERT_EQ(scene.strands.strandCount(), groom.size());
    float worst = 0.0f;
    for (size_t s = 0; s < groom.size(); ++s) {
        std::vector<glm::vec3> placedStrand;
        for (const glm::vec3& p : groom[s])
            placedStrand.push_back(applyPlacement(g.placement, p));
        std::vector<glm::vec3> expected = placedStrand.size() == v ? placedStrand : resampleStrand(placedStrand, v);
        for (uint32_t i = 1; i < v; ++i) {
            float want = glm::length(expected[i] - expected[i - 1]);
            float got = glm::length(scene.strands.rest[s * v + i] - scene.strands.rest[s * v + i - 1]);
            worst = std::max(worst, std::abs(got - want) / want);
        }
    }
    EXPECT_LT(worst, 1e-5f);
    // Said: one line, and as JSON.
    std::vector<std::string> lines = describeLoadedHair(scene);
    ASSERT_GE(lines.size(), 2u);
    EXPECT_EQ(lines[1].rfind("hair transfer: " + std::to_string(t.moved) + " of 400 roots moved onto the scalp", 0), 0u)
        << lines[1];
    EXPECT_NE(lines[1].find("by median "), std::string::npos) << lines[1];
    nlohmann::json j = loadedHairJson(scene);
    EXPECT_EQ(j["transfer"]["moved"], t.moved);
    EXPECT_FLOAT_EQ(j["transfer"]["displacement"]["max"].get<float>(), t.max);

    // On its own head nothing moves: the groom stays as in the file.
    Strands own = test::grownStrands(200, v, [](glm::vec3 p) { return p; });
    test::writeTfx4(dir / "own.tfx", own);
    GroomedHead home =
        buildLoadedHead(defaultHeadPath(), {{.file = dir / "own.tfx", .placement = std::nullopt, .settings = {}}}, v);
    EXPECT_EQ(home.placement->method, GroomPlacement::Method::File);
    EXPECT_EQ(home.transfer->moved, 0u);
    EXPECT_EQ(home.transfer->turned + home.transfer->lifted, 0u);
    for (size_t s = 0; s < own.size(); ++s)
        EXPECT_LT(glm::length(home.strands.rest[s * v + v - 1] - own[s][v - 1]), 1e-5f);
    EXPECT_EQ(describeLoadedHair(home)[1].find("hair transfer"), std::string::npos);

    // On its own head with a few strands pulled 5% of the head away: still as in the file; those
    // move back onto the scalp (nearer where they grew than where they were pulled), and are kept
    // out of the head; the rest stay exactly where they are.
    Strands pulled = own;
    glm::vec3 centre = defaultHead().mesh.bounds().center();
    float diagonal = defaultHead().mesh.bounds().diagonal();
    for (size_t s = 0; s < pulled.size(); s += 20)
        for (glm::vec3& p : pulled[s])
            p += 0.05f * diagonal * glm::normalize(pulled[s][0] - centre);
    test::writeTfx4(dir / "pulled.tfx", pulled);
    GroomedHead back = buildLoadedHead(defaultHeadPath(),
                                       {{.file = dir / "pulled.tfx", .placement = std::nullopt, .settings = {}}}, v);
    EXPECT_EQ(back.placement->method, GroomPlacement::Method::File);
    EXPECT_EQ(back.transfer->moved, (pulled.size() + 19) / 20);
    EXPECT_NEAR(back.transfer->median, 0.05f, 0.01f);
    EXPECT_FLOAT_EQ(back.transfer->beyond, kRootOnSurface);
    for (size_t s = 0; s < pulled.size(); ++s)
        if (s % 20 != 0)
            EXPECT_EQ(back.strands.rest[s * v + v - 1], home.strands.rest[s * v + v - 1]);
        else
            EXPECT_LT(glm::length(back.strands.rest[s * v] - own[s][0]), 0.04f * diagonal);
    expectOnAndOutOfTheHead(back, kRootOnSurface, "pulled", [](size_t s) { return s % 20 == 0; });
}

TEST(Transfer, AHeadWithNoScalpToMoveOntoIsRefusedSayingSo)
{
    TempDir dir;
    nlohmann::json head = nlohmann::json::parse(std::ifstream(defaultHeadPath()));
    head["mesh"] = (defaultHeadPath().parent_path() / head["mesh"].get<std::string>()).string();
    head["scalp"]["plane_point"] = {0.0, 5.0, 0.0}; // above the head: no triangle
    std::ofstream(dir / "bald.json") << head.dump();
    test::writeTfx4(dir / "stretched.tfx", test::grownStrands(200, 8, stretched));
    std::string e = errorOf([&] {
        buildLoadedHead(dir / "bald.json", {{.file = dir / "stretched.tfx", .placement = std::nullopt, .settings = {}}},
                        8);
    });
    EXPECT_NE(e.find("stretched.tfx: "), std::string::npos) << e;
    EXPECT_NE(e.find("the head has no scalp to move them onto: its scalp rule selects no triangle"), std::string::npos)
        << e;
    EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 0) << e;
}

TEST(Transfer, SintelsGroomIsMovedOntoTheTressFxBustAndTheDefaultHead)
{
    WISP_REQUIRE_DATA(hair, "sintel/sintel_hair_11400x16.tfx");
    WISP_REQUIRE_DATA(bust, "tressfx-text/head_max4.obj");
    for (const std::filesystem::path& headFile : {bust, defaultHeadPath()}) {
        GroomedHead scene = buildLoadedHead(headFile, {{.file = hair, .placement = std::nullopt, .settings = {}}}, 16);
        std::string name = headFile.filename().string();
        EXPECT_EQ(scene.placement->method, GroomPlacement::Method::Fitted)
            << name << ": " << scene.placement->describe();
        ASSERT_TRUE(scene.transfer.has_value()) << name;
        EXPECT_GT(scene.transfer->moved, 0u) << name;
        EXPECT_EQ(scene.transfer->roots, scene.strands.strandCount()) << name;
        expectOnAndOutOfTheHead(scene, 0.005f, name);
        for (const std::string& line : describeLoadedHair(scene))
            std::printf("%s: %s\n", name.c_str(), line.c_str());
    }
}
