// tests/test_mesh.cpp: mesh loading: real files from ../shared/data, n-gon triangulation, CRLF,
// generated normals, other formats through assimp, and every malformed-file path with its line.
#include "assets/mesh.h"
#include "core/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

using namespace wisp;
using wisp::test::TempDir;
using wisp::test::writeFile;

namespace {

std::string errorOf(const std::filesystem::path& path)
{
    try {
        loadMesh(path);
    } catch (const UserError& e) {
        return e.what();
    }
    return "";
}

void expectUnitNormals(const Mesh& mesh)
{
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (const glm::vec3& n : mesh.normals)
        ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
}

} // namespace

TEST(Mesh, LoadsSintelBustWithItsCounts)
{
    WISP_REQUIRE_DATA(path, "sintel/sintel.obj");
    Mesh mesh = loadMesh(path);
    EXPECT_EQ(mesh.sourceVertices, 3046u);  // ATTRIBUTION.md: 3,046 vertices
    EXPECT_EQ(mesh.triangleCount(), 5952u); // and 5,952 triangles
    expectUnitNormals(mesh);
    Bounds b = mesh.bounds();
    // Metres, y up: a bust some tens of centimetres tall.
    EXPECT_GT(b.size().y, 0.2f);
    EXPECT_LT(b.size().y, 1.0f);
}

TEST(Mesh, LoadsTressFxHeadInCentimetres)
{
    WISP_REQUIRE_DATA(path, "tressfx-text/head_max4.obj");
    Mesh mesh = loadMesh(path);
    EXPECT_GT(mesh.triangleCount(), 1000u);
    expectUnitNormals(mesh);
    EXPECT_GT(mesh.bounds().diagonal(), 10.0f); // centimetres, kept as they are
}

TEST(Mesh, TriangulatesQuadsAndAcceptsCrlf)
{
    TempDir dir;
    writeFile(dir / "quad.obj",
              "# a unit quad and a pentagon\r\nv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\n"
              "v 2 0 0\r\nv 3 0 0\r\nv 3.5 1 0\r\nv 2.5 2 0\r\nv 1.5 1 0\r\nf 1 2 3 4\r\nf 5 6 7 8 9\r\n");
    Mesh mesh = loadMesh(dir / "quad.obj");
    EXPECT_EQ(mesh.triangleCount(), 2u + 3u);
    EXPECT_EQ(mesh.sourceVertices, 9u);
    expectUnitNormals(mesh);
    // No normals in the file: generated ones face +z for a CCW quad in the xy plane.
    for (const glm::vec3& n : mesh.normals)
        EXPECT_GT(n.z, 0.99f);
}

TEST(Mesh, KeepsFileNormalsAndNegativeIndices)
{
    TempDir dir;
    writeFile(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -2\nf -3//1 -2//1 -1//1\n");
    Mesh mesh = loadMesh(dir / "tri.obj");
    ASSERT_EQ(mesh.triangleCount(), 1u);
    for (const glm::vec3& n : mesh.normals)
        EXPECT_NEAR(n.z, -1.0f, 1e-6f); // the file's normal, normalized
}

TEST(Mesh, LoadsOtherFormatsThroughAssimp)
{
    TempDir dir;
    writeFile(dir / "tri.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n2 0 0\n2 2 0\n0 2 0\n4 0 1 2 3\n");
    Mesh mesh = loadMesh(dir / "tri.ply");
    EXPECT_EQ(mesh.triangleCount(), 2u);
    expectUnitNormals(mesh);
    EXPECT_FLOAT_EQ(mesh.bounds().max.x, 2.0f);
}

TEST(Mesh, ComputedNormalsAreAreaWeighted)
{
    // Two triangles sharing vertex 0: a big one facing +z and a small one facing +x.
    std::vector<glm::vec3> p = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, -1}, {0, 1, 0}};
    std::vector<uint32_t> idx = {0, 1, 2, 0, 3, 4};
    std::vector<glm::vec3> n = computeVertexNormals(p, idx);
    EXPECT_GT(n[0].z, 0.99f); // dominated by the big triangle
    EXPECT_GT(n[0].x, 0.0f);
    EXPECT_NEAR(n[3].x, 1.0f, 1e-6f);
}

