// tests/test_scene_file.cpp: scene files (app/scene/scene_file.h) without a GPU: save and load (or
// parse) give the same scene, a window's state saved as one key, the shipped scenes, paths, and
// every validation error naming the file and the value's JSON pointer.
#include "app/scene/scene_file.h"
#include "assets/text.h"
#include "core/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

using namespace wisp;
using wisp::test::TempDir;
using wisp::test::writeFile;

namespace {

// A scene with every field of grown hair set.
Scene grownScene()
{
    Scene s;
    s.description = "every field";
    s.head = "heads/bust.json";
    s.hair.settings = {{"guides", "120"},
                       {"vertices_per_strand", "12"},
                       {"seed", "7"},
                       {"hair_length", "0.3"},
                       {"length_variation", "0.2"},
                       {"curl", "0.01"},
                       {"poisson", "on"},
                       {"global_stiffness", "0.15"},
                       {"local_stiffness", "0.35"},
                       {"damping", "0.8"},
                       {"drag", "2.5"}};
    s.colliders = std::vector<Ellipsoid>{{"cranium", {0.0f, 0.14f, 0.0f}, {0.09f, 0.11f, 0.12f}, {56.2f, 0.0f, 0.0f}},
                                         {"neck", {0.0f, 0.0f, -0.02f}, {0.06f, 0.12f, 0.06f}, {0.0f, 0.0f, 0.0f}}};
    s.physics = {{"wind", "1,0,-2.5"}, {"repulsion", "0.25"}, {"grid_atomics", "float"}};
    s.sphere = glm::vec4(0.1f, 0.2f, -0.3f, 0.05f);
    s.settings = {{"hair_preset", "auburn"},
                  {"strands_per_guide", "8"},
                  {"width", "0.0004"},
                  {"lod", "off"},
                  {"hair_color", "0.3,0.2,0.1"}};
    s.interpolation = SceneInterpolation::Linear;
    s.duration = 4.5;
    SceneKey a;
    a.time = 0.0;
    a.cameraYawDeg = 30.0f;
    a.cameraPitchDeg = -5.0f;
    a.cameraDistance = 1.25f;
    a.cameraTarget = glm::vec3(0.0f, 0.1f, 0.0f);
    a.sphere = glm::vec4(0.3f, 0.1f, -0.1f, 0.06f);
    a.lightAzimuthDeg = -40.0f;
    a.lightElevationDeg = 20.0f;
    a.lightIntensity = 2.5f;
    a.wind = glm::vec3(0.0f, 0.0f, 0.0f);
    a.headYawDeg = 0.0f;
    SceneKey b;
    b.time = 1.5;
    b.headYawDeg = -45.5f;
    SceneKey c;
    c.time = 3.25;
    c.wind = glm::vec3(3.0f, 0.5f, -7.0f);
    c.cameraYawDeg = 390.0f;
    s.keys = {a, b, c};
    return s;
}

Scene loadedScene()
{
    Scene s;
    s.hair.files = {{"shared:sintel/groom.tfx", {}},
                    {"parts/tail.tfx", {{"global_stiffness", "0.5"}, {"damping", "0.9"}, {"drag", "3"}}}};
    s.hair.settings = {{"vertices_per_strand", "16"}};
    s.hair.scale = 0.01f;
    s.hair.offset = glm::vec3(0.0f, -0.02f, 0.01f);
    s.hair.zUp = true;
    s.hair.mirrorZ = false;
    return s;
}

// What loadScene says about `text` (empty when it loads).
std::string loadError(const std::string& text, const std::string& name = "bad.json")
{
    TempDir dir;
    writeFile(dir / name, text);
    try {
        loadScene(dir / name);
    } catch (const UserError& e) {
        std::string message = e.what();
        EXPECT_EQ(message.rfind((dir / name).string() + ":", 0), 0u) << "names the file first: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
        return message;
    }
    return "";
}

} // namespace

