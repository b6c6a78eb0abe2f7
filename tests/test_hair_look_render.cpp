// tests/test_hair_look_render.cpp: the hair's look in the renderer: every shading model renders
// (and differently), blonde renders lighter than black, backlit hair glows (light transmitted
// through the fibres, TT), the lookup tables follow the look, the scalp's paint. (The presets and the
// look's settings, on the CPU: tests/test_hair_look.cpp.)
#include "app/session/headless.h"
#include "gpu/frame.h"
#include "physics/groomed_head.h"
#include "renderer/mesh_pass.h"
#include "renderer/renderer.h"
#include "shading/hair_look.h"
#include "small_groomed_head.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace wisp;

using test::renderHair;
using test::smallGroomedHead;
using test::smallRenderSettings;

namespace {

// Mean luminance (0..255) over the pixels where the hair changed the bald picture.
double hairBrightness(const Picture& hair, const Picture& bald, size_t* count = nullptr)
{
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < hair.rgba.size(); i += 4) {
        int d = std::abs(hair.rgba[i] - bald.rgba[i]) + std::abs(hair.rgba[i + 1] - bald.rgba[i + 1]) +
                std::abs(hair.rgba[i + 2] - bald.rgba[i + 2]);
        if (d < 12)
            continue;
        sum += 0.2126 * hair.rgba[i] + 0.7152 * hair.rgba[i + 1] + 0.0722 * hair.rgba[i + 2];
        ++n;
    }
    if (count)
        *count = n;
    return n ? sum / double(n) : 0.0;
}

} // namespace

