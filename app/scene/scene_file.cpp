// app/scene/scene_file.cpp: scene files read and checked value by value (errors name the file and a
// JSON pointer), written back atomically, and applied to the command line's options.
#include "app/scene/scene_file.h"

#include "app/settings/value_text.h"
#include "assets/text.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "physics/strand_set.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <memory>

#ifndef WISP_SOURCE_DIR
#error "WISP_SOURCE_DIR must name the source tree (the shared data folder is beside it)"
#endif

namespace wisp {

namespace {

// Ordered, so that settings apply in the file's order and saved files keep a readable order.
using Json = nlohmann::ordered_json;

constexpr int kSceneVersion = 1;
constexpr const char* kSharedPrefix = "shared:";

// RFC 6901: '~' and '/' in a key are escaped.
std::string pointerTo(const std::string& parent, const std::string& key)
{
    std::string escaped;
    for (char c : key)
        escaped += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    return parent + "/" + escaped;
}

std::string pointerTo(const std::string& parent, size_t index)
{
    return parent + "/" + std::to_string(index);
}

// Reads values of one file; every failure names the file and the value's JSON pointer.
struct Reader {
    std::filesystem::path file;

    [[noreturn]] void fail(const std::string& pointer, const std::string& what) const
    {
        throw UserError(file.string() + ": " + (pointer.empty() ? std::string("the document") : pointer) + ": " + what);
    }
    void expect(const Json& v, const std::string& pointer, bool ok, const std::string& wanted) const
    {
        if (!ok)
            fail(pointer, "must be " + wanted + ", got " + jsonTypeName(v));
    }
    // An object whose keys are all among `known`.
    void object(const Json& v, const std::string& pointer, const std::vector<std::string>& known) const
    {
        expect(v, pointer, v.is_object(), "an object");
        for (const auto& item : v.items()) {
            const std::string& key = item.key(); // clang 14 lambdas cannot capture a structured binding
            if (std::find(known.begin(), known.end(), key) == known.end()) {
                std::string names;
                for (const std::string& k : known)
                    names += (names.empty() ? "" : ", ") + k;
                fail(pointerTo(pointer, key), "unknown key (known: " + names + ")");
            }
        }
    }
    double number(const Json& v, const std::string& pointer, const Range& range, const std::string& unit = "") const
    {
        expect(v, pointer, v.is_number(), "a number");
        double d = v.get<double>();
        if (!std::isfinite(d))
            fail(pointer, "must be a finite number");
        if (!range.contains(d))
            fail(pointer, numberText(d) + " is out of range: allowed " + rangeText(range, unit));
        return d;
    }
    float real(const Json& v, const std::string& pointer, const Range& range, const std::string& unit = "") const
    {
        return float(number(v, pointer, range, unit));
    }
    bool boolean(const Json& v, const std::string& pointer) const
    {
        expect(v, pointer, v.is_boolean(), "true or false");
        return v.get<bool>();
    }
    std::string string(const Json& v, const std::string& pointer) const
    {
        expect(v, pointer, v.is_string(), "a string");
        return v.get<std::string>();
    }
    // An array of `n` numbers, each within `range`.
    std::vector<float> numbers(const Json& v, const std::string& pointer, size_t n, const Range& range,
                               const std::string& unit) const
    {
        expect(v, pointer, v.is_array(), "an array of " + std::to_string(n) + " numbers");
        if (v.size() != n)
            fail(pointer, "must hold " + std::to_string(n) + " numbers, got " + std::to_string(v.size()));
        std::vector<float> out;
        for (size_t i = 0; i < n; ++i)
            out.push_back(real(v[i], pointerTo(pointer, i), range, unit));
        return out;
    }
    glm::vec3 vec3(const Json& v, const std::string& pointer, const Range& range, const std::string& unit) const
    {
        std::vector<float> n = numbers(v, pointer, 3, range, unit);
        return {n[0], n[1], n[2]};
    }
    // x, y, z, radius (head units).
    glm::vec4 sphere(const Json& v, const std::string& pointer) const
    {
        expect(v, pointer, v.is_array() && v.size() == 4, "an array of 4 numbers x, y, z, radius");
        glm::vec3 c(real(v[0], pointerTo(pointer, 0), kPositionRange, "head units"),
                    real(v[1], pointerTo(pointer, 1), kPositionRange, "head units"),
                    real(v[2], pointerTo(pointer, 2), kPositionRange, "head units"));
        return {c, real(v[3], pointerTo(pointer, 3), kRadiusRange, "head units")};
    }
    // A value of the setting `name`, checked by the settings table (its range, its words).
    SettingValue setting(const Json& v, const std::string& pointer, const char* name) const
    {
        return settingFromJson(settingSpec(name), v, file.string() + ": " + pointer);
    }
    float settingReal(const Json& v, const std::string& pointer, const char* name) const
    {
        return float(setting(v, pointer, name).number);
    }
    glm::vec3 settingVector(const Json& v, const std::string& pointer, const char* name) const
    {
        return glm::vec3(setting(v, pointer, name).vector);
    }
};

// The keys of `section`'s own (not settings), then its settings' names: what the section takes.
std::vector<std::string> sectionKnown(SceneSection section, std::initializer_list<const char*> own)
{
    std::vector<std::string> known(own.begin(), own.end());
    for (const SceneSectionKey& k : sceneSectionKeys(section)) {
        known.push_back(k.name);
        if (!k.alias.empty())
            known.push_back(k.alias);
    }
    return known;
}

// The settings of `section` that `v` holds (under their names or older aliases), checked by the
// settings table, as NAME=VALUE in the file's order. Part settings take numbers only here: leaving
// the key out is what their unset word ("part": each part's own) says.
SceneSettings readSectionSettings(const Reader& r, const Json& v, const std::string& at, SceneSection section)
{
    SceneSettings out;
    for (const auto& item : v.items()) {
        const std::string& key = item.key();
        const std::vector<SceneSectionKey>& keys = sceneSectionKeys(section);
        auto k = std::find_if(keys.begin(), keys.end(),
                              [&](const SceneSectionKey& s) { return key == s.name || key == s.alias; });
        if (k == keys.end())
            continue;
        std::string pointer = pointerTo(at, key);
        if (std::any_of(out.begin(), out.end(), [&](const auto& done) { return done.first == k->name; }))
            r.fail(pointer, "gives " + k->name + " again (as " + k->name + " and " + k->alias + "): give it once");
        const SettingSpec& spec = settingSpec(k->name);
        if (spec.optional())
            r.expect(item.value(), pointer, item.value().is_number(), "a number");
        out.emplace_back(spec.name, settingText(spec, r.setting(item.value(), pointer, spec.name.c_str())));
    }
    return out;
}

void readHair(const Reader& r, const Json& v, SceneHair& hair)
{
    const std::string at = "/hair";
    r.object(v, at, sectionKnown(SceneSection::Hair, {"files", "scale", "offset", "z_up", "mirror_z", "half_turn"}));
    auto has = [&](const char* key) { return v.contains(key); };
    auto p = [&](const char* key) { return pointerTo(at, key); };
    hair.settings = readSectionSettings(r, v, at, SceneSection::Hair);
    if (has("scale"))
        hair.scale = r.real(v["scale"], p("scale"), kHairScaleRange);
    if (has("offset"))
        hair.offset = r.vec3(v["offset"], p("offset"), kPositionRange, "head units");
    if (has("z_up"))
        hair.zUp = r.boolean(v["z_up"], p("z_up"));
    if (has("mirror_z"))
        hair.mirrorZ = r.boolean(v["mirror_z"], p("mirror_z"));
    if (has("half_turn"))
        hair.halfTurn = r.boolean(v["half_turn"], p("half_turn"));
    if (has("files")) {
        const Json& files = v["files"];
        r.expect(files, p("files"), files.is_array(), "an array of file names (or objects with \"file\")");
        if (files.empty() || files.size() > gpu::kSimMaxParts)
            r.fail(p("files"), "must name 1 to " + std::to_string(gpu::kSimMaxParts) + " hair files, got " +
                                   std::to_string(files.size()));
        for (size_t i = 0; i < files.size(); ++i) {
            std::string where = pointerTo(p("files"), i);
            SceneHairFile f;
            if (files[i].is_string()) {
                f.path = files[i].get<std::string>();
            } else {
                r.expect(files[i], where, files[i].is_object(), "a file name or an object with \"file\"");
                r.object(files[i], where, sectionKnown(SceneSection::HairFile, {"file"}));
                if (!files[i].contains("file"))
                    r.fail(pointerTo(where, "file"), "is missing");
                f.path = r.string(files[i]["file"], pointerTo(where, "file"));
                f.settings = readSectionSettings(r, files[i], where, SceneSection::HairFile);
            }
            if (f.path.empty())
                r.fail(where, "must not be empty");
            hair.files.push_back(f);
        }
        for (const SceneSectionKey& k : sceneSectionKeys(SceneSection::Hair))
            for (const std::string& key : {k.name, k.alias})
                if (k.grownOnly && !key.empty() && has(key.c_str()))
                    r.fail(p(key.c_str()), "applies to grown hair, but this hair is loaded from /hair/files");
    } else {
        for (const char* placed : {"scale", "offset", "z_up", "mirror_z", "half_turn"})
            if (has(placed))
                r.fail(p(placed), "places loaded hair, but this hair is grown (no /hair/files)");
    }
}

std::vector<Ellipsoid> readColliders(const Reader& r, const Json& v)
{
    const std::string at = "/colliders";
    r.expect(v, at, v.is_array(), "an array of ellipsoids");
    std::vector<Ellipsoid> out;
    for (size_t i = 0; i < v.size(); ++i) {
        std::string where = pointerTo(at, i);
        const Json& c = v[i];
        r.object(c, where, {"name", "center", "radii", "rotation_deg"});
        for (const char* required : {"center", "radii"})
            if (!c.contains(required))
                r.fail(pointerTo(where, required), "is missing");
        Ellipsoid e;
        e.name = c.contains("name") ? r.string(c["name"], pointerTo(where, "name")) : "collider" + std::to_string(i);
        e.center = r.vec3(c["center"], pointerTo(where, "center"), kPositionRange, "head units");
        e.radii = r.vec3(c["radii"], pointerTo(where, "radii"), kRadiusRange, "head units");
        if (e.radii.x <= 0.0f || e.radii.y <= 0.0f || e.radii.z <= 0.0f)
            r.fail(pointerTo(where, "radii"), "must all be > 0");
        if (c.contains("rotation_deg"))
            e.rotationDeg =
                r.vec3(c["rotation_deg"], pointerTo(where, "rotation_deg"), Range{-360.0, 360.0}, "degrees");
        out.push_back(e);
    }
    if (out.empty())
        r.fail(at, "must hold at least one ellipsoid (leave it out for the head's own)");
    return out;
}

void readPhysics(const Reader& r, const Json& v, Scene& scene)
{
    const std::string at = "/physics";
    r.expect(v, at, v.is_object(), "an object");
    std::vector<std::string> known = sectionKnown(SceneSection::Physics, {"sphere"});
    for (const auto& item : v.items())
        if (std::find(known.begin(), known.end(), item.key()) == known.end() && findSetting(item.key()))
            r.fail(pointerTo(at, item.key()), "is a setting: put it under /settings");
    r.object(v, at, known);
    scene.physics = readSectionSettings(r, v, at, SceneSection::Physics);
    if (v.contains("sphere"))
        scene.sphere = r.sphere(v["sphere"], pointerTo(at, "sphere"));
}

SceneKey readKey(const Reader& r, const Json& v, const std::string& at)
{
    r.object(v, at, {"time", "camera", "sphere", "light", "wind", "head_yaw"});
    if (!v.contains("time"))
        r.fail(pointerTo(at, "time"), "is missing (every key has a time in seconds)");
    SceneKey k;
    k.time = r.number(v["time"], pointerTo(at, "time"), kSceneTimeRange, "s");
    if (v.contains("camera")) {
        std::string c = pointerTo(at, "camera");
        const Json& cam = v["camera"];
        r.object(cam, c, {"yaw", "pitch", "distance", "target", "eye", "up", "fov"});
        if (cam.contains("yaw"))
            k.cameraYawDeg = r.real(cam["yaw"], pointerTo(c, "yaw"), kSceneCameraYawRange, "degrees");
        if (cam.contains("pitch"))
            k.cameraPitchDeg = r.real(cam["pitch"], pointerTo(c, "pitch"), kSceneCameraPitchRange, "degrees");
        if (cam.contains("distance"))
            k.cameraDistance = r.real(cam["distance"], pointerTo(c, "distance"), kSceneCameraDistanceRange,
                                      "times the default framing's");
        if (cam.contains("target"))
            k.cameraTarget = r.vec3(cam["target"], pointerTo(c, "target"), kPositionRange, "head units");
        if (cam.contains("eye"))
            k.cameraEye = r.vec3(cam["eye"], pointerTo(c, "eye"), kPositionRange, "head units");
        if (cam.contains("up")) {
            k.cameraUp = r.vec3(cam["up"], pointerTo(c, "up"), kPositionRange, "a direction");
            if (glm::length(*k.cameraUp) == 0.0f)
                r.fail(pointerTo(c, "up"), "is [0, 0, 0]: the camera's up needs a direction");
        }
        if (cam.contains("fov"))
            k.cameraFovDeg = r.real(cam["fov"], pointerTo(c, "fov"), kSceneCameraFovRange, "degrees");
        if (k.cameraEye && k.cameraTarget && *k.cameraEye == *k.cameraTarget)
            r.fail(pointerTo(c, "eye"), "is the target: the camera needs a direction to look in");
        if (k.cameraEye && k.cameraTarget && k.cameraUp &&
            glm::length(glm::cross(*k.cameraUp, *k.cameraTarget - *k.cameraEye)) == 0.0f)
            r.fail(pointerTo(c, "up"), "is along the line of sight: it gives the camera no roll");
    }
    if (v.contains("sphere"))
        k.sphere = r.sphere(v["sphere"], pointerTo(at, "sphere"));
    if (v.contains("light")) {
        std::string l = pointerTo(at, "light");
        const Json& light = v["light"];
        r.object(light, l, {"azimuth", "elevation", "intensity"});
        // The light's channels are its settings, each a number here.
        auto channel = [&](const char* key, const char* setting, std::optional<float>& out) {
            if (!light.contains(key))
                return;
            r.expect(light[key], pointerTo(l, key), light[key].is_number(), "a number");
            out = r.settingReal(light[key], pointerTo(l, key), setting);
        };
        channel("azimuth", "light_azimuth", k.lightAzimuthDeg);
        channel("elevation", "light_elevation", k.lightElevationDeg);
        channel("intensity", "light_intensity", k.lightIntensity);
    }
    if (v.contains("wind")) {
        r.expect(v["wind"], pointerTo(at, "wind"), v["wind"].is_array(), "an array of 3 numbers");
        k.wind = r.settingVector(v["wind"], pointerTo(at, "wind"), "wind");
    }
    if (v.contains("head_yaw"))
        k.headYawDeg = r.real(v["head_yaw"], pointerTo(at, "head_yaw"), kSceneHeadYawRange, "degrees");
    return k;
}

// Where in `text` byte `offset` is, as line and column (1-based), lines ended as every text reader
// ends them (assets/text.h: LF, CRLF or a bare CR).
std::pair<size_t, size_t> lineAndColumn(std::string_view text, size_t offset)
{
    offset = std::min(offset, text.size());
    size_t lineStart = text.find_last_of("\r\n", offset == 0 ? std::string_view::npos : offset - 1);
    lineStart = lineStart == std::string_view::npos || offset == 0 ? 0 : lineStart + 1;
    return {lineOfByte(text, offset), offset - lineStart + 1};
}

// A float as the shortest decimal that reads back as the same float (0.3f is written 0.3, not
// 0.30000001192092896).
Json num(float v)
{
    return Json(shortest(v));
}

// Settings as the settings table writes them into JSON, under their names.
void writeSettings(Json& object, const SceneSettings& settings, const std::string& at)
{
    for (const auto& [name, value] : settings) {
        const SettingSpec& spec = settingSpec(name, at);
        object[name] = settingJson(spec, parseSetting(spec, value, pointerTo(at, name)));
    }
}

Json vecJson(const float* v, size_t n)
{
    Json a = Json::array();
    for (size_t i = 0; i < n; ++i)
        a.push_back(num(v[i]));
    return a;
}

} // namespace

const std::vector<SceneSectionKey>& sceneSectionKeys(SceneSection section)
{
    static const std::vector<SceneSectionKey> partKeys = [] {
        std::vector<SceneSectionKey> keys;
        for (const auto& [key, setting] : kPartKeys)
            keys.push_back({.name = settingSpec(setting).name, .alias = "", .grownOnly = false});
        return keys;
    }();
    // Every saved growth setting (what shapes the hair as it is grown; vertices_per_strand resamples
    // loaded hair too), then every part's values.
    static const std::vector<SceneSectionKey> hairKeys = [] {
        std::vector<SceneSectionKey> keys;
        for (const SettingSpec& spec : settingSpecs())
            if (spec.group == SettingGroup::Growth && spec.saved) {
                bool vertices = spec.name == "vertices_per_strand";
                keys.push_back({.name = spec.name, .alias = vertices ? "vertices" : "", .grownOnly = !vertices});
            }
        keys.insert(keys.end(), partKeys.begin(), partKeys.end());
        return keys;
    }();
    static const std::vector<SceneSectionKey> physicsKeys = {
        {.name = settingSpec("wind").name, .alias = "", .grownOnly = false},
        {.name = settingSpec("repulsion").name, .alias = "", .grownOnly = false},
        {.name = settingSpec("grid_atomics").name, .alias = "", .grownOnly = false}};
    switch (section) {
    case SceneSection::Hair:
        return hairKeys;
    case SceneSection::HairFile:
        return partKeys;
    case SceneSection::Physics:
        break;
    }
    return physicsKeys;
}

double Scene::length() const
{
    if (duration)
        return *duration;
    return keys.empty() ? 0.0 : keys.back().time;
}

namespace {

// A parser callback that refuses a key given twice in one object (JSON leaves it undefined and
// nlohmann keeps the last: a scene would silently lose a value), naming the key's JSON pointer.
Json::parser_callback_t duplicateKeyCheck(const std::filesystem::path& path)
{
    struct Container {
        bool object = false;
        std::vector<std::string> keys; // an object's, in order
        size_t elements = 0;           // an array's so far
    };
    auto open = std::make_shared<std::vector<Container>>();
    return [open, path](int, Json::parse_event_t event, Json& parsed) {
        std::vector<Container>& stack = *open;
        auto element = [&] { // a value starts: an array counts it
            if (!stack.empty() && !stack.back().object)
                ++stack.back().elements;
        };
        switch (event) {
        case Json::parse_event_t::object_start:
        case Json::parse_event_t::array_start:
            element();
            stack.push_back({.object = event == Json::parse_event_t::object_start, .keys = {}, .elements = 0});
            break;
        case Json::parse_event_t::object_end:
        case Json::parse_event_t::array_end:
            if (!stack.empty())
                stack.pop_back();
            break;
        case Json::parse_event_t::key: {
            std::string key = parsed.get<std::string>();
            std::vector<std::string>& keys = stack.back().keys;
            if (std::find(keys.begin(), keys.end(), key) != keys.end()) {
                std::string pointer;
                for (size_t i = 0; i + 1 < stack.size(); ++i)
                    pointer += "/" + (stack[i].object ? stack[i].keys.back() : std::to_string(stack[i].elements - 1));
                pointer += "/" + key;
                throw UserError(path.string() + ": " + pointer + ": the key '" + key +
                                "' is given twice in one object (give it once)");
            }
            keys.push_back(key);
            break;
        }
        case Json::parse_event_t::value:
            element();
            break;
        }
        return true;
    };
}

} // namespace

Scene loadScene(const std::filesystem::path& path)
{
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw UserError(path.string() + ": the scene file does not exist");
    std::ifstream in(path, std::ios::binary);
    if (!in || std::filesystem::is_directory(path, ec))
        throw UserError(path.string() + ": cannot read the scene file");
    std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return parseScene(content, path);
}

Scene parseScene(const std::string& content, const std::filesystem::path& path)
{
    // Trailing NULs and white space are padding; a NUL inside the text is an error naming its byte
    // (assets/text.h, the rule of every text reader). JSON takes any line ending as white space.
    std::string_view body = textOf(content);
    checkNoNulBytes(body, bomBytes(content), path, "a scene file");
    Json doc;
    try {
        doc = Json::parse(body, duplicateKeyCheck(path));
    } catch (const Json::parse_error& e) {
        auto [line, column] = lineAndColumn(body, e.byte > 0 ? e.byte - 1 : 0);
        std::string why = e.what();
        if (size_t c = why.find("column"); c != std::string::npos && why.find(": ", c) != std::string::npos)
            why = why.substr(why.find(": ", c) + 2);
        throw UserError(path.string() + ":" + std::to_string(line) + ":" + std::to_string(column) +
                        ": malformed JSON: " + why);
    } catch (const Json::out_of_range& e) {
        // A number too large for a double (1e400): nlohmann names the literal but not where it is.
        std::string why = e.what();
        std::string where = path.string();
        size_t quote = why.find('\'');
        if (quote != std::string::npos && why.find('\'', quote + 1) != std::string::npos) {
            std::string literal = why.substr(quote + 1, why.find('\'', quote + 1) - quote - 1);
            if (size_t at = body.find(literal); at != std::string_view::npos) {
                auto [line, column] = lineAndColumn(body, at);
                where += ":" + std::to_string(line) + ":" + std::to_string(column);
            }
            why = literal + " is too large a number";
        }
        throw UserError(where + ": " + why);
    }
    Reader r{path};
    r.object(doc, "",
             {"version", "description", "head", "hair", "colliders", "physics", "settings", "interpolation", "duration",
              "loop", "keys"});
    Scene scene;
    if (doc.contains("version")) {
        double version = r.number(doc["version"], "/version", Range{0.0, 1e9});
        if (version != kSceneVersion)
            r.fail("/version", numberText(version) + " is not a version this Wisp reads (it reads " +
                                   std::to_string(kSceneVersion) + ")");
    }
    if (doc.contains("description"))
        scene.description = r.string(doc["description"], "/description");
    if (doc.contains("head")) {
        scene.head = r.string(doc["head"], "/head");
        if (scene.head.empty())
            r.fail("/head", "must not be empty (leave it out for the default head)");
    }
    if (doc.contains("hair"))
        readHair(r, doc["hair"], scene.hair);
    if (doc.contains("colliders"))
        scene.colliders = readColliders(r, doc["colliders"]);
    if (doc.contains("physics"))
        readPhysics(r, doc["physics"], scene);
    if (doc.contains("settings")) {
        const Json& settings = doc["settings"];
        r.expect(settings, "/settings", settings.is_object(), "an object of settings from 'wisp settings'");
        // Checked here, so a bad value fails before anything runs.
        for (const auto& item : settings.items()) {
            std::string pointer = pointerTo("/settings", item.key());
            const SettingSpec* spec = findSetting(item.key());
            if (!spec)
                r.fail(pointer, "unknown setting (known: " + settingNames() + ")");
            scene.settings.emplace_back(spec->name,
                                        settingText(*spec, r.setting(item.value(), pointer, spec->name.c_str())));
        }
    }
    if (doc.contains("interpolation")) {
        std::string i = r.string(doc["interpolation"], "/interpolation");
        if (i == "linear")
            scene.interpolation = SceneInterpolation::Linear;
        else if (i == "smooth")
            scene.interpolation = SceneInterpolation::Smooth;
        else
            r.fail("/interpolation", "'" + i + "' is not allowed: linear | smooth");
    }
    if (doc.contains("duration"))
        scene.duration = r.number(doc["duration"], "/duration", kSceneTimeRange, "s");
    if (doc.contains("keys")) {
        const Json& keys = doc["keys"];
        r.expect(keys, "/keys", keys.is_array(), "an array of keys");
        for (size_t i = 0; i < keys.size(); ++i) {
            SceneKey k = readKey(r, keys[i], pointerTo("/keys", i));
            if (!scene.keys.empty() && !(k.time > scene.keys.back().time))
                r.fail(pointerTo(pointerTo("/keys", i), "time"),
                       numberText(k.time) + " is not after the previous key's " + numberText(scene.keys.back().time) +
                           " (times must increase)");
            scene.keys.push_back(k);
        }
    }
    if (doc.contains("loop")) {
        scene.loop = r.boolean(doc["loop"], "/loop");
        if (scene.loop && !(scene.length() > 0.0))
            r.fail("/loop", "a scene that loops needs a duration or keys after time 0");
    }
    return scene;
}

std::string sceneJson(const Scene& scene)
{
    Json doc;
    doc["version"] = kSceneVersion;
    if (!scene.description.empty())
        doc["description"] = scene.description;
    if (!scene.head.empty())
        doc["head"] = scene.head;
    const SceneHair& h = scene.hair;
    Json hair = Json::object();
    writeSettings(hair, h.settings, "/hair");
    if (!h.files.empty()) {
        Json files = Json::array();
        for (const SceneHairFile& f : h.files) {
            if (f.settings.empty()) {
                files.push_back(f.path);
                continue;
            }
            Json o = {{"file", f.path}};
            writeSettings(o, f.settings, "/hair/files");
            files.push_back(o);
        }
        hair["files"] = files;
    }
    if (h.scale)
        hair["scale"] = num(*h.scale);
    if (h.offset)
        hair["offset"] = vecJson(&h.offset->x, 3);
    if (h.zUp)
        hair["z_up"] = *h.zUp;
    if (h.mirrorZ)
        hair["mirror_z"] = *h.mirrorZ;
    if (h.halfTurn)
        hair["half_turn"] = *h.halfTurn;
    if (!hair.empty())
        doc["hair"] = hair;
    if (scene.colliders) {
        Json list = Json::array();
        for (const Ellipsoid& e : *scene.colliders)
            list.push_back({{"name", e.name},
                            {"center", vecJson(&e.center.x, 3)},
                            {"radii", vecJson(&e.radii.x, 3)},
                            {"rotation_deg", vecJson(&e.rotationDeg.x, 3)}});
        doc["colliders"] = list;
    }
    Json physics = Json::object();
    writeSettings(physics, scene.physics, "/physics");
    if (scene.sphere)
        physics["sphere"] = vecJson(&scene.sphere->x, 4);
    if (!physics.empty())
        doc["physics"] = physics;
    if (!scene.settings.empty()) {
        Json settings = Json::object();
        writeSettings(settings, scene.settings, "/settings");
        doc["settings"] = settings;
    }
    doc["interpolation"] = scene.interpolation == SceneInterpolation::Linear ? "linear" : "smooth";
    if (scene.duration)
        doc["duration"] = *scene.duration;
    if (scene.loop)
        doc["loop"] = true;
    Json keys = Json::array();
    for (const SceneKey& k : scene.keys) {
        Json key = {{"time", k.time}};
        Json camera = Json::object();
        if (k.cameraYawDeg)
            camera["yaw"] = num(*k.cameraYawDeg);
        if (k.cameraPitchDeg)
            camera["pitch"] = num(*k.cameraPitchDeg);
        if (k.cameraDistance)
            camera["distance"] = num(*k.cameraDistance);
        if (k.cameraTarget)
            camera["target"] = vecJson(&k.cameraTarget->x, 3);
        if (k.cameraEye)
            camera["eye"] = vecJson(&k.cameraEye->x, 3);
        if (k.cameraUp)
            camera["up"] = vecJson(&k.cameraUp->x, 3);
        if (k.cameraFovDeg)
            camera["fov"] = num(*k.cameraFovDeg);
        if (!camera.empty())
            key["camera"] = camera;
        if (k.sphere)
            key["sphere"] = vecJson(&k.sphere->x, 4);
        Json light = Json::object();
        if (k.lightAzimuthDeg)
            light["azimuth"] = num(*k.lightAzimuthDeg);
        if (k.lightElevationDeg)
            light["elevation"] = num(*k.lightElevationDeg);
        if (k.lightIntensity)
            light["intensity"] = num(*k.lightIntensity);
        if (!light.empty())
            key["light"] = light;
        if (k.wind)
            key["wind"] = vecJson(&k.wind->x, 3);
        if (k.headYawDeg)
            key["head_yaw"] = num(*k.headYawDeg);
        keys.push_back(key);
    }
    doc["keys"] = keys;
    return doc.dump(2) + "\n";
}

void saveScene(const std::filesystem::path& path, const Scene& scene)
{
    std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
    std::error_code ec;
    if (!std::filesystem::is_directory(folder, ec))
        throw UserError(path.string() + ": folder '" + folder.string() + "' does not exist");
    writeFileAtomically(path, sceneJson(scene));
}

std::filesystem::path sharedDataFolder()
{
    if (const char* env = std::getenv("WISP_SHARED_DATA"); env && *env)
        return std::filesystem::path(env).lexically_normal();
    return (std::filesystem::path(WISP_SOURCE_DIR) / ".." / "shared" / "data").lexically_normal();
}

std::filesystem::path resolveScenePath(const std::filesystem::path& sceneFile, const std::string& text,
                                       const std::string& pointer)
{
    if (text.rfind(kSharedPrefix, 0) == 0) {
        std::string relative = text.substr(std::string(kSharedPrefix).size());
        std::filesystem::path folder = sharedDataFolder();
        std::filesystem::path file = (folder / relative).lexically_normal();
        std::error_code ec;
        if (!std::filesystem::exists(file, ec))
            throw UserError(sceneFile.string() + ": " + pointer + ": '" + text + "': the shared data is missing: " +
                            file.string() + " does not exist (this scene needs the shared third-party assets in " +
                            folder.string() + ", beside the checkout, or in the folder $WISP_SHARED_DATA names)");
        return file;
    }
    std::filesystem::path p(text);
    std::filesystem::path file = p.is_absolute() ? p : (sceneFile.parent_path() / p).lexically_normal();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        throw UserError(
            sceneFile.string() + ": " + pointer + ": '" + text + "': no such file" +
            (file.string() != text ? " (" + file.string() + ", relative to the scene's folder)" : std::string()));
    return file;
}

std::string scenePathText(const std::filesystem::path& sceneFile, const std::filesystem::path& file)
{
    std::filesystem::path absolute = std::filesystem::absolute(file).lexically_normal();
    std::filesystem::path shared = std::filesystem::absolute(sharedDataFolder()).lexically_normal();
    std::filesystem::path inShared = absolute.lexically_relative(shared);
    if (!inShared.empty() && *inShared.begin() != "..")
        return kSharedPrefix + inShared.generic_string();
    std::filesystem::path folder = std::filesystem::absolute(sceneFile).lexically_normal().parent_path();
    std::filesystem::path relative = absolute.lexically_relative(folder);
    return relative.empty() ? absolute.generic_string() : relative.generic_string();
}

void applyScene(const Scene& scene, const std::filesystem::path& sceneFile, Settings& settings, HairSource& source)
{
    auto apply = [&](const SceneSettings& values, const std::string& at) {
        for (const auto& [name, value] : values) {
            std::string where = sceneFile.string() + ": " + pointerTo(at, name);
            const SettingSpec& spec = settingSpec(name, where);
            setSetting(settings, spec, parseSetting(spec, value, where), where);
        }
    };
    if (!scene.head.empty())
        source.headFile = resolveScenePath(sceneFile, scene.head, "/head");
    const SceneHair& h = scene.hair;
    apply(h.settings, "/hair");
    source.hairFiles.clear();
    source.scenePartOverrides.clear();
    for (size_t i = 0; i < h.files.size(); ++i) {
        const SceneHairFile& f = h.files[i];
        std::string pointer = "/hair/files/" + std::to_string(i);
        source.hairFiles.push_back(resolveScenePath(sceneFile, f.path, pointer).string());
        // As --part PART:key=value,... (kPartKeys), in the override keys' order.
        std::string values;
        for (const auto& [key, setting] : kPartKeys)
            for (const auto& [name, value] : f.settings)
                if (name == setting)
                    values += (values.empty() ? "" : ",") + std::string(key) + "=" + value;
        if (!values.empty())
            source.scenePartOverrides.push_back(std::to_string(i) + ":" + values);
    }
    if (h.scale)
        source.hairScale = *h.scale;
    if (h.offset)
        source.hairOffset = *h.offset;
    if (h.zUp)
        source.zUp = h.zUp;
    if (h.mirrorZ)
        source.mirrorZ = h.mirrorZ;
    if (h.halfTurn)
        source.halfTurn = h.halfTurn;
    if (scene.colliders)
        source.colliders = scene.colliders;
    apply(scene.physics, "/physics");
    if (scene.sphere && scene.sphere->w > 0.0f)
        source.sphere = *scene.sphere;
    apply(scene.settings, "/settings");
}

} // namespace wisp