TEST(Scene, SaveThenLoadGivesTheSameScene)
{
    TempDir dir;
    for (const Scene& original : {grownScene(), loadedScene(), Scene{}}) {
        saveScene(dir / "s.json", original);
        Scene loaded = loadScene(dir / "s.json");
        EXPECT_TRUE(loaded == original) << sceneJson(original) << "\nloaded as\n" << sceneJson(loaded);
        EXPECT_EQ(sceneJson(loaded), sceneJson(original));
    }
    // Written under a temporary name and renamed: nothing else is left in the folder.
    size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
        files += entry.is_regular_file() ? 1 : 0;
    EXPECT_EQ(files, 1u);
    // Floats are written as the shortest decimal that reads back the same.
    std::string text = sceneJson(grownScene());
    EXPECT_NE(text.find("\"hair_length\": 0.3,"), std::string::npos) << text;
    EXPECT_NE(text.find("\"strands_per_guide\": 8"), std::string::npos) << text; // a number again
    EXPECT_NE(text.find("\"lod\": false"), std::string::npos) << text;
}

TEST(Scene, SaveNeedsAnExistingFolder)
{
    EXPECT_THROW(saveScene("/nonexistent/folder/s.json", Scene{}), UserError);
}

TEST(Scene, ACompleteFileLoadsWithItsValues)
{
    std::string text = R"({
  "version": 1,
  "hair": {"guides": 40, "hair_length": 0.3},
  "physics": {"wind": [1, 0, 0], "sphere": [0, 0.1, -0.2, 0.05], "grid_atomics": "fixed"},
  "settings": {"melanin": 0.3, "hair_preset": "black", "lod": false, "hair_color": [0.5, 0.4, 0.3]},
  "keys": [
    {"time": 0, "camera": {"yaw": 10, "target": [0, 0.1, 0]}, "light": {"azimuth": 20}},
    {"time": 2.5, "head_yaw": -30, "wind": [0, 0, -4], "sphere": [0.2, 0.1, -0.2, 0]}
  ]
})";
    TempDir dir;
    writeFile(dir / "s.json", text);
    Scene s = loadScene(dir / "s.json");
    EXPECT_EQ(s.hair.settings, (SceneSettings{{"guides", "40"}, {"hair_length", "0.3"}}));
    EXPECT_EQ(s.physics, (SceneSettings{{"wind", "1,0,0"}, {"grid_atomics", "fixed"}}));
    // In the file's order (a later setting wins over an earlier one), as --set takes them.
    ASSERT_EQ(s.settings.size(), 4u);
    EXPECT_EQ(s.settings[0], std::make_pair(std::string("melanin"), std::string("0.3")));
    EXPECT_EQ(s.settings[1].first, "hair_preset");
    EXPECT_EQ(s.settings[2].second, "off");
    EXPECT_EQ(s.settings[3].second, "0.5,0.4,0.3");
    ASSERT_EQ(s.keys.size(), 2u);
    EXPECT_EQ(*s.keys[0].cameraTarget, glm::vec3(0.0f, 0.1f, 0.0f));
    EXPECT_FALSE(s.keys[0].cameraPitchDeg.has_value());
    EXPECT_EQ(*s.keys[1].headYawDeg, -30.0f);
    EXPECT_EQ(s.keys[1].sphere->w, 0.0f);
    EXPECT_DOUBLE_EQ(s.length(), 2.5);                      // no duration: the last key's time
    EXPECT_EQ(s.interpolation, SceneInterpolation::Smooth); // the default
}

TEST(Scene, ParsedTextIsTheSameAsTheLoadedFile)
{
    // parseScene reads what loadScene reads from the file (the scene fuzz target uses it), and its
    // errors name the path it is given.
    std::string text = sceneJson(grownScene());
    TempDir dir;
    writeFile(dir / "s.json", text);
    EXPECT_TRUE(parseScene(text, "memory.json") == loadScene(dir / "s.json"));
    try {
        parseScene(R"({"keys": [{"time": 0, "head_yaw": 120}]})", "scenes/turn.json");
        ADD_FAILURE() << "an out-of-range head turn was accepted";
    } catch (const UserError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("scenes/turn.json: /keys/0/head_yaw: 120 is out of range", 0), 0u)
            << e.what();
    }
    try {
        parseScene("{\n  \"keys\": [,]\n}", "scenes/broken.json");
        ADD_FAILURE() << "malformed JSON was accepted";
    } catch (const UserError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("scenes/broken.json:2:12: malformed JSON", 0), 0u) << e.what();
    }
}