TEST(HairLookRender, EveryShadingModelRendersItsOwnPicture)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(150);
    RenderSettings s = smallRenderSettings();
    Picture bald = renderPicture(ctx, scene.head, s);
    std::vector<Picture> pictures;
    for (ShadingModel m : {ShadingModel::Karis, ShadingModel::Kajiya, ShadingModel::Lut}) {
        s.hair.model = m;
        pictures.push_back(renderHair(ctx, scene, s));
        size_t n = 0;
        double brightness = hairBrightness(pictures.back(), bald, &n);
        EXPECT_GT(n, 1000u);
        EXPECT_GT(brightness, 15.0) << "model " << int(m) << " draws visible hair";
    }
    EXPECT_NE(pictures[0].rgba, pictures[1].rgba);
    EXPECT_NE(pictures[0].rgba, pictures[2].rgba);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(HairLookRender, BlondeRendersLighterThanBrownAndBrownThanBlack)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(150);
    RenderSettings s = smallRenderSettings();
    Picture bald = renderPicture(ctx, scene.head, s);
    double previous = -1.0;
    for (const char* preset : {"black", "brown", "blonde"}) {
        ASSERT_TRUE(applyHairPreset(s.hair, preset));
        double b = hairBrightness(renderHair(ctx, scene, s), bald);
        EXPECT_GT(b, previous + 5.0) << preset;
        previous = b;
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(HairLookRender, BacklitHairGlows)
{
    // With the light behind the head, what reaches the camera has passed through fibres (TT) or
    // scattered among them: lighter hair glows, compared with the same hair with the light off.
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(150);
    RenderSettings s = smallRenderSettings();
    applyHairPreset(s.hair, "blonde");
    s.light.azimuthDeg = 180.0f;
    s.light.elevationDeg = 20.0f;
    s.fill.intensity = 0.0f; // the key alone: the studio's fill and rim would light both pictures
    s.rim.intensity = 0.0f;
    Picture bald = renderPicture(ctx, scene.head, s);
    Picture backlit = renderHair(ctx, scene, s);
    s.light.intensity = 0.0f;
    Picture dark = renderHair(ctx, scene, s);
    EXPECT_GT(hairBrightness(backlit, bald), hairBrightness(dark, bald) + 10.0);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// multiple_scattering=off leaves Karis's multiple scattering out of karis and lut: their hair is
// darker, on both drawing paths; kajiya has none, so its picture does not change by a byte.
TEST(HairLookRender, MultipleScatteringOffDarkensKarisAndLeavesKajiyaAlone)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(150);
    RenderSettings s = smallRenderSettings();
    applyHairPreset(s.hair, "blonde"); // light hair: multiple scattering is much of its colour
    OrbitCamera camera;
    LightFit fit{Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)}, 1.0f};
    EXPECT_EQ(pack(s, camera, {64, 64}, 0.0f, fit).multipleScattering, 1u);
    s.hair.multipleScattering = false;
    EXPECT_EQ(pack(s, camera, {64, 64}, 0.0f, fit).multipleScattering, 0u);
    Picture bald = renderPicture(ctx, scene.head, s);
    for (HairRaster raster : {HairRaster::Graphics, HairRaster::Compute}) {
        s.hairRaster = raster;
        for (ShadingModel m : {ShadingModel::Karis, ShadingModel::Lut, ShadingModel::Kajiya}) {
            s.hair.model = m;
            s.hair.multipleScattering = true;
            Picture on = renderHair(ctx, scene, s);
            s.hair.multipleScattering = false;
            Picture off = renderHair(ctx, scene, s);
            if (m == ShadingModel::Kajiya) {
                EXPECT_EQ(on.rgba, off.rgba) << "raster " << int(raster);
                continue;
            }
            EXPECT_LT(hairBrightness(off, bald), hairBrightness(on, bald) - 10.0)
                << "raster " << int(raster) << " model " << int(m);
        }
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(HairLookRender, TheLookupTablesFollowTheLook)
{
    // In lut mode the tables are rebuilt when the look changes (the old image retired with the
    // frame): the same renderer draws darker hair after more melanin, validation clean.
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(150);
    RenderSettings s = smallRenderSettings();
    s.hair.model = ShadingModel::Lut;
    applyHairPreset(s.hair, "blonde");
    test::HairRenderer hair(ctx, scene, s);
    Renderer& renderer = hair.renderer;
    Frame& frame = hair.frame;
    OrbitCamera camera = hair.camera;
    Picture bald = renderPicture(ctx, scene.head, s);
    Picture blonde = renderFrame(ctx, renderer, frame, camera);
    applyHairPreset(renderer.settings().hair, "black");
    Picture black = renderFrame(ctx, renderer, frame, camera);
    EXPECT_GT(hairBrightness(blonde, bald), hairBrightness(black, bald) + 10.0);
    // Byte for byte what a renderer made black from the start draws: the tables were rebuilt.
    RenderSettings blackFromStart = s;
    applyHairPreset(blackFromStart.hair, "black");
    EXPECT_EQ(renderHair(ctx, scene, blackFromStart).rgba, black.rgba);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(ScalpPaint, CoverageIsFullAmongTheRootsAndFadesPastTheHairline)
{
    GroomedHead scene = smallGroomedHead(300);
    // The rule for a loaded groom (grown hair paints its own scalp field: Groom.GrownStrandsStay...).
    scene.strands.scalpPaint.clear();
    std::vector<float> w = scalpCoverage(scene.head.mesh, scene.strands);
    ASSERT_EQ(w.size(), scene.head.mesh.positions.size());
    // Every vertex next to a root is painted fully; the face and the shoulders are not painted.
    uint32_t V = scene.strands.verticesPerStrand;
    size_t nearRoots = 0, painted = 0;
    for (size_t v = 0; v < w.size(); ++v) {
        float nearest = INFINITY;
        for (size_t s = 0; s < scene.strands.strandCount(); ++s)
            nearest = std::min(nearest, glm::length(scene.strands.rest[s * V] - scene.head.mesh.positions[v]));
        if (nearest < 0.004f) {
            ++nearRoots;
            painted += w[v] == 1.0f ? 1 : 0;
        }
        if (nearest > 0.08f) {
            EXPECT_EQ(w[v], 0.0f) << "vertex " << v << " is far from every root";
        }
    }
    EXPECT_GT(nearRoots, 100u);
    EXPECT_EQ(painted, nearRoots);
}

TEST(ScalpPaint, SeenFromAboveTheGroomShowsNoBareScalp)
{
    // Bare, the scalp shows from the default camera as a wide white band along the parting and as
    // white skull between the crown's strands. Where it shows between strands seen from above (the
    // pixels the painting changes), painted a darkened hair colour it is not bright skin.
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = smallGroomedHead(400);
    RenderSettings s = smallRenderSettings();
    s.width = 160;
    s.height = 160;
    SceneState above;
    above.light = s.light;
    above.camera.pitchDeg = 80.0f;
    above.camera.yawDeg = 0.0f;
    SceneTimeline fromAbove({}, SceneInterpolation::Linear, above);
    HairSession first(ctx, scene, SimSettings{}, fromAbove), second(ctx, scene, SimSettings{}, fromAbove);
    Picture painted = renderPicture(ctx, first, s);
    s.scalpPaint = 0.0f;
    Picture bare = renderPicture(ctx, second, s);
    auto luminance = [](const Picture& p, size_t i) {
        return 0.2126f * p.rgba[i] + 0.7152f * p.rgba[i + 1] + 0.0722f * p.rgba[i + 2];
    };
    size_t scalp = 0, bareSkin = 0, paintedSkin = 0;
    for (size_t i = 0; i < painted.rgba.size(); i += 4) {
        if (std::abs(painted.rgba[i] - bare.rgba[i]) + std::abs(painted.rgba[i + 1] - bare.rgba[i + 1]) < 24)
            continue;
        ++scalp;
        bareSkin += luminance(bare, i) > 140.0f ? 1 : 0;
        paintedSkin += luminance(painted, i) > 140.0f ? 1 : 0;
    }
    // (A few stay bright: strands' highlights over the scalp, and the hairline's fade.)
    EXPECT_GT(bareSkin, scalp / 8) << "bare, the scalp shows white between the strands";
    EXPECT_LT(paintedSkin, scalp / 16) << "painted, hardly any (" << bareSkin << " bare)";
    EXPECT_LT(paintedSkin * 4, bareSkin);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}
