// assets/mesh.cpp: mesh loading. OBJ files are first checked line by line (numbers parse,
// positions lie in the range Wisp handles, face indices exist) so that a bad file is reported
// with its line; tinyobjloader then reads them. Other formats go through assimp. Normals missing or
// giving no direction (zero) are computed from the triangles.
#include "assets/mesh.h"

#include "assets/text.h"
#include "core/error.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string_view>

namespace wisp {

Mesh makeSphereMesh(uint32_t stacks, uint32_t slices)
{
    Mesh m;
    for (uint32_t i = 0; i <= stacks; ++i) {
        float theta = float(i) / float(stacks) * 3.14159265f;
        for (uint32_t j = 0; j <= slices; ++j) {
            float phi = float(j) / float(slices) * 6.2831853f;
            glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            m.positions.push_back(p);
            m.normals.push_back(p);
        }
    }
    for (uint32_t i = 0; i < stacks; ++i)
        for (uint32_t j = 0; j < slices; ++j) {
            uint32_t a = i * (slices + 1) + j, b = a + slices + 1;
            for (uint32_t k : {a, a + 1, b, a + 1, b + 1, b})
                m.indices.push_back(k);
        }
    m.sourceVertices = m.positions.size();
    return m;
}

Bounds Mesh::bounds() const
{
    Bounds b;
    if (positions.empty())
        return b;
    b.min = b.max = positions.front();
    for (const glm::vec3& p : positions) {
        b.min = glm::min(b.min, p);
        b.max = glm::max(b.max, p);
    }
    return b;
}

namespace {

// A unit vector along `v`, or +y for a zero vector. In double: a float's square overflows past
// about 1.8e19, and a normal of huge but finite components must still come out unit length.
glm::vec3 unitOr(glm::dvec3 v)
{
    double len = glm::length(v);
    return len > 0.0 && std::isfinite(len) ? glm::vec3(v / len) : glm::vec3(0.0f, 1.0f, 0.0f);
}

// A normal that gives no direction: zero (some exporters write "vn 0 0 0" for "none") or not finite.
bool degenerateNormal(glm::dvec3 v)
{
    double len = glm::length(v);
    return !(len > 0.0 && std::isfinite(len));
}

} // namespace

std::vector<glm::vec3> computeVertexNormals(const std::vector<glm::vec3>& positions,
                                            const std::vector<uint32_t>& indices)
{
    // In double: the cross products of finite float coordinates (up to 3.4e38) stay finite.
    std::vector<glm::dvec3> sums(positions.size(), glm::dvec3(0.0));
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        glm::dvec3 a = positions[indices[t]];
        glm::dvec3 b = positions[indices[t + 1]];
        glm::dvec3 c = positions[indices[t + 2]];
        glm::dvec3 n = glm::cross(b - a, c - a); // length = 2 * area: area weighting
        for (size_t k = 0; k < 3; ++k)
            sums[indices[t + k]] += n;
    }
    std::vector<glm::vec3> normals(positions.size());
    for (size_t v = 0; v < sums.size(); ++v)
        normals[v] = unitOr(sums[v]);
    return normals;
}

