// shaders/shared/shadows.h: light visibility for meshes and hair, the pure math of it, shared by
// GLSL and the C++ tests.
// - Shadow maps: the light renders the head and the hair, each into its own depth map (one
//   orthographic view, depth linear in distance). A point's visibility is percentage-closer
//   filtered (Reeves et al. 1987) over `pcfSamples` taps on a Vogel disk (golden-angle spiral,
//   rotated per pixel so the banding of few taps turns into fine noise).
// - Deep opacity maps (Yuksel & Keyser 2008): the hair depth map is each texel's first hair depth
//   z0; a second pass adds every hair fragment's opacity into one of up to four layers (the
//   channels of one RGBA image) that start at z0 and are `spacing` deep (the last one open-ended).
//   A point at depth z reads the opacity in front of it, interpolating within its layer, and its
//   transmittance is exp(-kappa * opacity).
// - Order-independent transparency (per-pixel linked lists, as TressFX does): the node layout.
#ifndef WISP_SHARED_SHADOWS_H
#define WISP_SHARED_SHADOWS_H
#include "prelude.h"

GPU_NAMESPACE_BEGIN

// Bindings of the light's maps, the same in every pipeline that reads them (mesh and hair).
GPU_CONST uint kBindingShadowHead = 4; // sampler2DShadow: the head's depth from the light
GPU_CONST uint kBindingShadowHair = 5; // sampler2DShadow: the hair's first depth from the light
GPU_CONST uint kBindingHairDepth = 6;  // sampler2D: the same hair depth, read as a value (z0)
GPU_CONST uint kBindingOpacity = 7;    // sampler2D: deep opacity layers (RGBA)

GPU_CONST uint kMaxDomLayers = 4u;
GPU_CONST uint kMaxPcfSamples = 64u;
GPU_CONST uint kMaxOitK = 16u;        // nearest fragments the OIT resolve sorts (oit_k <= this)
GPU_CONST uint kOitNil = 0xffffffffu; // end of a per-pixel list

// Bindings of the OIT resolve (oit_resolve.comp).
GPU_CONST uint kOitResolveBindingHeads = 0;    // the lists' heads, one per pixel
GPU_CONST uint kOitResolveBindingNodes = 1;    // the pool of nodes
GPU_CONST uint kOitResolveBindingCounters = 2; // OitCounters
GPU_CONST uint kOitResolveBindingColor = 3;    // image2D rgba16f: the resolved hair, premultiplied

// Tap i of n on a Vogel disk of unit radius, rotated by `angle` (radians): radii sqrt((i+0.5)/n)
// cover the disk with equal area per tap, angles step by the golden angle.
GPU_FN vec2 vogelDiskTap(uint i, uint n, float angle)
{
    float r = sqrt((float(i) + 0.5f) / float(n));
    float theta = float(i) * 2.39996323f + angle;
    return r * vec2(cos(theta), sin(theta));
}

// Interleaved gradient noise (Jimenez 2014): a per-pixel value in [0, 1) without a texture.
GPU_FN float interleavedGradientNoise(vec2 pixel)
{
    return fract(52.9829189f * fract(0.06711056f * pixel.x + 0.00583715f * pixel.y));
}

// The layer a hair fragment at `depth` (>= first depth z0, in the light's depth units) adds its
// opacity to: a one in that channel.
GPU_FN vec4 domLayerMask(float depth, float z0, float spacing, uint layers)
{
    float d = max(depth - z0, 0.0f) / max(spacing, 1e-12f);
    uint k = min(uint(d), layers - 1u);
    vec4 mask = vec4(0.0f);
    mask[int(k)] = 1.0f;
    return mask;
}

// The opacity in front of a point at `depth`: the full layers nearer than its own, plus its own
// layer's opacity in proportion to how far into it the point lies. Non-decreasing in depth.
GPU_FN float domOpacity(vec4 layerOpacity, float depth, float z0, float spacing, uint layers)
{
    float d = (depth - z0) / max(spacing, 1e-12f);
    if (d <= 0.0f)
        return 0.0f;
    float sum = 0.0f;
    for (uint k = 0u; k < layers; ++k) {
        float inLayer = k + 1u == layers ? min(d - float(k), 1.0f) : clamp(d - float(k), 0.0f, 1.0f);
        sum += layerOpacity[int(k)] * max(inLayer, 0.0f);
    }
    return sum;
}

GPU_FN float domTransmittance(float opacity, float kappa)
{
    return exp(-kappa * opacity);
}

// One fragment of the per-pixel lists, 12 bytes: its tone-mapped colour and alpha as RGBA8 with
// the colour square-rooted (a gamma of 2 keeps dark hair from banding in 8 bits), its window
// depth, and the index of the next node (kOitNil ends the list).
struct OitNode {
    uint color;  // packUnorm4x8(vec4(sqrt(rgb), alpha))
    float depth; // 0 near .. 1 far
    uint next;
};

// The pool's counters: nodes handed out (may pass the capacity: those fragments are dropped and
// counted as overflow).
struct OitCounters {
    uint allocated;
    uint overflow;
    uint capacity;
    uint pad;
};

GPU_NAMESPACE_END

#ifdef __cplusplus
// The layouts GLSL gives these blocks, checked where they are defined (C++ only).
static_assert(sizeof(gpu::OitNode) == 12 && sizeof(gpu::OitCounters) == 16);
#endif

#endif
