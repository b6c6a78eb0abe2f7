// tests/test_lighting.cpp: the shared surface-shading header compiled as C++: the same functions
// mesh.frag runs, checked against hand-computed values and their physical properties.
#include "shaders/shared/lighting.h"

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
