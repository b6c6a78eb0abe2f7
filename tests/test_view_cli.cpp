// tests/test_view_cli.cpp: `wisp view` under Xvfb: it opens, draws and closes; scripted runs are
// reproducible; scripts move the sphere, the light and the head; the panel applies settings; F2 and
// F3 save and load scenes; scenes play; F5 reloads the shaders; a lost device; bad scripts and no
// display.
#include "cli_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

using namespace wisp::test;

namespace {

// The numbers in the window's closing line "sphere on at (x, y, z) r R, light azimuth A elevation E, head yaw Y, ...".
struct ViewerStatus {
    bool sphereOn = false;
    float x = 0, y = 0, z = 0, r = 0, azimuth = 0, elevation = 0, yaw = 0;
};

ViewerStatus parseStatus(const std::string& out)
{
    ViewerStatus s;
    size_t at = out.find("sphere ");
    EXPECT_NE(at, std::string::npos) << out;
    if (at == std::string::npos)
        return s;
    char on[8] = {};
    int n = std::sscanf(out.c_str() + at, "sphere %3s at (%f, %f, %f) r %f, light azimuth %f elevation %f, head yaw %f",
                        on, &s.x, &s.y, &s.z, &s.r, &s.azimuth, &s.elevation, &s.yaw);
    EXPECT_EQ(n, 8) << out;
    s.sphereOn = std::string(on) == "on";
    return s;
}

} // namespace

TEST(Window, OpensUnderXvfbDrawsAndClosesCleanly)
{
    WISP_REQUIRE_XVFB();
    TempDir dir;
    auto r = runWisp(
        "--validation view --width 320 --height 240 --frames 4 --guides 200 --set shadow_size=512 --screenshot '" +
            (dir / "shot.png").string() + "'",
        WISP_XVFB);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("closed after 4 frames"), std::string::npos) << r.out;
    EXPECT_TRUE(std::filesystem::exists(dir / "shot.png"));
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
}

TEST(Window, ScriptedRunsWithHairAreReproducible)
{
    // With --frames every frame advances one frame's worth of fixed steps, and the hair grid sums
    // in fixed point: two runs give the same screenshot, and it differs from the bald head.
    WISP_REQUIRE_XVFB();
    TempDir dir;
    std::string common = "view --width 200 --height 150 --frames 12 --guides 200 --set strands_per_guide=8 --set "
                         "shadow_size=256 --wind 3,0,0 --screenshot ";
    auto xvfb = WISP_XVFB;
    ASSERT_EQ(runWisp(common + "'" + (dir / "a.png").string() + "'", xvfb).status, 0);
    ASSERT_EQ(runWisp(common + "'" + (dir / "b.png").string() + "'", xvfb).status, 0);
    ASSERT_EQ(runWisp("view --width 200 --height 150 --frames 12 --no-hair --screenshot '" +
                          (dir / "bald.png").string() + "'",
                      xvfb)
                  .status,
              0);
    EXPECT_EQ(readFile(dir / "a.png"), readFile(dir / "b.png"));
    EXPECT_NE(readFile(dir / "a.png"), readFile(dir / "bald.png"));
}

TEST(Window, AScriptMovesTheSphereAndTheLightAndTurnsTheHead)
{
    WISP_REQUIRE_XVFB();
    TempDir dir;
    writeFile(dir / "moves.txt",
              "# sphere: held right for 18 frames, then dragged up; light: held L for 20 frames; head: one turn\n"
              "2 press right\n20 release right\n22 drag-sphere 0 -40\n10 press l\n30 release l\n12 tap a\n");
    writeFile(dir / "still.txt", "# nothing happens\n");
    auto xvfb = WISP_XVFB;
    std::string common = "--validation view --width 160 --height 120 --frames 32 --guides 60 --set strands_per_guide=4 "
                         "--set shadow_size=256 ";
    auto moved = runWisp(common + "--script '" + (dir / "moves.txt").string() + "' --screenshot '" +
                             (dir / "moved.png").string() + "'",
                         xvfb);
    ASSERT_EQ(moved.status, 0) << moved.err;
    auto still = runWisp(common + "--script '" + (dir / "still.txt").string() + "' --screenshot '" +
                             (dir / "still.png").string() + "'",
                         xvfb);
    ASSERT_EQ(still.status, 0) << still.err;
    ViewerStatus a = parseStatus(moved.out), b = parseStatus(still.out);
    EXPECT_TRUE(a.sphereOn);  // moving it switched it on
    EXPECT_FALSE(b.sphereOn); // parked and off until used
    // 18 frames of 1/60 s at 0.35 scene sizes a second to the camera's right, then 40 pixels up.
    EXPECT_GT(std::abs(a.x - b.x) + std::abs(a.z - b.z), 0.01f);
    EXPECT_GT(a.y, b.y);
    EXPECT_NEAR(a.azimuth - b.azimuth, 20.0f, 0.5f); // 20 frames at 60 degrees a second
    EXPECT_EQ(a.elevation, b.elevation);
    EXPECT_LT(a.yaw, -5.0f); // turning toward -30 degrees
    EXPECT_EQ(b.yaw, 0.0f);
    EXPECT_NE(readFile(dir / "moved.png"), readFile(dir / "still.png")) << "the screenshot shows the moves";
}