TEST(Scene, TrailingPaddingIsReadAndANulInsideIsNamed)
{
    // The rule of every text file Wisp reads (assets/text.h): NULs and white space after the last
    // character are padding (a trailing NUL was "malformed JSON"), any line ending reads, and a NUL
    // inside the text is an error naming its line and byte.
    std::string lf = "{\n  \"hair\": {\"guides\": 40},\n  \"keys\": [{\"time\": 0, \"head_yaw\": 10}]\n}\n";
    std::string cr = lf;
    std::replace(cr.begin(), cr.end(), '\n', '\r');
    for (const std::string& text :
         {lf + std::string(3, '\0'), lf + std::string(1, '\0') + " \r\n\t" + std::string(8, '\0'),
          cr + std::string(1, '\0'), "\xEF\xBB\xBF" + lf + std::string(2, '\0')}) {
        EXPECT_EQ(loadError(text, "padded.json"), "") << quoteText(text);
        TempDir dir;
        writeFile(dir / "padded.json", text);
        Scene s = loadScene(dir / "padded.json");
        EXPECT_EQ(s.hair.settings, (SceneSettings{{"guides", "40"}}));
        ASSERT_EQ(s.keys.size(), 1u);
        EXPECT_EQ(*s.keys[0].headYawDeg, 10.0f);
    }
    std::string inside = lf;
    inside.insert(inside.find("40") + 1, 1, '\0'); // byte 24, on line 2
    std::string e = loadError(inside, "nul.json");
    EXPECT_NE(e.find("nul.json:2: byte 24 is a NUL byte inside the text (in '4\\x000},')"), std::string::npos) << e;
    EXPECT_NE(e.find("a scene file holds none but as padding"), std::string::npos) << e;
    EXPECT_EQ(e.find('\0'), std::string::npos);
    // The JSON reader stops at a NUL: what followed one was ignored without a word.
    e = loadError(lf + std::string(1, '\0') + "{\"keys\": 5}\n", "after.json");
    EXPECT_NE(e.find("after.json:5: byte " + std::to_string(lf.size()) + " is a NUL byte inside the text"),
              std::string::npos)
        << e;
    // With bare CR line endings a JSON error names the line it is on.
    std::string broken = cr;
    broken.replace(broken.find("10"), 2, "1x");
    e = loadError(broken, "cr.json");
    EXPECT_NE(e.find("cr.json:3:"), std::string::npos) << e;
}

TEST(Scene, AWindowsStateSavesAsOneKey)
{
    // What the window will do: its orbit camera relative to the framing, and every channel, as
    // one key that a timeline gives back.
    Bounds head{glm::vec3(-0.2f, -0.1f, -0.1f), glm::vec3(0.2f, 0.3f, 0.1f)};
    OrbitCamera framing = OrbitCamera::framing(head, 1.5f);
    OrbitCamera camera = framing;
    camera.orbit(40.0f, -15.0f);
    camera.zoom(0.8f);
    camera.pan(0.01f, 0.02f);
    SceneState state;
    state.camera = cameraPoseOf(framing, camera);
    state.sphere = glm::vec4(0.1f, 0.2f, 0.3f, 0.05f);
    state.light.azimuthDeg = -20.0f;
    state.wind = glm::vec3(2.0f, 0.0f, 1.0f);
    state.headYawDeg = 12.0f;
    Scene scene;
    scene.keys = {sceneKey(0.0, state)};
    TempDir dir;
    saveScene(dir / "saved.json", scene);
    Scene loaded = loadScene(dir / "saved.json");
    SceneState back = SceneTimeline(loaded.keys, loaded.interpolation, SceneState{}).at(3.0);
    OrbitCamera again = poseCamera(framing, back.camera);
    EXPECT_FLOAT_EQ(again.yawDeg, camera.yawDeg);
    EXPECT_FLOAT_EQ(again.pitchDeg, camera.pitchDeg);
    EXPECT_NEAR(again.distance, camera.distance, 1e-6f);
    EXPECT_EQ(again.target, camera.target);
    EXPECT_EQ(back.sphere, state.sphere);
    EXPECT_EQ(back.light.azimuthDeg, -20.0f);
    EXPECT_EQ(back.wind, state.wind);
    EXPECT_EQ(back.headYawDeg, 12.0f);
}

