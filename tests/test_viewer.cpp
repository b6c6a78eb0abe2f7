// tests/test_viewer.cpp: the window's interactive state without a window: keys move the sphere
// relative to the camera and the light around the head, the head's turn settles on its target,
// wind and one-shot requests behave, scripts parse; its head turn is the scene files' (headYawTransform).
#include "app/scene/scene_file.h"
#include "app/settings/settings_table.h"
#include "app/window/viewer.h"
#include "app/window/window_scene.h"
#include "core/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace wisp;
using wisp::test::TempDir;

namespace {

Viewer makeViewer()
{
    Bounds scene{glm::vec3(-0.1f), glm::vec3(0.1f)};
    return Viewer(OrbitCamera::framing(scene, 1.5f), scene, glm::vec4(0.0f), LightSettings{}, glm::vec3(0.0f));
}

} // namespace

TEST(Viewer, ArrowsMoveTheSphereAlongTheCameraAxes)
{
    Viewer v = makeViewer();
    EXPECT_EQ(v.sphere().w, 0.0f); // parked, off
    glm::mat4 view = v.camera().view();
    glm::vec3 right(view[0][0], view[1][0], view[2][0]);
    glm::vec3 before = glm::vec3(v.sphere());
    v.press(ViewerKey::SphereRight);
    for (int i = 0; i < 30; ++i)
        v.update(1.0f / 60.0f);
    v.release(ViewerKey::SphereRight);
    v.update(1.0f); // released: no more motion
    glm::vec3 moved = glm::vec3(v.sphere()) - before;
    EXPECT_GT(v.sphere().w, 0.0f); // moving it switched it on
    EXPECT_GT(glm::dot(moved, right), 0.9f * glm::length(moved));
    EXPECT_NEAR(glm::length(moved), 0.35f * 0.5f * glm::length(glm::vec3(0.2f)), 1e-4f); // half a second
    v.press(ViewerKey::SphereToggle);
    EXPECT_EQ(v.sphere().w, 0.0f);
}

TEST(Viewer, TheHeadTurnSettlesOnItsTargetAndTheLightStaysInRange)
{
    Viewer v = makeViewer();
    v.press(ViewerKey::HeadRight);
    v.release(ViewerKey::HeadRight);
    float peak = 0.0f;
    for (int i = 0; i < 240; ++i) {
        v.update(1.0f / 60.0f);
        peak = std::max(peak, v.headYawDeg());
    }
    EXPECT_NEAR(v.headYawDeg(), 30.0f, 0.1f);
    EXPECT_LT(peak, 30.5f); // critically damped: no overshoot to speak of
    v.press(ViewerKey::LightUp);
    for (int i = 0; i < 600; ++i)
        v.update(1.0f / 60.0f);
    EXPECT_LE(v.light().elevationDeg, float(settingSpec("light_elevation").range.max));
}

TEST(Viewer, WindPauseStepAndOneShotRequests)
{
    Viewer v = makeViewer();
    EXPECT_EQ(v.wind(), glm::vec3(0.0f));
    v.press(ViewerKey::Wind);
    float strength = glm::length(v.wind());
    EXPECT_GT(strength, 0.0f);
    v.press(ViewerKey::WindStronger);
    EXPECT_NEAR(glm::length(v.wind()), strength * 1.25f, 1e-4f);
    v.press(ViewerKey::Step);
    v.press(ViewerKey::Step);
    EXPECT_TRUE(v.paused());
    EXPECT_EQ(v.takeSteps(), 2u);
    EXPECT_EQ(v.takeSteps(), 0u);
    v.press(ViewerKey::Screenshot);
    EXPECT_TRUE(v.takeScreenshot());
    EXPECT_FALSE(v.takeScreenshot());
}

TEST(Viewer, ScriptsParseAndPlayByFrame)
{
    test::TempDir dir;
    test::writeFile(dir / "s.txt", "# comment\n5 tap w\n1 press j   # held\n3 release j\n4 drag-light 10 0\n");
    std::vector<ScriptEvent> events = loadScript(dir / "s.txt");
    ASSERT_EQ(events.size(), 4u);
    EXPECT_EQ(events.front().frame, 1u); // sorted by frame
    Viewer v = makeViewer();
    float azimuth = v.light().azimuthDeg;
    for (uint32_t f = 0; f < 6; ++f) {
        playScript(events, f, v, 100.0f);
        v.update(1.0f / 60.0f);
    }
    EXPECT_NEAR(v.light().azimuthDeg, azimuth - 2.0f + 4.0f, 1e-3f); // 2 frames held J, then a 10 px drag
    EXPECT_GT(glm::length(v.wind()), 0.0f);
    EXPECT_THROW(loadScript(dir / "missing.txt"), UserError);
}

TEST(Viewer, HeadTurnIsTheScenesConvention)
{
    // The window turns the head as a scene's head_yaw does (app/scene/scene_file.h headYawTransform).
    Bounds head{glm::vec3(-0.2f, -0.1f, -0.1f), glm::vec3(0.2f, 0.3f, 0.1f)};
    Viewer viewer(OrbitCamera::framing(head, 1.5f), head, glm::vec4(0.0f), LightSettings{}, glm::vec3(0.0f));
    viewer.press(ViewerKey::HeadLeft);
    viewer.release(ViewerKey::HeadLeft);
    for (int i = 0; i < 30; ++i)
        viewer.update(1.0f / 60.0f);
    ASSERT_NE(viewer.headYawDeg(), 0.0f);
    glm::mat4 a = headYawTransform(head, viewer.headYawDeg()), b = viewer.headTransform();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(a[c][r], b[c][r], 1e-6f);
    // The centre stays put; a point in front of it turns about the vertical axis.
    glm::vec3 centre = head.center();
    glm::mat4 quarter = headYawTransform(head, 90.0f);
    glm::vec3 moved = glm::vec3(quarter * glm::vec4(centre + glm::vec3(0.0f, 0.0f, 0.1f), 1.0f));
    EXPECT_NEAR(glm::length(glm::vec3(quarter * glm::vec4(centre, 1.0f)) - centre), 0.0f, 1e-6f);
    EXPECT_NEAR(moved.x - centre.x, 0.1f, 1e-6f);
    EXPECT_NEAR(moved.y - centre.y, 0.0f, 1e-6f);
}

TEST(Viewer, TheWindowsSavedSceneGrowsTheSameGroom)
{
    // F2 on a styled groom, then `wisp view --scene` on what it saved: every setting comes back,
    // the style's shape stiffness (no setting of its own) too. It kept seven growth settings only,
    // and a style's groom came back as the default's.
    for (const char* refine : {"", "curl=0.004"}) {
        Settings settings;
        applySetting(settings, "hair_style=afro");
        if (*refine)
            applySetting(settings, refine);
        TempDir dir;
        std::filesystem::path path = dir / "saved.json";
        saveScene(path, windowScene(path, HairSource{}, settings, SceneState{}));
        Settings back;
        HairSource source;
        applyScene(loadScene(path), path, back, source);
        EXPECT_EQ(settingsJson(back).dump(), settingsJson(settings).dump()) << refine;
        if (!*refine) { // a refined style is "custom": its stiffness is the default's (docs: hair styles)
            EXPECT_EQ(back.growth.globalStiffness, settings.growth.globalStiffness);
        }
        EXPECT_EQ(back.growth.curlRadiusMetres, settings.growth.curlRadiusMetres) << refine;
    }
}