TEST(Window, ThePanelAppliesSettingsLiveAndDrawsOverTheScene)
{
    // Settings set as the panel sets them: one applied in place (shading), one that rebuilds the
    // renderer (shadow_size), one that rebuilds the solver (step_hz); the panel drawn over the
    // scene only when asked into the screenshot.
    WISP_REQUIRE_XVFB();
    TempDir dir;
    writeFile(dir / "sets.txt",
              "2 set shading=kajiya\n3 set shadow_size=128\n4 set step_hz=120\n5 set hair_preset=blonde\n");
    writeFile(dir / "none.txt", "");
    auto xvfb = WISP_XVFB;
    std::string common = "--validation view --width 200 --height 150 --frames 8 --guides 60 --set strands_per_guide=4 "
                         "--set shadow_size=256 --script '";
    auto changed =
        runWisp(common + (dir / "sets.txt").string() + "' --screenshot '" + (dir / "changed.png").string() + "'", xvfb);
    ASSERT_EQ(changed.status, 0) << changed.err;
    auto plain =
        runWisp(common + (dir / "none.txt").string() + "' --screenshot '" + (dir / "plain.png").string() + "'", xvfb);
    ASSERT_EQ(plain.status, 0) << plain.err;
    auto panel = runWisp(common + (dir / "none.txt").string() + "' --screenshot-panel --screenshot '" +
                             (dir / "panel.png").string() + "'",
                         xvfb);
    ASSERT_EQ(panel.status, 0) << panel.err;
    EXPECT_NE(readFile(dir / "changed.png"), readFile(dir / "plain.png")) << "blonde Kajiya-Kay hair looks different";
    EXPECT_NE(readFile(dir / "panel.png"), readFile(dir / "plain.png")) << "the panel is drawn over the scene";

    writeFile(dir / "bad.txt", "1 set guides=10\n");
    auto bad = runWisp(common + (dir / "bad.txt").string() + "'", xvfb);
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.err.find("the hair is grown at start"), std::string::npos) << bad.err;
    writeFile(dir / "bad.txt", "1 set shading=phong\n");
    bad = runWisp(common + (dir / "bad.txt").string() + "'", xvfb);
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.err.find("karis | kajiya | lut"), std::string::npos) << bad.err;
}

TEST(Window, SamplesTheDeviceLacksAreSaidWhenThePanelSetsThem)
{
    // The command line says what a device draws of --samples it lacks; the panel drew them as fewer
    // without a word. A script sets them as the panel does.
    WISP_REQUIRE_XVFB();
    auto info = runWisp("info --json");
    ASSERT_EQ(info.status, 0) << info.err;
    std::vector<uint32_t> has;
    size_t usable = 0;
    for (const auto& d : nlohmann::json::parse(info.out))
        if (d["usable"].get<bool>()) {
            ++usable;
            has = d["msaa_samples"].get<std::vector<uint32_t>>();
        }
    if (usable != 1 || std::find(has.begin(), has.end(), 8u) != has.end())
        GTEST_SKIP() << "not one usable device lacking 8 samples";
    TempDir dir;
    writeFile(dir / "samples.txt", "2 set samples=8\n");
    auto r = runWisp("--validation view --width 64 --height 48 --frames 4 --guides 10 --set strands_per_guide=1 "
                     "--set shadow_size=128 --script '" +
                         (dir / "samples.txt").string() + "'",
                     WISP_XVFB);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("wisp: samples 8: '"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("; drawing with "), std::string::npos) << r.err;
}

TEST(Window, F2SavesTheStateAsASceneAndF3LoadsItBack)
{
    WISP_REQUIRE_XVFB();
    TempDir dir;
    // Sphere moved and switched on, Kajiya-Kay, saved at frame 9; switched off, then loaded back.
    writeFile(dir / "s.txt", "3 press right\n8 release right\n9 tap f2\n12 tap o\n14 tap f3\n");
    std::string prefix = "cd '" + dir.path().string() + "' && " WISP_XVFB;
    auto r = runWisp("--validation view --frames 18 --width 160 --height 120 --guides 60 --set strands_per_guide=4 "
                     "--set shadow_size=256 --set shading=kajiya --script s.txt",
                     prefix);
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_TRUE(std::filesystem::exists(dir / "wisp-scene-001.json")) << r.out;
    EXPECT_NE(r.out.find("loaded the scene"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("sphere on at"), std::string::npos) << "F3 brought back the saved sphere: " << r.out;
    std::string json = readFile(dir / "wisp-scene-001.json");
    EXPECT_NE(json.find("\"shading\": \"kajiya\""), std::string::npos) << json;
    EXPECT_NE(json.find("\"guides\": 60"), std::string::npos) << json;
    // The saved file is a scene like any other.
    auto rendered = runWisp("--validation render --scene '" + (dir / "wisp-scene-001.json").string() +
                            "' --width 96 --height 72 --out '" + (dir / "saved.png").string() + "'");
    EXPECT_EQ(rendered.status, 0) << rendered.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "saved.png"));
}