TEST(Scene, ALoopReadsSavesAndNeedsALength)
{
    // "loop" reads, saves and reads back; it needs a length to repeat.
    TempDir dir;
    writeFile(dir / "loop.json",
              R"({"duration": 4, "loop": true, "keys": [{"time": 0, "head_yaw": 0}, {"time": 2, "head_yaw": 40}]})");
    Scene s = loadScene(dir / "loop.json");
    EXPECT_TRUE(s.loop);
    saveScene(dir / "again.json", s);
    EXPECT_TRUE(loadScene(dir / "again.json") == s);
    EXPECT_NE(loadError(R"({"loop": true})").find("/loop: a scene that loops needs a duration or keys after time 0"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"loop": 1})").find("/loop: must be true or false"), std::string::npos)
        << loadError(R"({"loop": 1})");
}

TEST(Scene, ShippedScenesLoad)
{
    std::filesystem::path folder = std::filesystem::path(WISP_SOURCE_DIR) / "scenes";
    for (const char* name : {"sphere-sweep.json", "wind-gusts.json", "head-turn.json", "sintel.json", "soak.json"}) {
        Scene s = loadScene(folder / name);
        EXPECT_FALSE(s.description.empty()) << name;
        EXPECT_GE(s.keys.size(), 2u) << name;
        EXPECT_GT(s.length(), 2.0) << name;
        // Saved again, each reads back the same.
        TempDir dir;
        saveScene(dir / name, s);
        EXPECT_TRUE(loadScene(dir / name) == s) << name;
    }
    Scene sweep = loadScene(folder / "sphere-sweep.json");
    SceneTimeline t(sweep.keys, sweep.interpolation, SceneState{});
    EXPECT_GT(glm::distance(glm::vec3(t.at(0.0).sphere), glm::vec3(t.at(2.2).sphere)), 0.3f); // it sweeps
    Scene sintel = loadScene(folder / "sintel.json");
    ASSERT_EQ(sintel.hair.files.size(), 1u);
    EXPECT_EQ(sintel.hair.files[0].path.rfind("shared:", 0), 0u);
}

TEST(Scene, SharedPathsAndRelativePaths)
{
    TempDir shared, scenes;
    std::filesystem::create_directories(shared / "sintel");
    writeFile(shared / "sintel" / "head.obj", "v 0 0 0\n");
    writeFile(scenes / "local.tfx", "x");
    const char* previous = std::getenv("WISP_SHARED_DATA");
    std::string saved = previous ? previous : "";
    setenv("WISP_SHARED_DATA", shared.path().c_str(), 1);
    std::filesystem::path scene = scenes / "s.json";
    EXPECT_EQ(resolveScenePath(scene, "shared:sintel/head.obj", "/head"), shared / "sintel" / "head.obj");
    EXPECT_EQ(resolveScenePath(scene, "local.tfx", "/hair/files/0"), scenes / "local.tfx");
    EXPECT_EQ(scenePathText(scene, shared / "sintel" / "head.obj"), "shared:sintel/head.obj");
    EXPECT_EQ(scenePathText(scene, scenes / "local.tfx"), "local.tfx");
    try {
        resolveScenePath(scene, "shared:sintel/missing.tfx", "/hair/files/0");
        ADD_FAILURE() << "a missing shared file was accepted";
    } catch (const UserError& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("/hair/files/0"), std::string::npos) << m;
        EXPECT_NE(m.find("the shared data is missing"), std::string::npos) << m;
    }
    try {
        resolveScenePath(scene, "nowhere.obj", "/head");
        ADD_FAILURE() << "a missing file was accepted";
    } catch (const UserError& e) {
        EXPECT_NE(std::string(e.what()).find("/head: 'nowhere.obj': no such file"), std::string::npos) << e.what();
    }
    if (previous)
        setenv("WISP_SHARED_DATA", saved.c_str(), 1);
    else
        unsetenv("WISP_SHARED_DATA");
}

