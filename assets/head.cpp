// assets/head.cpp: head description parsing with errors that name the file and the key.
#include "assets/head.h"

#include "assets/text.h"
#include "core/error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#ifndef WISP_MODELS_DIR
#error "WISP_MODELS_DIR must name the source tree's models folder"
#endif

namespace wisp {

namespace {

using nlohmann::json;

struct Reader {
    std::filesystem::path path;

    [[noreturn]] void fail(const std::string& key, const std::string& what) const
    {
        throw UserError(path.string() + ": '" + key + "' " + what);
    }
    const json& require(const json& object, const std::string& key, const std::string& where) const
    {
        if (!object.contains(key))
            fail(where + key, "is missing");
        return object.at(key);
    }
    float number(const json& value, const std::string& key) const
    {
        if (!value.is_number())
            fail(key, "must be a number");
        double v = value.get<double>();
        if (!std::isfinite(v))
            fail(key, "must be finite");
        return static_cast<float>(v);
    }
    glm::vec3 vec3(const json& value, const std::string& key) const
    {
        if (!value.is_array() || value.size() != 3)
            fail(key, "must be an array of 3 numbers");
        return {number(value[0], key + "[0]"), number(value[1], key + "[1]"), number(value[2], key + "[2]")};
    }
    // A point or a size in the head's units: within kMaxCoordinate, as the mesh's positions.
    glm::vec3 position(const json& value, const std::string& key) const
    {
        glm::vec3 v = vec3(value, key);
        for (int axis = 0; axis < 3; ++axis)
            if (std::string error = coordinateRangeError(v[axis]); !error.empty())
                fail(key + "[" + std::to_string(axis) + "]", error);
        return v;
    }
    glm::vec3 direction(const json& value, const std::string& key) const
    {
        glm::dvec3 v = vec3(value, key); // in double: a float's square overflows past about 1.8e19
        double len = glm::length(v);
        if (!(len >= 1e-6))
            fail(key, "must not be the zero vector");
        return glm::vec3(v / len);
    }
    std::string string(const json& value, const std::string& key) const
    {
        if (!value.is_string())
            fail(key, "must be a string");
        return value.get<std::string>();
    }
};

} // namespace

HeadDescription loadHeadDescription(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw UserError(path.string() + ": cannot open head description");
    std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad())
        throw UserError(path.string() + ": read error");
    // Trailing NULs and white space are padding (JSON takes any line ending as white space).
    std::string_view text = textOf(data);
    checkNoNulBytes(text, bomBytes(data), path, "a head description");
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::parse_error& e) {
        size_t at = e.byte > 0 ? e.byte - 1 : 0; // nlohmann counts bytes from 1
        throw UserError(path.string() + ":" + std::to_string(lineOfByte(text, at)) + ": byte " +
                        std::to_string(at + bomBytes(data)) + ": malformed JSON");
    }
    Reader r{path};
    if (!doc.is_object())
        throw UserError(path.string() + ": a head description must be a JSON object");

    HeadDescription d;
    d.name = doc.contains("name") ? r.string(doc["name"], "name") : path.stem().string();
    d.meshPath = path.parent_path() / r.string(r.require(doc, "mesh", ""), "mesh");
    if (doc.contains("units"))
        d.units = r.string(doc["units"], "units");
    if (doc.contains("up"))
        d.up = r.direction(doc["up"], "up");
    if (doc.contains("front"))
        d.front = r.direction(doc["front"], "front");
    if (doc.contains("scalp")) {
        const json& s = doc["scalp"];
        if (!s.is_object())
            r.fail("scalp", "must be an object");
        ScalpRule rule;
        rule.planePoint = r.position(r.require(s, "plane_point", "scalp."), "scalp.plane_point");
        rule.planeNormal = r.direction(r.require(s, "plane_normal", "scalp."), "scalp.plane_normal");
        if (s.contains("face_direction"))
            rule.faceDirection = r.direction(s["face_direction"], "scalp.face_direction");
        if (s.contains("face_max_dot")) {
            rule.faceMaxDot = r.number(s["face_max_dot"], "scalp.face_max_dot");
            if (rule.faceMaxDot < -1.0f || rule.faceMaxDot > 1.0f)
                r.fail("scalp.face_max_dot", "must be in [-1, 1]");
        }
        d.scalp = rule;
    }
    if (doc.contains("colliders")) {
        const json& list = doc["colliders"];
        if (!list.is_array())
            r.fail("colliders", "must be an array");
        for (size_t i = 0; i < list.size(); ++i) {
            std::string key = "colliders[" + std::to_string(i) + "]";
            const json& c = list[i];
            if (!c.is_object())
                r.fail(key, "must be an object");
            Ellipsoid e;
            e.name = c.contains("name") ? r.string(c["name"], key + ".name") : key;
            e.center = r.position(r.require(c, "center", key + "."), key + ".center");
            e.radii = r.position(r.require(c, "radii", key + "."), key + ".radii");
            if (e.radii.x <= 0.0f || e.radii.y <= 0.0f || e.radii.z <= 0.0f)
                r.fail(key + ".radii", "must all be > 0");
            if (c.contains("rotation_deg"))
                e.rotationDeg = r.vec3(c["rotation_deg"], key + ".rotation_deg");
            d.colliders.push_back(e);
        }
    }
    return d;
}

Head loadHead(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    for (char& c : ext)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    Head head;
    if (ext == ".json") {
        head.description = loadHeadDescription(path);
    } else {
        head.description.name = path.stem().string();
        head.description.meshPath = path;
        head.description.units = "file";
    }
    head.mesh = loadMesh(head.description.meshPath);
    // A head must have depth: colliders are fitted to it and hair grows on and around it.
    glm::vec3 size = head.mesh.bounds().size();
    float largest = std::max({size.x, size.y, size.z});
    const char* axes[3] = {"x", "y", "z"};
    for (int axis = 0; axis < 3; ++axis)
        if (!(size[axis] > 1e-4f * largest))
            throw UserError(head.description.meshPath.string() + ": the head is flat: its extent along " + axes[axis] +
                            " is " + std::to_string(size[axis]) + " of " + std::to_string(largest) +
                            " (a head needs width, height and depth)");
    return head;
}

std::vector<uint32_t> scalpTriangles(const Mesh& mesh, const ScalpRule& rule)
{
    std::vector<uint32_t> out;
    for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::vec3& a = mesh.positions[mesh.indices[3 * t]];
        const glm::vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
        const glm::vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
        glm::vec3 centroid = (a + b + c) / 3.0f;
        glm::vec3 n = glm::cross(b - a, c - a);
        float len = glm::length(n);
        if (len <= 0.0f)
            continue;
        bool above = glm::dot(centroid - rule.planePoint, rule.planeNormal) > 0.0f;
        bool face = glm::dot(n / len, rule.faceDirection) > rule.faceMaxDot;
        if (above && !face)
            out.push_back(t);
    }
    return out;
}

std::filesystem::path defaultHeadPath()
{
    std::error_code ec;
    std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        std::filesystem::path beside = exe.parent_path() / "models" / "head.json";
        if (std::filesystem::exists(beside, ec))
            return beside;
    }
    return std::filesystem::path(WISP_MODELS_DIR) / "head.json";
}

} // namespace wisp