TEST(MeshErrors, MissingFileNamesThePath)
{
    std::string e = errorOf("/nonexistent/head.obj");
    EXPECT_NE(e.find("/nonexistent/head.obj"), std::string::npos) << e;
    EXPECT_NE(e.find("no such"), std::string::npos) << e;
}

TEST(MeshErrors, BadNumberNamesTheLine)
{
    TempDir dir;
    writeFile(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 banana 0\nf 1 2 3\n");
    std::string e = errorOf(dir / "bad.obj");
    EXPECT_NE(e.find("bad.obj:3:"), std::string::npos) << e;
    EXPECT_NE(e.find("banana"), std::string::npos) << e;
}

TEST(MeshErrors, ShortVertexNamesTheLine)
{
    TempDir dir;
    writeFile(dir / "bad.obj", "v 0 0 0\nv 1 0\n");
    EXPECT_NE(errorOf(dir / "bad.obj").find("bad.obj:2:"), std::string::npos);
}

TEST(MeshErrors, FaceIndexOutOfRangeNamesTheLine)
{
    TempDir dir;
    writeFile(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 7\n");
    std::string e = errorOf(dir / "bad.obj");
    EXPECT_NE(e.find("bad.obj:5:"), std::string::npos) << e;
    EXPECT_NE(e.find("only 3"), std::string::npos) << e;
}

TEST(MeshErrors, DegenerateFaceNamesTheLine)
{
    TempDir dir;
    writeFile(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
    EXPECT_NE(errorOf(dir / "bad.obj").find("bad.obj:3:"), std::string::npos);
}

TEST(MeshErrors, NoTrianglesIsAnError)
{
    TempDir dir;
    writeFile(dir / "empty.obj", "# nothing\nv 0 0 0\n");
    EXPECT_NE(errorOf(dir / "empty.obj").find("no triangles"), std::string::npos);
}

TEST(MeshErrors, NoFacesSaysSo)
{
    TempDir dir;
    writeFile(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    std::string e = errorOf(dir / "points.obj");
    EXPECT_NE(e.find("3 vertices and no faces"), std::string::npos) << e;
}

TEST(MeshErrors, BinaryDataNamedObjIsNotOBJText)
{
    // An ELF executable passed as a head: it was "the mesh holds no triangles".
    TempDir dir;
    std::string elf("\x7f"
                    "ELF\x02\x01\x01\0\0\0\0\0\0\0\0\0\x03\0>\0",
                    20);
    writeFile(dir / "head.obj", elf + std::string(200, '\x01'));
    std::string e = errorOf(dir / "head.obj");
    EXPECT_NE(e.find("head.obj:1: byte 7 is a NUL byte inside the text (in '\\x7FELF\\x02\\x01\\x01\\x00"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("OBJ text holds none but as padding at the end of the file (binary data?)"), std::string::npos)
        << e;
    writeFile(dir / "late.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n# x") + '\0' + "y\n");
    e = errorOf(dir / "late.obj");
    EXPECT_NE(e.find("late.obj:5: byte 35 is a NUL byte inside the text (in 'x\\x00y')"), std::string::npos) << e;
}

TEST(MeshErrors, DegenerateMeshesAreRefused)
{
    // Every vertex at one point: simulate printed -nan and render wrote a blank picture.
    TempDir dir;
    writeFile(dir / "point.obj", "v 1 2 3\nv 1 2 3\nv 1 2 3\nv 1 2 3\nf 1 2 3\nf 1 3 4\n");
    std::string e = errorOf(dir / "point.obj");
    EXPECT_NE(e.find("point.obj: the mesh is degenerate: all its 4 vertices lie at one point (1.0"), std::string::npos)
        << e;
    writeFile(dir / "line.obj", "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n");
    e = errorOf(dir / "line.obj");
    EXPECT_NE(e.find("none of its 1 triangles has an area"), std::string::npos) << e;
    writeFile(dir / "line.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                "0 0 0\n0 0 0\n0 0 0\n3 0 1 2\n");
    e = errorOf(dir / "line.ply");
    EXPECT_NE(e.find("degenerate"), std::string::npos) << e;
}

TEST(MeshErrors, GarbageForAssimpNamesTheFile)
{
    TempDir dir;
    writeFile(dir / "junk.fbx", "this is not an fbx file at all");
    std::string e = errorOf(dir / "junk.fbx");
    EXPECT_NE(e.find("junk.fbx"), std::string::npos) << e;
}

TEST(MeshErrors, DirectoryIsNotAMesh)
{
    TempDir dir;
    EXPECT_NE(errorOf(dir.path()).find("directory"), std::string::npos);
}

// ---- Found by fuzzing (fuzz/fuzz_obj.cpp) -------------------------------------------------------

TEST(MeshErrors, CornerEndingInSlashNamesTheLine)
{
    // tinyobjloader reads the missing index of "3/3/" from the next corner (normal 2 of 1) and only
    // warns; Wisp then read past the normals (heap overflow). The fuzzer's input, minimized:
    TempDir dir;
    writeFile(dir / "bad.obj",
              "v 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/ 2/2/1\n");
    std::string e = errorOf(dir / "bad.obj");
    EXPECT_NE(e.find("bad.obj:8:"), std::string::npos) << e;
    EXPECT_NE(e.find("'3/3/'"), std::string::npos) << e;
    writeFile(dir / "bad.obj", "v 1 0 0\nv 1 1 0\nv 0 1 0\nf 1// 2// 3//\n");
    EXPECT_NE(errorOf(dir / "bad.obj").find("bad.obj:4:"), std::string::npos);
}

TEST(MeshErrors, LinesEndAtABareCarriageReturnAsInTinyobjloader)
{
    // Old Mac line endings: tinyobjloader ends lines at "\r", so the check must too, or a face
    // naming a missing vertex reaches the loader unchecked (it read past the positions).
    TempDir dir;
    writeFile(dir / "cr.obj", "v 0 0 0\rv 1 0 0\rf 1 2 3\r");
    std::string e = errorOf(dir / "cr.obj");
    EXPECT_NE(e.find("cr.obj:3:"), std::string::npos) << e;
    EXPECT_NE(e.find("only 2"), std::string::npos) << e;
    writeFile(dir / "cr.obj", "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r");
    EXPECT_EQ(loadMesh(dir / "cr.obj").triangleCount(), 1u);
}

TEST(MeshErrors, WordsSplitOnSpacesAndTabsOnlyAsInTinyobjloader)
{
    // "v\v1 2 3" is no vertex to tinyobjloader (its keys end at a space or tab): the face naming it
    // is refused with its line instead of read past the positions.
    TempDir dir;
    writeFile(dir / "vt.obj", "v 0 0 0\nv 1 0 0\nv\v0 1 0\nf 1 2 3\n");
    std::string e = errorOf(dir / "vt.obj");
    EXPECT_NE(e.find("vt.obj:4:"), std::string::npos) << e;
}

TEST(Mesh, HugeCoordinatesStillGiveUnitNormals)
{
    // Cross products of coordinates near the float maximum overflow in float; normals are summed
    // and normalized in double, so they stay unit length (they were NaN or zero). (A file with such
    // positions is refused, MeshErrors.PositionsPastTheFloatMathsRangeNameTheLine; its normals are not.)
    std::vector<glm::vec3> n = computeVertexNormals({{-3e38f, 0, 0}, {3e38f, 0, 0}, {0, 3e38f, 0}}, {0, 1, 2});
    for (const glm::vec3& v : n)
        EXPECT_NEAR(v.z, 1.0f, 1e-6f);
    TempDir dir;
    writeFile(dir / "big.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 3e38 3e38 0\nf 1//1 2//1 3//1\n");
    Mesh mesh = loadMesh(dir / "big.obj");
    expectUnitNormals(mesh);
    EXPECT_NEAR(mesh.normals[0].x, std::sqrt(0.5f), 1e-6f);
}

// ---- text as people's tools write it -------------------------------------------------

namespace {

// An octahedron of radius 2 around (1, 2, 3): every vertex's true normal points away from the centre.
const std::string kOctahedron = "v 3 2 3\nv -1 2 3\nv 1 4 3\nv 1 0 3\nv 1 2 5\nv 1 2 1\n";
const char* kOctahedronFaces[8] = {"1 3 5", "3 2 5", "2 4 5", "4 1 5", "3 1 6", "2 3 6", "4 2 6", "1 4 6"};

void expectOutwardNormals(const Mesh& mesh)
{
    expectUnitNormals(mesh);
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        glm::vec3 out = glm::normalize(mesh.positions[v] - glm::vec3(1, 2, 3));
        EXPECT_GT(glm::dot(mesh.normals[v], out), 0.99f) << "vertex " << v;
    }
}

} // namespace

TEST(MeshText, TrailingNulsAndWhiteSpaceArePadding)
{
    // Some exporters end a file with a NUL: it was "binary data, not OBJ text".
    TempDir dir;
    std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    writeFile(dir / "nul.obj", tri + std::string(1, '\0'));
    EXPECT_EQ(loadMesh(dir / "nul.obj").triangleCount(), 1u);
    writeFile(dir / "padded.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3" + std::string(40, '\0') + "\r\n \t");
    EXPECT_EQ(loadMesh(dir / "padded.obj").triangleCount(), 1u);
    // A NUL before the padding is still refused, with its line, byte and word.
    writeFile(dir / "inside.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1" + std::string(1, '\0') + "5 0\nf 1 2 3\n" + std::string(3, '\0'));
    std::string e = errorOf(dir / "inside.obj");
    EXPECT_NE(e.find("inside.obj:3: byte 21 is a NUL byte inside the text (in '1\\x005')"), std::string::npos) << e;
    EXPECT_EQ(e.find('\0'), std::string::npos);
}

TEST(MeshText, NumbersTooSmallForAFloatReadAsZero)
{
    // 1.58480958e-48 is finite: it was "not a finite number". In a float it underflows to 0.
    TempDir dir;
    writeFile(dir / "tiny.obj", "v 0 0 1.58480958e-48\nv 1 0 -1e-300\nv 0 1 1e-400\nf 1 2 3\n");
    Mesh mesh = loadMesh(dir / "tiny.obj");
    ASSERT_EQ(mesh.positions.size(), 3u);
    for (const glm::vec3& p : mesh.positions)
        EXPECT_EQ(p.z, 0.0f);
    writeFile(dir / "huge.obj", "v 0 0 0\nv 1 0 4e38\nv 0 1 0\nf 1 2 3\n");
    std::string e = errorOf(dir / "huge.obj");
    EXPECT_NE(e.find("huge.obj:2: '4e38' is beyond the float range (+-3.4e38)"), std::string::npos) << e;
    writeFile(dir / "inf.obj", "v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n");
    e = errorOf(dir / "inf.obj");
    EXPECT_NE(e.find("inf.obj:2: 'inf' is not a finite number"), std::string::npos) << e;
}

TEST(MeshText, ZeroNormalsAreComputedFromTheTriangles)
{
    // A head whose normals were all "vn 0 0 0" was drawn flat and unlit (every normal became +y).
    TempDir dir;
    std::string zero = kOctahedron + "vn 0 0 0\n";
    for (const char* f : kOctahedronFaces) {
        std::string face = f;
        zero += "f " + face.replace(face.find(' '), 1, "//1 ").replace(face.rfind(' '), 1, "//1 ") + "//1\n";
    }
    writeFile(dir / "zero.obj", zero);
    Mesh mesh = loadMesh(dir / "zero.obj");
    EXPECT_EQ(mesh.positions.size(), 6u); // one vertex per position: the corners share their normals
    expectOutwardNormals(mesh);
    // The same through assimp (a PLY with normal properties, all zero).
    std::string ply = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
                      "property float nx\nproperty float ny\nproperty float nz\nelement face 8\n"
                      "property list uchar int vertex_indices\nend_header\n";
    for (const char* v : {"3 2 3", "-1 2 3", "1 4 3", "1 0 3", "1 2 5", "1 2 1"})
        ply += std::string(v) + " 0 0 0\n";
    for (const char* f : kOctahedronFaces) {
        int a = 0, b = 0, c = 0;
        std::sscanf(f, "%d %d %d", &a, &b, &c);
        ply += "3 " + std::to_string(a - 1) + " " + std::to_string(b - 1) + " " + std::to_string(c - 1) + "\n";
    }
    writeFile(dir / "zero.ply", ply);
    expectOutwardNormals(loadMesh(dir / "zero.ply"));
    // Usable normals in the same file are kept; only the zero ones are computed.
    writeFile(dir / "some.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nvn 1 0 0\nf 1//1 2//2 3//1\n");
    mesh = loadMesh(dir / "some.obj");
    for (size_t v = 0; v < mesh.positions.size(); ++v)
        EXPECT_NEAR(mesh.positions[v].x == 1.0f ? mesh.normals[v].x : mesh.normals[v].z, 1.0f, 1e-6f) << v;
}

TEST(MeshErrors, PositionsPastTheFloatMathsRangeNameTheLine)
{
    // A head scaled to 1e30 was "hair strand 0 has a zero-length segment": no file named, the hair blamed.
    TempDir dir;
    writeFile(dir / "far.obj", "v 0 0 0\nv 1e30 0 0\nv 0 1e30 0\nf 1 2 3\n");
    std::string e = errorOf(dir / "far.obj");
    EXPECT_NE(e.find("far.obj:2: vertex 2: coordinate 1e+30 is out of the range Wisp's float math handles"),
              std::string::npos)
        << e;
    writeFile(dir / "far.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n1 0 0\n0 -5e20 0\n3 0 1 2\n");
    e = errorOf(dir / "far.ply");
    EXPECT_NE(e.find("far.ply: vertex 2: coordinate -5e+20 is out of the range"), std::string::npos) << e;
    // Normals are directions: any finite size is fine.
    writeFile(dir / "ok.obj", "v 0 0 0\nv 1e9 0 0\nv 0 1e9 0\nvn 0 0 1e30\nf 1//1 2//1 3//1\n");
    EXPECT_EQ(loadMesh(dir / "ok.obj").triangleCount(), 1u);
}

TEST(MeshText, BareCarriageReturnsAndCrlfReadAsLineFeeds)
{
    TempDir dir;
    std::string lf = kOctahedron;
    for (const char* f : kOctahedronFaces)
        lf += "f " + std::string(f) + "\n";
    std::string cr = lf, crlf;
    std::replace(cr.begin(), cr.end(), '\n', '\r');
    for (char c : lf)
        crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    for (const auto& [name, text] : {std::pair{"lf.obj", lf}, std::pair{"cr.obj", cr}, std::pair{"crlf.obj", crlf}}) {
        writeFile(dir / name, text);
        Mesh mesh = loadMesh(dir / name);
        EXPECT_EQ(mesh.triangleCount(), 8u) << name;
        expectOutwardNormals(mesh);
    }
}