TEST(SceneErrors, WrongTypesNameTheJsonPointer)
{
    EXPECT_NE(loadError(R"({"keys": [{"time": "1"}]})").find("/keys/0/time: must be a number, got a string"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"keys": {"time": 1}})").find("/keys: must be an array of keys, got an object"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"keys": [{"time": 0, "sphere": [0, 0, 1]}]})")
                  .find("/keys/0/sphere: must be an array of 4 numbers"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"keys": [{"time": 0, "wind": [0, "x", 1]}]})").find("/keys/0/wind/1: must be a number"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"hair": {"poisson": 1}})").find("/hair/poisson: must be true or false, got a number"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"hair": {"guides": 2.5}})").find("/hair/guides: 2.5 is not a whole number"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"settings": {"shading": {"model": "karis"}}})")
                  .find("/settings/shading: must be a string (karis | kajiya | lut), got an object"),
              std::string::npos);
    EXPECT_NE(loadError("[1, 2]").find("must be an object, got an array"), std::string::npos);
}

TEST(SceneErrors, UnknownKeysListTheKnownOnes)
{
    std::string top = loadError(R"({"kes": []})");
    EXPECT_NE(top.find("/kes: unknown key (known: version, description, head, hair, colliders, physics, settings, "
                       "interpolation, duration, loop, keys)"),
              std::string::npos)
        << top;
    std::string key = loadError(R"({"keys": [{"time": 0, "spheer": [0, 0, 0, 1]}]})");
    EXPECT_NE(key.find("/keys/0/spheer: unknown key (known: time, camera, sphere, light, wind, head_yaw)"),
              std::string::npos)
        << key;
    EXPECT_NE(loadError(R"({"keys": [{"time": 0, "camera": {"zoom": 2}}]})")
                  .find("/keys/0/camera/zoom: unknown key (known: yaw"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"hair": {"lenght": 0.2}})")
                  .find("/hair/lenght: unknown key (known: files, scale, offset, z_up, mirror_z, half_turn, "
                        "hair_style, guides, vertices_per_strand, vertices, seed,"),
              std::string::npos);
    std::string setting = loadError(R"({"settings": {"sparkle": 3}})");
    EXPECT_NE(setting.find("/settings/sparkle: unknown setting (known: hair_style, guides,"), std::string::npos)
        << setting;
    EXPECT_NE(
        loadError(R"({"physics": {"step_hz": 240}})").find("/physics/step_hz: is a setting: put it under /settings"),
        std::string::npos);
}

TEST(SceneErrors, AKeyGivenTwiceIsNamedWithItsFile)
{
    std::string top = loadError(R"({"duration": 2, "loop": true, "duration": 3})");
    EXPECT_NE(top.find("/duration: the key 'duration' is given twice in one object"), std::string::npos) << top;
    std::string deep = loadError(R"({"keys": [{"time": 0}, {"time": 1, "wind": [1, 0, 0], "wind": [0, 0, 1]}]})");
    EXPECT_NE(deep.find("/keys/1/wind: the key 'wind' is given twice"), std::string::npos) << deep;
    std::string setting = loadError(R"({"settings": {"oit_k": 4, "samples": 4, "oit_k": 8}})");
    EXPECT_NE(setting.find("/settings/oit_k: the key 'oit_k' is given twice"), std::string::npos) << setting;
    // The same key in two objects is no repetition.
    EXPECT_EQ(loadError(R"({"keys": [{"time": 0, "wind": [1, 0, 0]}, {"time": 1, "wind": [0, 0, 1]}]})"), "");
}

TEST(SceneErrors, TimesMustIncrease)
{
    std::string m = loadError(R"({"keys": [{"time": 0}, {"time": 2}, {"time": 1.5}]})");
    EXPECT_NE(m.find("/keys/2/time: 1.5 is not after the previous key's 2 (times must increase)"), std::string::npos)
        << m;
    EXPECT_NE(loadError(R"({"keys": [{"time": 1}, {"time": 1}]})").find("/keys/1/time"), std::string::npos);
    EXPECT_NE(loadError(R"({"keys": [{"head_yaw": 3}]})").find("/keys/0/time: is missing"), std::string::npos);
    EXPECT_NE(loadError(R"({"keys": [{"time": -1}]})").find("/keys/0/time: -1 is out of range: allowed 0 .. 3600 s"),
              std::string::npos);
}

