// assets/signed_distance.cpp: pseudonormals of a mesh's features over its welded vertices, and the
// exact signed distance through the closest triangle.
#include "assets/signed_distance.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace wisp {

namespace {

// Vertices welded where they lie within `eps` of each other (an exact weld leaves a sphere's pole,
// whose copies differ in the last bits, as slivers of any normal): each vertex takes the weld of
// the first earlier vertex within eps, found through a hash grid of eps cells.
std::vector<uint32_t> weldVertices(const std::vector<glm::vec3>& positions, float eps)
{
    struct CellHash {
        size_t operator()(const glm::ivec3& c) const
        {
            return size_t((uint64_t(uint32_t(c.x)) * 73856093u) ^ (uint64_t(uint32_t(c.y)) * 19349663u) ^
                          (uint64_t(uint32_t(c.z)) * 83492791u));
        }
    };
    std::unordered_map<glm::ivec3, std::vector<uint32_t>, CellHash> grid;
    std::vector<uint32_t> weld(positions.size());
    std::vector<glm::vec3> representative;
    for (size_t v = 0; v < positions.size(); ++v) {
        glm::vec3 p = positions[v];
        glm::ivec3 cell = glm::ivec3(glm::floor(p / eps));
        uint32_t found = UINT32_MAX;
        for (int dz = -1; dz <= 1 && found == UINT32_MAX; ++dz)
            for (int dy = -1; dy <= 1 && found == UINT32_MAX; ++dy)
                for (int dx = -1; dx <= 1 && found == UINT32_MAX; ++dx) {
                    auto it = grid.find(cell + glm::ivec3(dx, dy, dz));
                    if (it == grid.end())
                        continue;
                    for (uint32_t w : it->second)
                        if (glm::length(representative[w] - p) <= eps) {
                            found = w;
                            break;
                        }
                }
        if (found == UINT32_MAX) {
            found = uint32_t(representative.size());
            representative.push_back(p);
            grid[cell].push_back(found);
        }
        weld[v] = found;
    }
    return weld;
}

// The angle at corner `a` of triangle abc (0 for a degenerate corner).
float cornerAngle(glm::vec3 a, glm::vec3 b, glm::vec3 c)
{
    glm::vec3 u = b - a, v = c - a;
    float lu = glm::length(u), lv = glm::length(v);
    if (!(lu > 0.0f) || !(lv > 0.0f))
        return 0.0f;
    return std::acos(std::clamp(glm::dot(u, v) / (lu * lv), -1.0f, 1.0f));
}

} // namespace

std::vector<gpu::SdfTriangle> sdfTriangles(const Mesh& mesh)
{
    // Vertices welded (a mesh split where its normals part is one surface) within a millionth of its
    // size; a triangle with two corners welded together is a sliver of no normal.
    std::vector<uint32_t> weld = weldVertices(mesh.positions, 1e-6f * mesh.bounds().diagonal());
    size_t welded = weld.empty() ? 0 : size_t(*std::max_element(weld.begin(), weld.end())) + 1;
    size_t triangles = mesh.triangleCount();
    std::vector<glm::vec3> faceNormal(triangles);
    std::vector<glm::dvec3> vertexNormal(welded, glm::dvec3(0.0));
    std::unordered_map<uint64_t, glm::dvec3> edgeNormal;
    edgeNormal.reserve(triangles * 2);
    auto edgeKey = [&](uint32_t i, uint32_t j) {
        uint64_t a = weld[i], b = weld[j];
        return a < b ? (a << 32) | b : (b << 32) | a;
    };
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t* idx = &mesh.indices[3 * t];
        glm::vec3 p[3] = {mesh.positions[idx[0]], mesh.positions[idx[1]], mesh.positions[idx[2]]};
        glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
        float len = glm::length(n);
        bool sliver = weld[idx[0]] == weld[idx[1]] || weld[idx[1]] == weld[idx[2]] || weld[idx[2]] == weld[idx[0]];
        n = len > 0.0f && !sliver ? n / len : glm::vec3(0.0f);
        faceNormal[t] = n;
        for (int c = 0; c < 3; ++c) {
            vertexNormal[weld[idx[c]]] += glm::dvec3(n) * double(cornerAngle(p[c], p[(c + 1) % 3], p[(c + 2) % 3]));
            edgeNormal[edgeKey(idx[c], idx[(c + 1) % 3])] += glm::dvec3(n);
        }
    }
    std::vector<gpu::SdfTriangle> out(triangles);
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t* idx = &mesh.indices[3 * t];
        gpu::SdfTriangle& s = out[t];
        s.a = glm::vec4(mesh.positions[idx[0]], 0.0f);
        s.b = glm::vec4(mesh.positions[idx[1]], 0.0f);
        s.c = glm::vec4(mesh.positions[idx[2]], 0.0f);
        s.face = glm::vec4(faceNormal[t], 0.0f);
        s.edgeAB = glm::vec4(glm::vec3(edgeNormal[edgeKey(idx[0], idx[1])]), 0.0f);
        s.edgeBC = glm::vec4(glm::vec3(edgeNormal[edgeKey(idx[1], idx[2])]), 0.0f);
        s.edgeCA = glm::vec4(glm::vec3(edgeNormal[edgeKey(idx[2], idx[0])]), 0.0f);
        s.vertexA = glm::vec4(glm::vec3(vertexNormal[weld[idx[0]]]), 0.0f);
        s.vertexB = glm::vec4(glm::vec3(vertexNormal[weld[idx[1]]]), 0.0f);
        s.vertexC = glm::vec4(glm::vec3(vertexNormal[weld[idx[2]]]), 0.0f);
    }
    return out;
}

MeshSignedDistance::MeshSignedDistance(const Mesh& mesh) : closest_(mesh), triangles_(sdfTriangles(mesh)) {}

MeshSignedDistance::Result MeshSignedDistance::query(glm::vec3 p) const
{
    MeshDistance::Closest c = closest_.closest(p);
    Result r;
    if (c.triangle >= triangles_.size())
        return {INFINITY, p, 0};
    r.triangle = c.triangle;
    r.point = c.point;
    float sign = gpu::sdfSignedDistance(p, triangles_[c.triangle]) < 0.0f ? -1.0f : 1.0f;
    r.distance = sign * c.distance;
    return r;
}

} // namespace wisp
