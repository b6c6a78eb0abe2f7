// tests/test_head.cpp: the project's own head (models/head.obj + head.json): it loads, looks like
// a bust in proportions, its scalp rule picks the top and back, its colliders cover the head;
// the generator rebuilds the committed files byte for byte; bad descriptions are reported; colliders
// fitted to a bare mesh that is no head are said to hold it badly.
#include "assets/head.h"
#include "core/error.h"
#include "core/rotation.h"
#include "physics/colliders.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>

using namespace wisp;
using wisp::test::TempDir;
using wisp::test::writeFile;

namespace {

std::string errorOf(const std::filesystem::path& path)
{
    try {
        loadHeadDescription(path);
    } catch (const UserError& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(DefaultHead, LoadsAsAMannequinBust)
{
    Head head = loadHead(defaultHeadPath());
    EXPECT_EQ(head.description.units, "m");
    EXPECT_GT(head.mesh.triangleCount(), 10000u);
    Bounds b = head.mesh.bounds();
    // A bust in metres: about 0.4 m tall, shoulders wider than the head is deep.
    EXPECT_GT(b.size().y, 0.25f);
    EXPECT_LT(b.size().y, 0.6f);
    EXPECT_GT(b.size().x, 0.25f);
    EXPECT_LT(b.size().x, 0.7f);
    // The head is much narrower than the shoulders: the top 20% of the bust spans well under half the width.
    float topY = b.max.y - 0.2f * b.size().y;
    float minX = 1e9f, maxX = -1e9f;
    for (const glm::vec3& p : head.mesh.positions)
        if (p.y > topY) {
            minX = std::min(minX, p.x);
            maxX = std::max(maxX, p.x);
        }
    EXPECT_LT(maxX - minX, 0.5f * b.size().x);
}

TEST(DefaultHead, ScalpIsTheTopAndBackOfTheHead)
{
    Head head = loadHead(defaultHeadPath());
    ASSERT_TRUE(head.description.scalp.has_value());
    std::vector<uint32_t> scalp = scalpTriangles(head.mesh, *head.description.scalp);
    double fraction = double(scalp.size()) / double(head.mesh.triangleCount());
    EXPECT_GT(fraction, 0.05);
    EXPECT_LT(fraction, 0.45);
    // Every scalp triangle lies in the upper half of the bust, and none faces the front squarely.
    Bounds b = head.mesh.bounds();
    float meanZ = 0.0f;
    for (uint32_t t : scalp) {
        glm::vec3 c =
            (head.mesh.positions[head.mesh.indices[3 * t]] + head.mesh.positions[head.mesh.indices[3 * t + 1]] +
             head.mesh.positions[head.mesh.indices[3 * t + 2]]) /
            3.0f;
        EXPECT_GT(c.y, b.center().y);
        meanZ += c.z;
    }
    meanZ /= float(scalp.size());
    float headMeanZ = 0.0f;
    for (const glm::vec3& p : head.mesh.positions)
        headMeanZ += p.z;
    headMeanZ /= float(head.mesh.positions.size());
    EXPECT_LT(meanZ, headMeanZ + 0.02f); // the scalp sits toward the back, not over the face
}

TEST(DefaultHead, CollidersCoverTheCraniumFromOutside)
{
    Head head = loadHead(defaultHeadPath());
    ASSERT_GE(head.description.colliders.size(), 3u);
    ASSERT_TRUE(head.description.scalp.has_value());
    // Scalp vertices are inside or within a few millimetres of some collider: the hair will rest there.
    std::vector<uint32_t> scalp = scalpTriangles(head.mesh, *head.description.scalp);
    size_t covered = 0, checked = 0;
    for (uint32_t t : scalp) {
        glm::vec3 p = head.mesh.positions[head.mesh.indices[3 * t]];
        ++checked;
        for (const Ellipsoid& e : head.description.colliders) {
            glm::vec3 local = glm::transpose(rotationXyzDegrees(e.rotationDeg)) * (p - e.center);
            glm::vec3 u = local / (e.radii + glm::vec3(0.005f));
            if (glm::dot(u, u) <= 1.0f) {
                ++covered;
                break;
            }
        }
    }
    EXPECT_GT(double(covered) / double(checked), 0.95);
}

TEST(DefaultHead, GeneratorRebuildsTheCommittedFiles)
{
    std::filesystem::path generator = std::filesystem::path(WISP_BINARY).parent_path() / "wisp_make_head";
    if (!std::filesystem::exists(generator))
        GTEST_SKIP() << "wisp_make_head was not built";
    TempDir dir;
    std::string command = "'" + generator.string() + "' --out-dir '" + dir.path().string() + "' >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0);
    std::filesystem::path models = std::filesystem::path(WISP_SOURCE_DIR) / "models";
    EXPECT_TRUE(test::readFile(dir / "head.obj") == test::readFile(models / "head.obj"))
        << "models/head.obj is stale: run scripts/make_head.sh";
    EXPECT_TRUE(test::readFile(dir / "head.json") == test::readFile(models / "head.json"))
        << "models/head.json is stale: run scripts/make_head.sh";
}

TEST(HeadErrors, MalformedJsonNamesTheByte)
{
    TempDir dir;
    writeFile(dir / "h.json", "{\"mesh\": \"head.obj\",\r\n, }");
    std::string e = errorOf(dir / "h.json");
    EXPECT_NE(e.find("h.json:2: byte 22: malformed JSON"), std::string::npos) << e;
}

TEST(HeadText, AnyLineEndingAndTrailingPaddingRead)
{
    // The same rules as every text file Wisp reads (assets/text.h): LF, CRLF or CR, and NULs or white
    // space after the last character are padding.
    TempDir dir;
    std::string lf = "{\n\"mesh\": \"a.obj\",\n\"up\": [0, 1, 0],\n\"colliders\": [{\"center\": [0, 1, 0], "
                     "\"radii\": [1, 2, 3]}]\n}\n";
    std::string cr = lf, crlf;
    std::replace(cr.begin(), cr.end(), '\n', '\r');
    for (char c : lf)
        crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    for (const std::string& text : {lf, cr, crlf, lf + std::string(5, '\0') + "\r\n", cr + std::string(1, '\0')}) {
        writeFile(dir / "h.json", text);
        HeadDescription d = loadHeadDescription(dir / "h.json");
        ASSERT_EQ(d.colliders.size(), 1u);
        EXPECT_EQ(d.colliders[0].radii, glm::vec3(1, 2, 3));
    }
    // A NUL before the end is named with its line and byte.
    writeFile(dir / "h.json", "{\r\"mesh\": \"a" + std::string(1, '\0') + ".obj\"}");
    std::string e = errorOf(dir / "h.json");
    EXPECT_NE(e.find("h.json:2: byte 12 is a NUL byte inside the text (in '\"a\\x00.obj\"}')"), std::string::npos) << e;
}

TEST(HeadErrors, CoordinatesPastTheFloatMathsRangeAreNamed)
{
    TempDir dir;
    writeFile(dir / "h.json", R"({"mesh": "a.obj", "colliders": [{"center": [0, 1e30, 0], "radii": [1, 1, 1]}]})");
    std::string e = errorOf(dir / "h.json");
    EXPECT_NE(e.find("h.json: 'colliders[0].center[1]' coordinate 1e+30 is out of the range"), std::string::npos) << e;
    // A direction may be any size: it is normalized (in double: a float's square overflows).
    writeFile(dir / "h.json", R"({"mesh": "a.obj", "up": [0, 1e30, 0]})");
    EXPECT_EQ(loadHeadDescription(dir / "h.json").up, glm::vec3(0, 1, 0));
}

TEST(HeadErrors, MissingMeshKeyIsNamed)
{
    TempDir dir;
    writeFile(dir / "h.json", "{\"name\": \"x\"}");
    EXPECT_NE(errorOf(dir / "h.json").find("'mesh' is missing"), std::string::npos);
}

TEST(HeadErrors, NegativeRadiusIsNamed)
{
    TempDir dir;
    writeFile(dir / "h.json", R"({"mesh": "a.obj", "colliders": [{"center": [0,0,0], "radii": [1,-1,1]}]})");
    std::string e = errorOf(dir / "h.json");
    EXPECT_NE(e.find("colliders[0].radii"), std::string::npos) << e;
}

TEST(HeadErrors, WrongShapeIsNamed)
{
    TempDir dir;
    writeFile(dir / "h.json", R"({"mesh": "a.obj", "scalp": {"plane_point": [0,0], "plane_normal": [0,1,0]}})");
    EXPECT_NE(errorOf(dir / "h.json").find("scalp.plane_point"), std::string::npos);
}

TEST(HeadErrors, AFlatHeadIsRefused)
{
    TempDir dir;
    writeFile(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
    try {
        loadHead(dir / "flat.obj");
        FAIL() << "expected an error";
    } catch (const UserError& e) {
        EXPECT_NE(std::string(e.what()).find("flat.obj: the head is flat: its extent along z is 0"), std::string::npos)
            << e.what();
    }
}

TEST(HeadErrors, DescriptionNamingAMissingMesh)
{
    TempDir dir;
    writeFile(dir / "h.json", R"({"mesh": "gone.obj"})");
    try {
        loadHead(dir / "h.json");
        FAIL() << "expected an error";
    } catch (const UserError& e) {
        EXPECT_NE(std::string(e.what()).find("gone.obj"), std::string::npos);
    }
}

// ---- colliders fitted to a bare mesh -----------------------------------------------------------

namespace {

// OBJ text of a closed cube (half side h, its base at y = 0), each face split into n x n quads,
// counter-clockwise seen from outside.
std::string cubeObj(float h, int n)
{
    std::string obj, faces;
    char line[96];
    int next = 1;
    for (int a = 0; a < 3; ++a)
        for (int s : {1, -1}) {
            int u = (a + 1) % 3, v = (a + 2) % 3, base = next;
            for (int i = 0; i <= n; ++i)
                for (int j = 0; j <= n; ++j, ++next) {
                    glm::vec3 p(0.0f);
                    p[a] = float(s) * h;
                    p[u] = h * (2.0f * float(i) / float(n) - 1.0f);
                    p[v] = h * (2.0f * float(j) / float(n) - 1.0f);
                    std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", p.x, p.y + h, p.z);
                    obj += line;
                }
            auto at = [&](int i, int j) { return base + i * (n + 1) + j; };
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    // e_u x e_v = e_a: (i, j), (i+1, j), (i+1, j+1) turns counter-clockwise seen from +a.
                    int p0 = at(i, j), p1 = at(i + 1, j), p2 = at(i + 1, j + 1), p3 = at(i, j + 1);
                    if (s < 0)
                        std::swap(p1, p3);
                    std::snprintf(line, sizeof line, "f %d %d %d\nf %d %d %d\n", p0, p1, p2, p0, p2, p3);
                    faces += line;
                }
        }
    return obj + faces;
}

// The colliders fitted to `mesh` as a grown groom gets them (physics/groomed_head.cpp), measured.
struct Fitted {
    ColliderFit fit;
    std::vector<std::string> warnings;
};
Fitted fitAndMeasure(const Mesh& mesh)
{
    std::vector<Ellipsoid> colliders = fitColliders(mesh);
    std::vector<uint32_t> scalp = scalpTriangles(mesh, defaultScalpRule(colliders.front()));
    inscribeColliders(colliders, mesh, scalp, kInscribedTolerance * mesh.bounds().diagonal());
    return {measureColliderFit(colliders, mesh, scalp, kFitExposedGap), fittedColliderWarnings(mesh, colliders, scalp)};
}

} // namespace

// A cube given as a head: its fitted cranium, pulled under the scalp (the middle of the top face as
// well as its corners: no root starts inside it), leaves most of the scalp far outside it, where
// hair sinks into the cube; so does a cube split into 8 x 8 quads per face. The project's head, a
// bare mesh with fitted colliders, is held well and is said nothing of.
TEST(FittedColliders, ACubeIsSaidToHoldBadlyAndAHeadIsNot)
{
    TempDir dir;
    writeFile(dir / "cube.obj", cubeObj(0.1f, 1));
    writeFile(dir / "cube8.obj", cubeObj(0.1f, 8));
    for (const char* name : {"cube.obj", "cube8.obj"}) {
        Mesh mesh = loadMesh(dir / name);
        Fitted cube = fitAndMeasure(mesh);
        // The scalp outside every collider, within the inscribed tolerance (and a float's rounding).
        EXPECT_LT(cube.fit.intrusion, 1.01f * kInscribedTolerance) << name;
        EXPECT_GT(cube.fit.exposed, 3.0f * kFitExposedLimit) << name;
        ASSERT_EQ(cube.warnings.size(), 1u) << name;
        EXPECT_NE(cube.warnings[0].find("hold its scalp badly, as they do a mesh that is no head"), std::string::npos)
            << cube.warnings[0];
    }
    Fitted head = fitAndMeasure(loadMesh(std::filesystem::path(WISP_SOURCE_DIR) / "models" / "head.obj"));
    EXPECT_LT(head.fit.intrusion, 1.01f * kInscribedTolerance);
    EXPECT_LT(head.fit.exposed, 0.5f * kFitExposedLimit);
    EXPECT_TRUE(head.warnings.empty()) << head.warnings.front();
}