TEST(SceneErrors, OutOfRangeValuesNameTheRange)
{
    auto expect = [](const std::string& text, const std::string& mention) {
        std::string m = loadError(text);
        EXPECT_NE(m.find(mention), std::string::npos) << text << "\n" << m;
    };
    expect(R"({"keys": [{"time": 0, "sphere": [0, 0, 0, -1]}]})",
           "/keys/0/sphere/3: -1 is out of range: allowed 0 .. 10000");
    expect(R"({"keys": [{"time": 0, "light": {"elevation": 95}}]})",
           "/keys/0/light/elevation: 95 is out of range: allowed -89 .. 89");
    expect(R"({"keys": [{"time": 0, "light": {"intensity": -1}}]})",
           "/keys/0/light/intensity: -1 is out of range: allowed 0 .. 20");
    expect(R"({"keys": [{"time": 0, "head_yaw": 120}]})", "/keys/0/head_yaw: 120 is out of range: allowed -80 .. 80");
    expect(R"({"keys": [{"time": 0, "camera": {"distance": 0}}]})",
           "/keys/0/camera/distance: 0 is out of range: allowed 0.1 .. 10");
    expect(R"({"keys": [{"time": 0, "camera": {"pitch": 90}}]})",
           "/keys/0/camera/pitch: 90 is out of range: allowed -85 .. 85");
    expect(R"({"keys": [{"time": 0, "camera": {"fov": 0.5}}]})",
           "/keys/0/camera/fov: 0.5 is out of range: allowed 1 .. 170");
    expect(R"({"keys": [{"time": 0, "camera": {"eye": [0, 0, 1], "up": [0, 0, 0]}}]})",
           "/keys/0/camera/up: is [0, 0, 0]");
    expect(R"({"keys": [{"time": 0, "camera": {"eye": [0, 0, 1], "target": [0, 0, 1]}}]})",
           "/keys/0/camera/eye: is the target");
    expect(R"({"keys": [{"time": 0, "camera": {"eye": [0, 0, 1], "target": [0, 0, 0], "up": [0, 0, 2]}}]})",
           "/keys/0/camera/up: is along the line of sight");
    // JSON has no NaN or infinity, but it has huge numbers.
    expect(R"({"keys": [{"time": 0, "wind": [1e300, 0, 0]}]})",
           "/keys/0/wind/0: 1e+300 is out of range: allowed -100 .. 100");
    expect("{\n  \"keys\": [\n    {\"time\": 0, \"wind\": [1e400, 0, 0]}\n  ]\n}",
           "bad.json:3:26: 1e400 is too large a number");
    expect(R"({"hair": {"guides": 0}})", "/hair/guides: 0 is out of range: allowed 1 .. 2000000");
    expect(R"({"hair": {"vertices": 65}})", "/hair/vertices: 65 is out of range: allowed 4 .. 64");
    expect(R"({"hair": {"vertices_per_strand": 3}})", "/hair/vertices_per_strand: 3 is out of range: allowed 4 .. 64");
    // Numbers read the same way everywhere (app/settings/value_text.h): the value as written, in full.
    expect(R"({"keys": [{"time": 0, "head_yaw": 80.123456789012}]})",
           "/keys/0/head_yaw: 80.123456789012 is out of range: allowed -80 .. 80 degrees");
    expect(R"({"hair": {"hair_length": 2.123456789012}})",
           "/hair/hair_length: 2.123456789012 is out of range: allowed 0.01 .. 2 m");
    expect(R"({"hair": {"files": ["a.tfx", {"file": "b.tfx", "drag": 101}]}})",
           "/hair/files/1/drag: 101 is out of range: allowed 0 .. 100");
    expect(R"({"physics": {"sphere": [0, 0, 0, 1e5]}})", "/physics/sphere/3: 100000 is out of range");
    expect(R"({"colliders": [{"center": [0, 0, 0], "radii": [0.1, 0, 0.1]}]})", "/colliders/0/radii: must all be > 0");
    expect(R"({"settings": {"strands_per_guide": 0}})",
           "/settings/strands_per_guide: 0 is out of range: allowed 1 .. 4096");
    expect(R"({"settings": {"interpolation": "cubic"}})",
           "/settings/interpolation: 'cubic' is not allowed: single | multi | mixed");
    expect(R"({"interpolation": "cubic"})", "/interpolation: 'cubic' is not allowed: linear | smooth");
    expect(R"({"version": 2})", "/version: 2 is not a version this Wisp reads (it reads 1)");
}

