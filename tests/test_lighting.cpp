// tests/test_lighting.cpp: the shared surface-shading header compiled as C++: the same functions
// mesh.frag runs, checked against hand-computed values and their physical properties; and the
// studio's lights and backdrop (frame_params.h) as the meshes' and the strands' shading sums them.
#include "shaders/shared/lighting.h"
#include "shaders/shared/mesh_raster.h"
#include "shaders/shared/strand_shading.h"

#include <gtest/gtest.h>

using namespace gpu;

TEST(Lighting, LambertAtNormalIncidenceIsAlbedoOverPi)
{
    vec3 n(0, 0, 1);
    // Sharpest highlight (roughness 0) and a viewer far from the mirror direction: the
    // specular term is below 1e-30 and only Lambert remains.
    vec3 r = surfaceRadiance(n, n, normalize(vec3(1, 0, 0.05f)), vec3(0.5f), 0.0f, vec3(1.0f));
    EXPECT_NEAR(r.x, 0.5f / 3.14159265f, 1e-6f);
}

TEST(Lighting, NothingFromALightBehindTheSurface)
{
    vec3 r = surfaceRadiance(vec3(0, 0, 1), normalize(vec3(0, 0.3f, -1)), vec3(0, 0, 1), vec3(0.8f), 0.5f, vec3(5.0f));
    EXPECT_EQ(r, vec3(0.0f));
}

TEST(Lighting, DiffuseFallsOffAsCosine)
{
    vec3 n(0, 0, 1), v(0, 1, 0);
    float at0 = surfaceRadiance(n, n, v, vec3(1.0f), 1.0f, vec3(1.0f)).x;
    float at60 = surfaceRadiance(n, normalize(vec3(std::sqrt(3.0f), 0, 1)), v, vec3(1.0f), 1.0f, vec3(1.0f)).x;
    EXPECT_NEAR(at60 / at0, 0.5f, 0.02f);
}

TEST(Lighting, HighlightPeaksInTheMirrorDirection)
{
    vec3 n(0, 0, 1);
    vec3 l = normalize(vec3(1, 0, 1));
    float mirror = surfaceRadiance(n, l, normalize(vec3(-1, 0, 1)), vec3(0.0f), 0.2f, vec3(1.0f)).x;
    float off = surfaceRadiance(n, l, normalize(vec3(-1, 0.6f, 1)), vec3(0.0f), 0.2f, vec3(1.0f)).x;
    EXPECT_GT(mirror, 5.0f * off);
}

TEST(Lighting, HemisphereAmbientBlendsSkyAndGround)
{
    vec3 sky(1, 0, 0), ground(0, 0, 1);
    EXPECT_EQ(hemisphereAmbient(vec3(0, 1, 0), sky, ground), sky);
    EXPECT_EQ(hemisphereAmbient(vec3(0, -1, 0), sky, ground), ground);
    EXPECT_EQ(hemisphereAmbient(vec3(1, 0, 0), sky, ground), vec3(0.5f, 0, 0.5f));
}

TEST(Lighting, ToneMapIsMonotonicAndBounded)
{
    float previous = -1.0f;
    for (float x = 0.0f; x < 50.0f; x += 0.05f) {
        float y = toneMapAces(vec3(x)).x;
        EXPECT_GE(y, previous);
        EXPECT_GE(y, 0.0f);
        EXPECT_LE(y, 1.0f);
        previous = y;
    }
    EXPECT_NEAR(toneMapAces(vec3(0.0f)).x, 0.0f, 1e-6f);
    EXPECT_GT(toneMapAces(vec3(100.0f)).x, 0.99f);
}

namespace {

// A frame lit by the key alone (straight above the camera's axis), no ambient, exposure 1.
FrameParams keyOnlyFrame()
{
    FrameParams f{};
    f.lightDirection = vec3(0, 0, 1);
    f.lightIntensity = 2.0f;
    f.lightColor = vec3(1.0f);
    f.cameraPosition = vec3(0, 0, 5);
    f.exposure = 1.0f;
    f.viewportHeight = 100.0f;
    for (FrameLight& l : f.unshadowed)
        l = FrameLight{.direction = vec3(0, 1, 0), .intensity = 0.0f, .color = vec3(1.0f), .pad = 0.0f};
    return f;
}

} // namespace

