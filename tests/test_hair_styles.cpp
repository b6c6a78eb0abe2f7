// tests/test_hair_styles.cpp: every named style (physics/hair_style.h) on the GPU (lavapipe in CI),
// small: two seconds at rest keep the invariants and the style's shape, a turning head with the
// sphere pushed through the hair keeps it on the head, and each style renders with validation on.
#include "app/session/simulate.h"
#include "physics/groomed_head.h"
#include "physics/hair_style.h"
#include "small_groomed_head.h"
#include "test_support.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

using namespace wisp;

namespace {

GroomedHead styledScene(const HairStyle& style, uint32_t guides)
{
    GrowthSettings g;
    applyHairStyle(g, style);
    g.guides = guides;
    return buildGrownHead(defaultHeadPath(), g);
}

// Mean distance of the free vertices from the rest pose, and the strands' mean length.
std::pair<float, float> shapeKept(const GroomedHead& scene, const SimState& state)
{
    const StrandSet& s = scene.strands;
    uint32_t V = s.verticesPerStrand;
    double moved = 0.0, length = 0.0;
    size_t n = 0;
    for (size_t k = 0; k < s.strandCount(); ++k)
        for (uint32_t i = 1; i < V; ++i) {
            moved += glm::length(glm::vec3(state.positions[k * V + i]) - s.rest[k * V + i]);
            length += glm::length(s.rest[k * V + i] - s.rest[k * V + i - 1]);
            ++n;
        }
    return {float(moved / double(n)), float(length / double(s.strandCount()))};
}

} // namespace

TEST(HairStyles, EveryStyleRestsTwoSecondsWithItsInvariantsAndItsShape)
{
    vk::Context ctx(test::validatedOptions());
    for (const HairStyle& style : hairStyles()) {
        GroomedHead scene = styledScene(style, 100);
        float diagonal = scene.head.mesh.bounds().diagonal();
        SimulationReport r = simulateHeadless(ctx, scene, SimSettings{}, 240, {}, 40); // 2 s at 120 Hz
        auto [moved, length] = shapeKept(scene, r.state);
        std::fprintf(stderr, "%s: stretch %g, worst penetration %g of the diagonal, resets %u, moved %g of %g\n",
                     style.name, double(r.last.maxStretch), double(r.worst.maxPenetration / diagonal),
                     r.nonfiniteResets, double(moved), double(length));
        EXPECT_LT(r.last.maxStretch, 1e-3f) << style.name;
        EXPECT_EQ(r.nonfiniteResets, 0u) << style.name;
        EXPECT_LT(r.worst.maxPenetration / diagonal, 0.01f) << style.name;
        // The shape constraints keep the style without freezing it: the groom settles under gravity
        // within 15% of its strands' length of the pose it was grown in (curls stay curls, a bob a bob).
        EXPECT_LT(moved, 0.15f * length) << style.name;
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(HairStyles, EveryStyleStaysOnATurningHeadWithTheSpherePushedThrough)
{
    vk::Context ctx(test::validatedOptions());
    // The head turns 60 degrees and back within 1.5 s while a 5 cm sphere sweeps across the back of it.
    Motion motion;
    motion.head = [](float t) {
        float u = glm::clamp(t / 0.6f, 0.0f, 1.0f), v = glm::clamp((t - 0.9f) / 0.6f, 0.0f, 1.0f);
        float angle = glm::radians(60.0f) * (u * u * (3.0f - 2.0f * u) - v * v * (3.0f - 2.0f * v));
        return glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 1, 0));
    };
    motion.sphere = [](float t) { return glm::vec4(-0.2f + 0.27f * t, 0.12f, -0.15f, 0.05f); };
    for (const HairStyle& style : hairStyles()) {
        GroomedHead scene = styledScene(style, 80);
        float diagonal = scene.head.mesh.bounds().diagonal();
        SimulationReport r = simulateHeadless(ctx, scene, SimSettings{}, 180, motion, 30);
        std::fprintf(stderr, "%s: worst penetration %g of the diagonal, drift %g, resets %u\n", style.name,
                     double(r.worst.maxPenetration / diagonal), double(r.worst.rootDrift), r.nonfiniteResets);
        EXPECT_EQ(r.nonfiniteResets, 0u) << style.name;
        EXPECT_LT(r.worst.maxPenetration / diagonal, 0.01f) << style.name;
        EXPECT_LT(r.worst.rootDrift, 1e-5f) << style.name;
        EXPECT_LT(r.last.maxStretch, 1e-3f) << style.name;
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(HairStyles, EveryStyleRendersWithValidationOn)
{
    vk::Context ctx(test::validatedOptions());
    RenderSettings s = test::smallRenderSettings();
    for (const HairStyle& style : hairStyles()) {
        GroomedHead scene = styledScene(style, 120);
        Picture picture = test::renderHair(ctx, scene, s);
        ASSERT_EQ(picture.width, s.width);
        // Hair darkens and colours the picture: count the pixels that differ from the frame drawn
        // with no hair strands at all (same head, same camera).
        RenderSettings noStrands = s;
        noStrands.transparency.hairOpacity = 0.01f;
        Picture faint = test::renderHair(ctx, scene, noStrands);
        size_t changed = 0;
        for (size_t i = 0; i < picture.rgba.size(); i += 4)
            changed += std::abs(int(picture.rgba[i]) - int(faint.rgba[i])) > 8 ? 1 : 0;
        std::fprintf(stderr, "%s: %zu pixels show hair\n", style.name, changed);
        EXPECT_GT(changed, size_t(s.width) * s.height / 150) << style.name;
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}