// An exact camera in a key: eye, target, up and field of view read and written back.
TEST(Scene, AnExactCameraReadsAndSaves)
{
    TempDir dir;
    writeFile(
        dir / "s.json",
        R"({"keys": [{"time": 0, "camera": {"eye": [0.1, 0.2, 1.5], "target": [0, 0.1, 0], "up": [0, 1, 0.5], "fov": 24}}]})");
    Scene s = loadScene(dir / "s.json");
    ASSERT_EQ(s.keys.size(), 1u);
    EXPECT_EQ(s.keys[0].cameraEye, glm::vec3(0.1f, 0.2f, 1.5f));
    EXPECT_EQ(s.keys[0].cameraTarget, glm::vec3(0.0f, 0.1f, 0.0f));
    EXPECT_EQ(s.keys[0].cameraUp, glm::vec3(0.0f, 1.0f, 0.5f));
    EXPECT_EQ(s.keys[0].cameraFovDeg, 24.0f);
    saveScene(dir / "t.json", s);
    EXPECT_TRUE(loadScene(dir / "t.json") == s);
}

TEST(SceneErrors, ContradictionsAreNamed)
{
    EXPECT_NE(loadError(R"({"hair": {"files": ["a.tfx"], "guides": 3}})")
                  .find("/hair/guides: applies to grown hair, but this hair is loaded from /hair/files"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"hair": {"scale": 2}})").find("/hair/scale: places loaded hair, but this hair is grown"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"hair": {"files": []}})").find("/hair/files: must name 1 to 8 hair files, got 0"),
              std::string::npos);
    EXPECT_NE(loadError(R"({"head": ""})").find("/head: must not be empty"), std::string::npos);
}

TEST(SceneErrors, MissingAndMalformedFiles)
{
    try {
        loadScene("/nonexistent/scene.json");
        ADD_FAILURE() << "a missing scene was accepted";
    } catch (const UserError& e) {
        EXPECT_EQ(std::string(e.what()), "/nonexistent/scene.json: the scene file does not exist");
    }
    // A trailing comma on line 4: the message names the line and column.
    std::string m = loadError("{\n  \"hair\": {\n    \"guides\": 60,\n  }\n}\n");
    EXPECT_NE(m.find("bad.json:4:3: malformed JSON:"), std::string::npos) << m;
    EXPECT_NE(loadError("{\"keys\": [").find("bad.json:1:11: malformed JSON:"), std::string::npos);
    EXPECT_NE(loadError("").find("malformed JSON"), std::string::npos);
}

TEST(SceneErrors, AnUnknownKeyNamesTheKeyAndTheFile)
{
    TempDir dir;
    writeFile(dir / "mine.json", R"({"hair": {"guides": 40, "vertices_per_strnd": 8}})");
    try {
        loadScene(dir / "mine.json");
        ADD_FAILURE() << "an unknown key was accepted";
    } catch (const UserError& e) {
        std::string m = e.what();
        EXPECT_EQ(m.rfind((dir / "mine.json").string() + ": /hair/vertices_per_strnd: unknown key (known: ", 0), 0u)
            << m;
    }
    std::string file = loadError(R"({"hair": {"files": [{"file": "a.tfx", "stiffness": 0.2}]}})");
    EXPECT_NE(file.find("/hair/files/0/stiffness: unknown key (known: file, global_stiffness, local_stiffness, "
                        "damping, drag)"),
              std::string::npos)
        << file;
    // A setting in /physics that is not one of its own is named as a setting.
    EXPECT_NE(
        loadError(R"({"physics": {"gravity": 9}})").find("/physics/gravity: is a setting: put it under /settings"),
        std::string::npos);
}