TEST(StudioLights, FrameLightListsTheKeyThenTheFillAndTheRim)
{
    FrameParams f = keyOnlyFrame();
    f.unshadowed[0].intensity = 0.5f;
    f.unshadowed[1].intensity = 4.0f;
    EXPECT_EQ(frameLight(f, kFrameKeyLight).direction, f.lightDirection);
    EXPECT_EQ(frameLight(f, kFrameKeyLight).intensity, 2.0f);
    EXPECT_EQ(frameLight(f, 1).intensity, 0.5f);
    EXPECT_EQ(frameLight(f, 2).intensity, 4.0f);
}

TEST(StudioLights, EachLightAddsItsLambertToTheMeshAndOnlyTheKeyIsShadowed)
{
    // Lights at 0 and 60 degrees from the normal, the viewer 45 degrees off it, away from both
    // mirror directions (roughness 0: the highlight is below 1e-8 for both), so each light adds
    // its Lambert term: the fill alone (the key shadowed) is the key's response at half the
    // radiance; the tone map is the same monotonic curve on both sides.
    vec3 n(0, 0, 1), v = normalize(vec3(-1, 0, 1)), albedo(0.5f);
    FrameParams f = keyOnlyFrame();
    vec3 keyAlone = meshSurfaceColor(f, n, v, 1.0f, albedo, 0.0f, albedo, 0.0f);
    f.unshadowed[0].direction = normalize(vec3(-std::sqrt(3.0f), 0, 1)); // 60 degrees: cos = 0.5
    f.unshadowed[0].intensity = 2.0f;
    vec3 withFill = meshSurfaceColor(f, n, v, 1.0f, albedo, 0.0f, albedo, 0.0f);
    EXPECT_GT(withFill.x, keyAlone.x);
    FrameParams half = keyOnlyFrame();
    half.lightIntensity = 1.0f;
    EXPECT_NEAR(meshSurfaceColor(f, n, v, 0.0f, albedo, 0.0f, albedo, 0.0f).x,
                meshSurfaceColor(half, n, v, 1.0f, albedo, 0.0f, albedo, 0.0f).x, 1e-6f);
    // A light from behind the surface adds nothing, even straight opposite the viewer (l = -v).
    f.unshadowed[1] = FrameLight{.direction = -v, .intensity = 10.0f, .color = vec3(1.0f), .pad = 0.0f};
    EXPECT_NEAR(meshSurfaceColor(f, n, v, 1.0f, albedo, 0.0f, albedo, 0.0f).x, withFill.x, 1e-6f);
}

TEST(StudioLights, TheRimLightsAStrandFromBehindThroughItsTransmission)
{
    // A vertical strand seen from the front, the rim straight behind it (phi = pi: Karis's TT
    // peak); the unshadowed rim is attenuated by the hair's occlusion, not by the key's shadow.
    FrameParams f = keyOnlyFrame();
    f.lightIntensity = 0.0f;
    f.shadingModel = kShadingKaris;
    f.hairAmbientOcclusion = 0.6f;
    f.hair.baseColor = vec4(0.6f, 0.4f, 0.25f, 0.0f);
    f.hair.sigmaA = vec4(0.3f, 0.6f, 1.2f, 1.55f);      // w: eta
    f.hair.roughness = vec4(0.3f, 0.3f, -0.035f, 0.0f); // beta_m, beta_n, alpha
    vec3 lut[kFrameLights] = {};
    vec3 dark = shadeStrandPoint(f, vec3(0), vec3(0, 1, 0), 0.5f, 7u, vec2(1.0f), lut);
    f.unshadowed[1] = FrameLight{.direction = vec3(0, 0, -1), .intensity = 5.0f, .color = vec3(1.0f), .pad = 0.0f};
    vec3 rim = shadeStrandPoint(f, vec3(0), vec3(0, 1, 0), 0.5f, 7u, vec2(1.0f), lut);
    EXPECT_GT(rim.x, dark.x + 0.05f);
    vec3 headShadowed = shadeStrandPoint(f, vec3(0), vec3(0, 1, 0), 0.5f, 7u, vec2(0.0f, 1.0f), lut);
    EXPECT_EQ(headShadowed, rim) << "the head's shadow is the key's alone";
    vec3 deep = shadeStrandPoint(f, vec3(0), vec3(0, 1, 0), 0.5f, 7u, vec2(1.0f, 0.0f), lut);
    EXPECT_LT(deep.x, rim.x) << "deep in the hair the rim is dimmer";
    EXPECT_GT(deep.x, dark.x) << "but not gone (the occlusion is softened as the ambient's)";
}