namespace {

[[noreturn]] void badFile(const std::filesystem::path& path, size_t line, const std::string& what)
{
    throw UserError(path.string() + ":" + std::to_string(line) + ": " + what);
}

// The words of a line as tinyobjloader splits them: on spaces and tabs only.
std::vector<std::string> objWords(std::string_view line)
{
    std::vector<std::string> words;
    std::string_view rest = line;
    while (true) {
        size_t start = rest.find_first_not_of(" \t");
        if (start == std::string_view::npos)
            return words;
        rest.remove_prefix(start);
        size_t end = std::min(rest.find_first_of(" \t"), rest.size());
        words.emplace_back(rest.substr(0, end));
        rest.remove_prefix(end);
    }
}

// Checks the lines tinyobjloader would otherwise accept silently or mis-read: vertex records
// with missing or non-numeric coordinates (or positions past the range Wisp's float math
// handles), and faces whose indices name no vertex or that it would read past (a corner ending in
// '/' takes its last index from the next corner). `text` is textOf the file (no NUL in it); its
// lines end as tinyobjloader ends them ("\n", "\r" or "\r\n"), so the line numbers agree.
void checkObj(const std::filesystem::path& path, std::string_view text)
{
    size_t lineNumber = 0;
    long positions = 0, texcoords = 0, normals = 0;
    for (std::string_view line : splitLines(text)) {
        ++lineNumber;
        std::vector<std::string> args = objWords(line);
        if (args.empty() || args.front()[0] == '#')
            continue;
        std::string key = args.front();
        args.erase(args.begin());
        if (key == "v" || key == "vn" || key == "vt") {
            size_t need = key == "vt" ? 1 : 3;
            if (args.size() < need)
                badFile(path, lineNumber,
                        "'" + key + "' needs " + std::to_string(need) + " numbers, found " +
                            std::to_string(args.size()));
            for (size_t i = 0; i < need; ++i) {
                float value = 0.0f;
                if (std::string error = parseFloatWord(args[i], value); !error.empty())
                    badFile(path, lineNumber, error);
                if (key == "v")
                    if (std::string error = coordinateRangeError(value); !error.empty())
                        badFile(path, lineNumber, "vertex " + std::to_string(positions + 1) + ": " + error);
            }
            (key == "v" ? positions : key == "vn" ? normals : texcoords) += 1;
        } else if (key == "f") {
            if (args.size() < 3)
                badFile(path, lineNumber, "a face needs at least 3 vertices, found " + std::to_string(args.size()));
            for (const std::string& corner : args) {
                if (corner.back() == '/')
                    badFile(path, lineNumber,
                            "face corner '" + quoteText(corner) + "' ends with '/': an index must follow it");
                long counts[3] = {positions, texcoords, normals};
                const char* names[3] = {"vertex", "texture coordinate", "normal"};
                size_t start = 0;
                for (int part = 0; part < 3 && start <= corner.size(); ++part) {
                    size_t slash = corner.find('/', start);
                    std::string field =
                        corner.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
                    start = slash == std::string::npos ? corner.size() + 1 : slash + 1;
                    if (field.empty() && part > 0)
                        continue;
                    long index = 0;
                    auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), index);
                    if (ec != std::errc() || end != field.data() + field.size() || index == 0)
                        badFile(path, lineNumber, "face corner '" + quoteText(corner) + "' is not a valid index");
                    long resolved = index < 0 ? counts[part] + index + 1 : index;
                    if (resolved < 1 || resolved > counts[part])
                        badFile(path, lineNumber,
                                "face corner '" + quoteText(corner) + "' names " + names[part] + " " +
                                    std::to_string(index) + " but only " + std::to_string(counts[part]) +
                                    " are defined before it");
                }
            }
        }
    }
}

Mesh loadObj(const std::filesystem::path& path)
{
    std::ifstream file(path, std::ios::binary);
    if (!file)
        throw UserError(path.string() + ": cannot open mesh file");
    return parseObj(file, path);
}

Mesh loadWithAssimp(const std::filesystem::path& path)
{
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                                aiProcess_GenSmoothNormals |
                                                                aiProcess_PreTransformVertices | aiProcess_SortByPType);
    if (!scene || !scene->mRootNode)
        throw UserError(path.string() + ": cannot read mesh: " + importer.GetErrorString());
    Mesh mesh;
    std::vector<bool> degenerate; // per vertex: its normal gives no direction
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* src = scene->mMeshes[m];
        if (!(src->mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
            continue;
        uint32_t base = static_cast<uint32_t>(mesh.positions.size());
        for (unsigned v = 0; v < src->mNumVertices; ++v) {
            glm::vec3 p(src->mVertices[v].x, src->mVertices[v].y, src->mVertices[v].z);
            for (int axis = 0; axis < 3; ++axis)
                if (std::string error = coordinateRangeError(p[axis]); !error.empty())
                    throw UserError(path.string() + ": vertex " + std::to_string(mesh.positions.size()) + ": " + error);
            mesh.positions.push_back(p);
            glm::dvec3 n = src->mNormals ? glm::dvec3(src->mNormals[v].x, src->mNormals[v].y, src->mNormals[v].z)
                                         : glm::dvec3(0.0);
            degenerate.push_back(degenerateNormal(n));
            mesh.normals.push_back(unitOr(n));
        }
        for (unsigned f = 0; f < src->mNumFaces; ++f) {
            const aiFace& face = src->mFaces[f];
            if (face.mNumIndices != 3)
                continue;
            for (unsigned k = 0; k < 3; ++k)
                mesh.indices.push_back(base + face.mIndices[k]);
        }
    }
    mesh.sourceVertices = mesh.positions.size();
    if (std::find(degenerate.begin(), degenerate.end(), true) != degenerate.end()) {
        std::vector<glm::vec3> smooth = computeVertexNormals(mesh.positions, mesh.indices);
        for (size_t v = 0; v < degenerate.size(); ++v)
            if (degenerate[v])
                mesh.normals[v] = smooth[v];
    }
    return mesh;
}

} // namespace

