// app/scene/scene_file.h: the scene file format: one JSON file naming the head, the hair (grown or
// loaded in parts), the colliders, any settings from `wisp settings`, the physics options, and
// keyframes over time for the camera, the sphere, the light, the wind and the head's turn (their
// meaning over time is app/scene/scene_timeline.h). The keys that are settings (/hair/guides,
// /physics/wind, ...) are the settings table's names. loadScene() (parseScene() for text in
// memory) checks every value (errors name the file and a JSON pointer), saveScene() writes one
// atomically, applyScene() gives a scene to the settings. `render`, `record` and `view` take
// `--scene`.
#pragma once

#include "app/scene/scene_timeline.h"
#include "app/settings/hair_source.h"
#include "app/settings/settings_table.h"
#include "assets/head.h"

#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace wisp {

// Settings as NAME=VALUE (the text --set takes), by the settings' own names, in the file's order
// (a later one wins).
using SceneSettings = std::vector<std::pair<std::string, std::string>>;

// A hair file of a loaded groom, with its part's own values of the part settings (kPartKeys of
// app/settings/hair_source.h: global_stiffness, local_stiffness, damping, drag; absent: the groom's or the
// default).
struct SceneHairFile {
    std::string path; // as written: relative to the scene file, absolute, or "shared:REL"
    SceneSettings settings;
    bool operator==(const SceneHairFile&) const = default;
};

// The hair: grown (files empty) or loaded. Absent values keep the defaults (or the command
// line's). Its settings are the growth settings (guides, vertices_per_strand, hair_length, ...:
// group growth of `wisp settings`) and the part settings for every part, each under its setting's
// name (sceneSectionKeys).
struct SceneHair {
    SceneSettings settings;
    std::vector<SceneHairFile> files;
    std::optional<float> scale; // placement of loaded hair (as --hair-scale, ...)
    std::optional<glm::vec3> offset;
    std::optional<bool> zUp, mirrorZ, halfTurn;
    bool operator==(const SceneHair&) const = default;
};

struct Scene {
    std::string description;
    std::string head; // as written; empty: the default head
    SceneHair hair;
    std::optional<std::vector<Ellipsoid>> colliders; // head space; absent: the head's (or fitted)
    // "physics": the sphere, and three settings older scenes wrote here (wind, repulsion,
    // grid_atomics, as "settings" would hold them). The wind and the sphere are the values while no
    // key sets those channels (as --wind and --sphere).
    SceneSettings physics;
    std::optional<glm::vec4> sphere; // head units
    SceneSettings settings;          // "settings": any setting
    SceneInterpolation interpolation = SceneInterpolation::Smooth;
    std::optional<double> duration; // seconds; absent: the last key's time
    bool loop = false;              // the keys repeat every length() seconds (a soak runs for hours)
    std::vector<SceneKey> keys;     // by increasing time
    bool operator==(const Scene&) const = default;

    // The length of the animation: `duration`, else the last key's time (0 without keys).
    double length() const;
};

// The settings a section of a scene file holds under their own names: /hair (every growth setting
// and part setting), /hair/files/N (the part settings), /physics (wind, repulsion, grid_atomics).
// `alias`: the name older scenes used, still read ("vertices" for vertices_per_strand).
struct SceneSectionKey {
    std::string name;
    std::string alias;
    bool grownOnly = false; // shapes grown hair only: refused beside /hair/files
};
enum class SceneSection { Hair, HairFile, Physics };
const std::vector<SceneSectionKey>& sceneSectionKeys(SceneSection section);

// Reads and checks a scene. Throws UserError naming the file and what is wrong: the JSON pointer
// of the value (/keys/2/sphere/3), the allowed range or type, unknown keys with the known ones,
// the line and column of malformed JSON. Files named by the scene are not opened here.
Scene loadScene(const std::filesystem::path& path);
// The same from a scene file's text already in memory; errors name `path` as if it were read.
Scene parseScene(const std::string& content, const std::filesystem::path& path);
// Writes `scene` as JSON (to a temporary file in the same folder, then renamed: never half
// written). Paths are written as the struct holds them (see scenePathText).
void saveScene(const std::filesystem::path& path, const Scene& scene);
// The same JSON text saveScene writes.
std::string sceneJson(const Scene& scene);

// Files a scene names: "shared:REL" is REL inside the shared data folder ($WISP_SHARED_DATA when
// set, else ../shared/data beside the checkout Wisp was built from); any other relative path is
// relative to the scene file's folder. A missing file is a UserError naming the scene and
// `pointer` (/head, /hair/files/0); a missing shared file says the shared data is missing.
std::filesystem::path sharedDataFolder();
std::filesystem::path resolveScenePath(const std::filesystem::path& sceneFile, const std::string& text,
                                       const std::string& pointer);
// How to write `file` into a scene saved at `sceneFile`: "shared:REL" inside the shared data
// folder, else relative to the scene's folder (absolute when on another root).
std::string scenePathText(const std::filesystem::path& sceneFile, const std::filesystem::path& file);

// Writes the scene's values into the settings and the hair's source (before the command line's own
// options are applied over them); files it names are resolved against `sceneFile`.
void applyScene(const Scene& scene, const std::filesystem::path& sceneFile, Settings& settings, HairSource& source);

} // namespace wisp