TEST(StudioLights, MultipleScatteringOffLeavesKarisSingleScatteringAndKajiyaAsItIs)
{
    // One strand point lit by the key: with multipleScattering 0 the karis model's response is its
    // single scattering alone (hairKaris), lut's its tables' alone; kajiya's does not change.
    FrameParams f = keyOnlyFrame();
    f.ambientIntensity = 0.0f;
    f.exposure = 0.05f; // far below the tone map's shoulder
    f.hair.baseColor = vec4(0.6f, 0.4f, 0.25f, 0.0f);
    f.hair.sigmaA = vec4(0.3f, 0.6f, 1.2f, 1.55f);
    f.hair.roughness = vec4(0.3f, 0.3f, -0.035f, 0.0f);
    f.hair.kajiya = vec4(0.05f, -0.1f, 80.0f, 20.0f);
    f.hair.kajiyaWeights = vec4(0.5f, 0.05f, 0.1f, 0.0f);
    vec3 t(0, 1, 0), wi = normalize(vec3(0.3f, 0.2f, 1.0f)), wo(0, 0, 1);
    f.lightDirection = wi;
    HairMaterial m = f.hair;
    vec3 base = vec3(m.baseColor);
    vec3 lut(0.02f, 0.015f, 0.01f);
    for (uint model : {kShadingKaris, kShadingLut, kShadingKajiya}) {
        f.shadingModel = model;
        f.multipleScattering = 1u;
        vec3 on = strandLightResponse(f, m, base, t, wi, wo, 0.7f, lut);
        f.multipleScattering = 0u;
        vec3 off = strandLightResponse(f, m, base, t, wi, wo, 0.7f, lut);
        if (model == kShadingKajiya) {
            EXPECT_EQ(on, off);
            continue;
        }
        vec3 multiple = 0.7f * hairKarisMultiple(t, wi, wo, m, 0.3f);
        vec3 single = model == kShadingKaris ? 0.7f * hairKaris(t, wi, wo, m) : 0.7f * lut;
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(off[c], single[c], 1e-6f) << "model " << model;
            EXPECT_NEAR(on[c], single[c] + multiple[c], 1e-6f) << "model " << model;
        }
        EXPECT_GT(multiple.x, 0.01f);
    }
    f.shadingModel = kShadingKaris;
    f.multipleScattering = 1u;
    EXPECT_EQ(strandLightResponse(f, m, base, t, wi, wo, 0.7f, lut), hairKarisLit(t, wi, wo, m, 0.3f));
}

TEST(StudioLights, TheBackdropRunsFromTopToBottom)
{
    FrameParams f = keyOnlyFrame();
    f.backgroundTop = vec3(0.2f, 0.3f, 0.4f);
    f.backgroundBottom = vec3(0.0f, 0.1f, 0.0f);
    EXPECT_EQ(frameBackground(f, 0.0f), f.backgroundTop);
    EXPECT_EQ(frameBackground(f, 100.0f), f.backgroundBottom);
    vec3 middle = frameBackground(f, 50.0f);
    EXPECT_NEAR(middle.y, 0.2f, 1e-6f); // smoothstep's midpoint
    for (float y = 1.0f; y <= 100.0f; y += 1.0f)
        EXPECT_LE(frameBackground(f, y).z, frameBackground(f, y - 1.0f).z);
}

TEST(StudioLights, TheHairVolumeHidesTheRimFromTheHairOverTheFace)
{
    // A rim from behind and above (+y up, the face toward +z) on a sphere of hair at the origin.
    vec4 volume(0, 0, 0, 1);
    vec3 rim = normalize(vec3(0, 0.6f, -1));
    float face = hairVolumeExposure(volume, vec3(0, 0, 1), rim);
    float side = hairVolumeExposure(volume, vec3(1, 0, 0), rim);
    float crown = hairVolumeExposure(volume, vec3(0, 1, 0), rim);
    float back = hairVolumeExposure(volume, vec3(0, 0, -1), rim);
    EXPECT_EQ(face, 0.0f);
    EXPECT_NEAR(side, 1.0f / 3.0f, 1e-6f); // the terminator, wrapped
    EXPECT_GT(crown, side);
    EXPECT_GT(back, crown);
    EXPECT_EQ(hairVolumeExposure(vec4(0.0f), vec3(0, 0, 1), rim), 1.0f) << "no volume, no attenuation";
}