TEST(Scene, SectionKeysAreTheSettingsNames)
{
    // Every key /hair, /hair/files/N and /physics hold as a setting is the table's name for it.
    for (SceneSection section : {SceneSection::Hair, SceneSection::HairFile, SceneSection::Physics})
        for (const SceneSectionKey& k : sceneSectionKeys(section))
            EXPECT_NE(findSetting(k.name), nullptr) << k.name;
    // The older name reads as the setting's and is written back under the setting's.
    TempDir dir;
    writeFile(dir / "old.json", R"({"hair": {"vertices": 12, "hair_length": 0.25}})");
    Scene old = loadScene(dir / "old.json");
    EXPECT_EQ(old.hair.settings, (SceneSettings{{"vertices_per_strand", "12"}, {"hair_length", "0.25"}}));
    std::string text = sceneJson(old);
    EXPECT_NE(text.find("\"vertices_per_strand\": 12"), std::string::npos) << text;
    EXPECT_EQ(text.find("\"vertices\""), std::string::npos) << text;
    // Given under both names: which one wins would be a guess.
    EXPECT_NE(loadError(R"({"hair": {"vertices": 12, "vertices_per_strand": 16}})")
                  .find("/hair/vertices_per_strand: gives vertices_per_strand again (as vertices_per_strand and "
                        "vertices): give it once"),
              std::string::npos)
        << loadError(R"({"hair": {"vertices": 12, "vertices_per_strand": 16}})");
}

TEST(Scene, EverySectionSettingRoundTripsThroughWriteAndRead)
{
    // Each setting a section holds, at a value other than its default, is written under its name,
    // read back as the same text, and applied as --set would apply it.
    auto otherValue = [](const SettingSpec& spec) {
        Settings defaults;
        SettingValue v = spec.get(defaults);
        v.unset = false;
        switch (spec.type) {
        case SettingType::Number:
        case SettingType::Integer:
            v.number = v.number == spec.range.max ? spec.range.min : spec.range.max;
            break;
        case SettingType::OnOff:
            v.number = 1.0 - v.number;
            break;
        case SettingType::Choice: // another style is another style's every parameter: the first two differ
            v.number = v.number == 1.0 ? 0.0 : 1.0;
            break;
        case SettingType::Vector:
        case SettingType::Color:
            v.vector = glm::dvec3(spec.range.max, spec.range.min, spec.range.max);
            break;
        }
        return settingText(spec, v);
    };
    TempDir dir;
    size_t checked = 0;
    for (SceneSection section : {SceneSection::Hair, SceneSection::HairFile, SceneSection::Physics})
        for (const SceneSectionKey& k : sceneSectionKeys(section)) {
            const SettingSpec& spec = settingSpec(k.name);
            std::string value = otherValue(spec);
            ASSERT_NE(value, settingText(spec, spec.get(Settings{}))) << k.name;
            Scene scene;
            SceneSettings one = {{k.name, value}};
            if (section == SceneSection::Hair)
                scene.hair.settings = one;
            else if (section == SceneSection::HairFile)
                scene.hair.files = {{"a.tfx", one}};
            else
                scene.physics = one;
            std::string text = sceneJson(scene);
            EXPECT_NE(text.find("\"" + k.name + "\": "), std::string::npos) << text;
            Scene back = parseScene(text, dir / "s.json");
            EXPECT_TRUE(back == scene) << k.name << "\n" << text << "\nread back as\n" << sceneJson(back);
            if (section != SceneSection::HairFile) {
                Settings settings;
                HairSource source;
                applyScene(back, dir / "s.json", settings, source);
                EXPECT_EQ(settingText(spec, spec.get(settings)), value) << k.name;
            }
            ++checked;
        }
    EXPECT_GT(checked, 30u); // the growth settings, the part settings (twice) and the physics three
}
