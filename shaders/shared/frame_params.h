// shaders/shared/frame_params.h: the per-frame uniform block (camera, light, background) read by
// every graphics pass, and the binding it lives at. One definition for GLSL and C++.
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
    vec3 backgroundColor;   // linear RGB clear colour
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
    float pad0;
    HairMaterial hair;
};

GPU_NAMESPACE_END

#endif
