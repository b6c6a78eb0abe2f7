// tests/small_scene.h: the small hair scene the rendering suites share: grown guides on the
// default head, a 200 x 150 picture with a 512² shadow map and light strands, rendered offscreen.
#pragma once

#include "app/headless.h"
#include "physics/hair_scene.h"
#include "assets/head.h"
#include "renderer/settings.h"

namespace wisp::test {

inline HairScene smallHairScene(uint32_t guides)
{
    GrowthSettings g;
    g.guides = guides;
    return buildGrownScene(defaultHeadPath(), g);
}

inline RenderSettings smallRenderSettings()
{
    RenderSettings s;
    s.width = 200;
    s.height = 150;
    s.shadows.mapSize = 512;
    s.strands.strandsPerGuide = 8;
    s.strands.divisions = 12;
    return s;
}

// The scene's head and hair as the default camera frames them (the hair unsimulated).
inline Picture renderHair(const vk::Context& ctx, const HairScene& scene, const RenderSettings& s)
{
    HairSession session(ctx, scene, SimSettings{}, stillTimeline(glm::vec4(0.0f), glm::vec3(0.0f), s.light));
    return renderPicture(ctx, session, s);
}

}  // namespace wisp::test
