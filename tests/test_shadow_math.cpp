// tests/test_shadow_math.cpp: the light's maps' shared math (shaders/shared/shadows.h) on the CPU:
// the Vogel-disk PCF taps fill the unit disk evenly, and the deep opacity layers grow with depth and
// sum to the whole.
#include "shaders/shared/shadows.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

TEST(ShadowMath, VogelTapsFillTheUnitDiskEvenly)
{
    for (uint32_t n : {1u, 4u, 16u, 64u}) {
        glm::vec2 mean(0.0f);
        uint32_t inner = 0;
        for (uint32_t i = 0; i < n; ++i) {
            glm::vec2 t = gpu::vogelDiskTap(i, n, 0.7f);
            EXPECT_LE(glm::length(t), 1.0f + 1e-6f);
            mean += t / float(n);
            inner += glm::length(t) < std::sqrt(0.5f) ? 1u : 0u;
        }
        if (n >= 16) {
            EXPECT_LT(glm::length(mean), 0.1f);                // centred
            EXPECT_NEAR(float(inner) / float(n), 0.5f, 0.07f); // equal area: half the taps inside r^2 = 1/2
        }
    }
}

TEST(ShadowMath, DeepOpacityGrowsWithDepthAndSumsTheLayers)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 3.0f);
    for (int trial = 0; trial < 200; ++trial) {
        glm::vec4 layers(u(rng), u(rng), u(rng), u(rng));
        uint32_t count = 1u + uint32_t(trial) % 4u;
        float z0 = 0.3f, spacing = 0.01f;
        float previous = 0.0f;
        for (float z = 0.25f; z < 0.4f; z += 0.0005f) {
            float o = gpu::domOpacity(layers, z, z0, spacing, count);
            EXPECT_GE(o, previous - 1e-6f) << "opacity must never fall with depth";
            previous = o;
            EXPECT_GE(gpu::domTransmittance(o, 0.9f), 0.0f);
        }
        EXPECT_EQ(gpu::domOpacity(layers, z0, z0, spacing, count), 0.0f); // nothing in front of the first hair
        float all = 0.0f;
        for (uint32_t k = 0; k < count; ++k)
            all += layers[int(k)];
        EXPECT_NEAR(gpu::domOpacity(layers, z0 + float(count) * spacing, z0, spacing, count), all, 1e-4f);
    }
    // A fragment adds to the layer its depth falls in; past the last, to the last.
    EXPECT_EQ(gpu::domLayerMask(0.305f, 0.3f, 0.01f, 4), glm::vec4(1, 0, 0, 0));
    EXPECT_EQ(gpu::domLayerMask(0.325f, 0.3f, 0.01f, 4), glm::vec4(0, 0, 1, 0));
    EXPECT_EQ(gpu::domLayerMask(0.9f, 0.3f, 0.01f, 3), glm::vec4(0, 0, 1, 0));
}