void checkNotDegenerate(const Mesh& mesh, const std::filesystem::path& path)
{
    double largest = 0.0; // twice the largest triangle's area, in double (float squares overflow)
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        glm::dvec3 a = mesh.positions[mesh.indices[t]];
        glm::dvec3 b = mesh.positions[mesh.indices[t + 1]];
        glm::dvec3 c = mesh.positions[mesh.indices[t + 2]];
        largest = std::max(largest, glm::length(glm::cross(b - a, c - a)));
    }
    if (largest > 0.0)
        return;
    Bounds b = mesh.bounds();
    if (b.diagonal() == 0.0f)
        throw UserError(path.string() + ": the mesh is degenerate: all its " + std::to_string(mesh.sourceVertices) +
                        " vertices lie at one point (" + std::to_string(b.min.x) + ", " + std::to_string(b.min.y) +
                        ", " + std::to_string(b.min.z) + ")");
    throw UserError(path.string() + ": the mesh is degenerate: none of its " + std::to_string(mesh.triangleCount()) +
                    " triangles has an area (its vertices lie on a line)");
}

Mesh parseObj(std::istream& in, const std::filesystem::path& path)
{
    std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad())
        throw UserError(path.string() + ": read error");
    // Trailing NULs and white space are padding; a NUL before the last word is binary data.
    std::string_view text = textOf(data);
    checkNoNulBytes(text, bomBytes(data), path, "OBJ text");
    checkObj(path, text);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warnings, errors;
    std::istringstream file{std::string(text)};
    bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &file, nullptr, true);
    if (!ok)
        throw UserError(path.string() + ": " + (errors.empty() ? std::string("malformed OBJ") : errors));

    // tinyobjloader reports indices it could not resolve only as warnings and returns them: a
    // face it read differently from the check above must still never index past the arrays.
    size_t vertexCount = attrib.vertices.size() / 3, normalCount = attrib.normals.size() / 3;
    for (const tinyobj::shape_t& shape : shapes)
        for (const tinyobj::index_t& idx : shape.mesh.indices)
            if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= vertexCount ||
                (idx.normal_index >= 0 && size_t(idx.normal_index) >= normalCount))
                throw UserError(
                    path.string() + ": a face names a vertex or normal that does not exist" +
                    (warnings.empty() ? std::string() : " (" + warnings.substr(0, warnings.find('\n')) + ")"));

    Mesh mesh;
    mesh.sourceVertices = vertexCount;
    // A corner whose normal gives no direction (zero, not finite) counts as one without a normal.
    std::vector<bool> usable(normalCount);
    for (size_t n = 0; n < normalCount; ++n)
        usable[n] =
            !degenerateNormal(glm::dvec3(attrib.normals[3 * n], attrib.normals[3 * n + 1], attrib.normals[3 * n + 2]));
    std::map<std::pair<int, int>, uint32_t> corners; // (position, normal) -> vertex
    for (const tinyobj::shape_t& shape : shapes) {
        for (const tinyobj::index_t& idx : shape.mesh.indices) {
            int normal = idx.normal_index >= 0 && usable[size_t(idx.normal_index)] ? idx.normal_index : -1;
            auto [it, inserted] =
                corners.try_emplace({idx.vertex_index, normal}, static_cast<uint32_t>(mesh.positions.size()));
            if (inserted) {
                const float* p = &attrib.vertices[3 * static_cast<size_t>(idx.vertex_index)];
                mesh.positions.emplace_back(p[0], p[1], p[2]);
                if (normal >= 0) {
                    const float* n = &attrib.normals[3 * static_cast<size_t>(normal)];
                    mesh.normals.push_back(unitOr(glm::dvec3(n[0], n[1], n[2])));
                } else {
                    mesh.normals.emplace_back(0.0f);
                }
            }
            mesh.indices.push_back(it->second);
        }
    }
    bool anyMissing = false;
    for (const auto& [key, vertex] : corners)
        anyMissing = anyMissing || key.second < 0;
    if (anyMissing) { // some corners had no usable normal: area-weighted normals over shared positions
        std::vector<glm::vec3> smooth = computeVertexNormals(mesh.positions, mesh.indices);
        for (const auto& [key, vertex] : corners)
            if (key.second < 0)
                mesh.normals[vertex] = smooth[vertex];
    }
    return mesh;
}

Mesh loadMesh(const std::filesystem::path& path)
{
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw UserError(path.string() + ": no such mesh file");
    if (std::filesystem::is_directory(path, ec))
        throw UserError(path.string() + ": is a directory, not a mesh file");
    std::string ext = path.extension().string();
    for (char& c : ext)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    Mesh mesh = ext == ".obj" ? loadObj(path) : loadWithAssimp(path);
    if (mesh.indices.empty())
        throw UserError(path.string() + ": the mesh holds no triangles (" + std::to_string(mesh.sourceVertices) +
                        " vertices and no faces)");
    checkNotDegenerate(mesh, path);
    return mesh;
}

} // namespace wisp