TEST(Window, AScenePlaysItsKeysAndTStopsIt)
{
    WISP_REQUIRE_XVFB();
    TempDir dir;
    writeFile(dir / "stop.txt", "0 tap t\n");
    writeFile(dir / "none.txt", "");
    auto xvfb = WISP_XVFB;
    // 60 frames of 1/60 s: 1.0 s into head-turn.json, whose head turns from 0 (0.5 s) to -60 (1.2 s).
    std::string common = "--validation view --scene '" + std::string(WISP_SOURCE_DIR) +
                         "/scenes/head-turn.json' --frames 60 --width 96 --height 72 --guides 40 "
                         "--set strands_per_guide=2 --set shadow_size=128 --script '";
    auto played = runWisp(common + (dir / "none.txt").string() + "'", xvfb);
    ASSERT_EQ(played.status, 0) << played.err;
    auto stopped = runWisp(common + (dir / "stop.txt").string() + "'", xvfb);
    ASSERT_EQ(stopped.status, 0) << stopped.err;
    float playedYaw = 0.0f, stoppedYaw = 0.0f;
    ASSERT_EQ(std::sscanf(played.out.c_str() + played.out.find("head yaw"), "head yaw %f", &playedYaw), 1)
        << played.out;
    ASSERT_EQ(std::sscanf(stopped.out.c_str() + stopped.out.find("head yaw"), "head yaw %f", &stoppedYaw), 1)
        << stopped.out;
    EXPECT_LT(playedYaw, -20.0f);
    EXPECT_GT(playedYaw, -60.0f);
    EXPECT_EQ(stoppedYaw, 0.0f);
}

TEST(Window, SceneSetsTheInitialSphereAndLight)
{
    WISP_REQUIRE_XVFB();
    TempDir dir;
    writeFile(
        dir / "s.json",
        R"({"keys": [{"time": 0, "sphere": [0.1, 0.2, 0.05, 0.04], "light": {"azimuth": 77, "elevation": 12}}]})");
    auto r = runWisp("view --scene '" + (dir / "s.json").string() + "' --no-hair --width 160 --height 120 --frames 2",
                     WISP_XVFB);
    ASSERT_EQ(r.status, 0) << r.err;
    ViewerStatus s = parseStatus(r.out);
    EXPECT_TRUE(s.sphereOn);
    EXPECT_NEAR(s.x, 0.1f, 1e-4f);
    EXPECT_NEAR(s.y, 0.2f, 1e-4f);
    EXPECT_NEAR(s.r, 0.04f, 1e-4f);
    EXPECT_NEAR(s.azimuth, 77.0f, 0.05f);
    EXPECT_NEAR(s.elevation, 12.0f, 0.05f);
}

TEST(Window, DeviceLostClosesTheWindowWithItsOwnStatus)
{
    WISP_REQUIRE_XVFB();
    // Two frames in flight, a swapchain, the panel: their teardown after the loss returns cleanly.
    auto r = runWisp("--validation view --guides 60 --set strands_per_guide=4 --width 160 --height 120 --frames 30",
                     lostAt(30) + " " WISP_XVFB);
    expectDeviceLost(r, "view");
}

TEST(BadInput, ViewWithoutDisplayPointsToRender)
{
    auto r = runWisp("view", "env -u DISPLAY -u WAYLAND_DISPLAY");
    expectUserError(r, "wisp render");
}

TEST(BadInput, ViewScriptErrorsNameTheFileAndLine)
{
    WISP_REQUIRE_XVFB();
    TempDir dir;
    auto xvfb = WISP_XVFB;
    auto check = [&](const std::string& text, const std::string& expected) {
        writeFile(dir / "bad.txt", text);
        auto r = runWisp("view --frames 1 --no-hair --script '" + (dir / "bad.txt").string() + "'", xvfb);
        EXPECT_EQ(r.status, 2) << text;
        EXPECT_NE(r.err.find("bad.txt:"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    };
    check("1 press q\n", "unknown key 'q'");
    check("# ok\nx tap a\n", ":2: 'x' is not a frame number");
    check("3 jump\n", "unknown action 'jump'");
    check("3 drag-sphere 1\n", "two finite pixel distances");
    check("3 tap a b\n", "unexpected 'b'");
}

TEST(Window, F5ReloadsEveryShaderTheSolversIncluded)
{
    // F5 rebuilds the shaders' SPIR-V (the build's own target), makes the solver's kernels and the
    // renderer's pipelines again, and the run goes on clean.
    WISP_REQUIRE_XVFB();
    TempDir dir;
    writeFile(dir / "f5.txt", "2 tap f5\n");
    auto r = runWisp("--validation view --width 160 --height 120 --frames 5 --guides 40 --set strands_per_guide=2 "
                     "--set shadow_size=128 --script '" +
                         (dir / "f5.txt").string() + "'",
                     WISP_XVFB);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("wisp: shaders reloaded"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("closed after 5 frames"), std::string::npos) << r.out;
}
