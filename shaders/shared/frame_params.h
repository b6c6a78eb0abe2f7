// shaders/shared/frame_params.h: the per-frame uniform block (camera, lights, background) read by
// every graphics pass, and the binding it lives at; the lights as one list (frameLight) and the
// backdrop's gradient (frameBackground). One definition for GLSL and C++.
#ifndef WISP_SHARED_FRAME_PARAMS_H
#define WISP_SHARED_FRAME_PARAMS_H
#include "hair_shading.h"
#include "prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kFrameParamsBinding = 0;

// FrameParams.shadingModel: which model of hair_shading.h the hair fragments use.
GPU_CONST uint kShadingKaris = 0u;
GPU_CONST uint kShadingKajiya = 1u;
GPU_CONST uint kShadingLut = 2u;

// The studio's lights: 0 the key (shadowed: the light's maps are made along it), 1 the fill and
// 2 the rim (unshadowed). Every shading function loops over them through frameLight.
GPU_CONST uint kFrameLights = 3u;
GPU_CONST uint kFrameKeyLight = 0u;

// One directional light as the shading sees it.
struct FrameLight {
    vec3 direction;  // unit vector from the shading point toward the light
    float intensity; // radiance scale, 0: off
    vec3 color;      // linear RGB
    float pad;
};

struct FrameParams {
    mat4 view;              // world -> camera
    mat4 projection;        // camera -> clip (Vulkan: y down, depth 0..1)
    mat4 viewProjection;    // projection * view
    vec3 cameraPosition;    // world space, asset units
    float time;             // simulated seconds since the start (never wall-clock)
    vec3 lightDirection;    // unit vector from the shading point toward the light
    float lightIntensity;   // radiance scale of the key light, 0..10, typically 3
    vec3 lightColor;        // linear RGB
    float ambientIntensity; // scale of the hemisphere ambient, 0..1
    vec3 skyColor;          // hemisphere ambient from above (linear RGB)
    float exposure;         // linear multiplier before tone mapping
    vec3 groundColor;       // hemisphere ambient from below (linear RGB)
    float viewportWidth;    // pixels
    vec3 backgroundTop;     // the backdrop's colour at the top row (linear RGB; frameBackground)
    float viewportHeight;   // pixels
    mat4 headTransform;     // head space -> world this frame (rigid); the colliders move with it
    // The light's view (shared/shadows.h): orthographic along lightDirection, depth 0..1 linear.
    mat4 lightViewProjection; // world -> light clip
    float shadowMapSize;      // texels per side of the light's maps
    float lightTexelsPerUnit; // shadow-map texels per world unit
    float lightDepthRange;    // world units the light's depth 0..1 spans
    uint pcfSamples;          // PCF taps; 0 = no shadows at all
    float pcfRadius;          // PCF disk radius, texels
    float shadowBias;         // depth bias of the shadow test, light depth units
    uint domLayers;           // deep opacity layers, 0 = off (hair self-shadows with PCF instead)
    float domSpacing;         // depth of one layer, light depth units
    float domKappa;           // transmittance = exp(-domKappa * opacity)
    float hairOpacity;        // opacity of one strand of full coverage (OIT blending, deep opacity)
    uint shadingModel;        // kShading*
    uint shadowsEnabled;      // 0 or 1
    // The hair's look (hair.frag): its material, and how strands vary around it.
    float hairVariation;        // per-strand spread of absorption, 0..1
    float hairStreaks;          // strength of streaks along strands (Meshuggah's noise), 0..1
    float hairAmbientOcclusion; // how much the deep opacity map darkens the ambient, 0..1
    uint multipleScattering;    // 1: karis and lut add Karis's multiple scattering (hairKarisMultiple), 0: not
    HairMaterial hair;
    FrameLight unshadowed[kFrameLights - 1u]; // the fill and the rim (frameLight 1 and 2)
    vec3 backgroundBottom;                    // the backdrop's colour at the bottom row (linear RGB)
    float strandLengthJitter; // drawn strands' cut from the tip, at most (strands.h strandLengthFraction)
    vec4 hairVolume; // the hair's rest bounds as a sphere, posed this frame: xyz centre (world), w radius (0: no hair)
    vec4 hairAlong;  // x: how much the absorption varies along a strand (strandAbsorptionScale), 0..1; yzw unused
};

// Light i of the frame (kFrameLights of them; 0 the key).
GPU_FN FrameLight frameLight(FrameParams frame, uint i)
{
    if (i == kFrameKeyLight) {
        FrameLight key;
        key.direction = frame.lightDirection;
        key.intensity = frame.lightIntensity;
        key.color = frame.lightColor;
        key.pad = 0.0f;
        return key;
    }
    return frame.unshadowed[i - 1u];
}

// The backdrop behind everything at pixel row y (0 at the top, viewportHeight at the bottom; the
// pixel's centre): a soft vertical gradient from backgroundTop to backgroundBottom, smoothstep-eased
// so neither end shows an edge, as a studio's paper backdrop lit from above.
GPU_FN vec3 frameBackground(FrameParams frame, float y)
{
    float t = clamp(y / max(frame.viewportHeight, 1.0f), 0.0f, 1.0f);
    return mix(frame.backgroundTop, frame.backgroundBottom, t * t * (3.0f - 2.0f * t));
}

GPU_NAMESPACE_END

#ifdef __cplusplus
// The layouts GLSL gives these blocks, checked where they are defined (C++ only).
static_assert(sizeof(gpu::FrameLight) == 32);
static_assert(sizeof(gpu::FrameParams) == 3 * 64 + 6 * 16 + 64 + 64 + 48 + 16 + 80 + 2 * 32 + 16 + 16 + 16,
              "FrameParams must match its std140 layout");
static_assert(offsetof(gpu::FrameParams, unshadowed) == 560);
static_assert(offsetof(gpu::FrameParams, hair) == 480);
static_assert(offsetof(gpu::FrameParams, lightViewProjection) == 352);
static_assert(offsetof(gpu::FrameParams, shadowsEnabled) == 460);
static_assert(offsetof(gpu::FrameParams, headTransform) == 288);
static_assert(offsetof(gpu::FrameParams, cameraPosition) == 192);
static_assert(offsetof(gpu::FrameParams, lightDirection) == 208);
static_assert(offsetof(gpu::FrameParams, viewportHeight) == 284);
#endif

#endif
