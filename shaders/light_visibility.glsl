// light_visibility.glsl: how much of the key light reaches a point, for mesh.frag and hair.frag:
// PCF over the head's and the hair's depth maps from the light, and the deep opacity map's
// transmittance (the math is in shared/shadows.h). Needs FrameParams `frame` declared first.
#include "shared/shadows.h"

layout(set = 0, binding = kBindingShadowHead) uniform sampler2DShadow shadowHead;
layout(set = 0, binding = kBindingShadowHair) uniform sampler2DShadow shadowHair;
layout(set = 0, binding = kBindingHairDepth) uniform sampler2D hairDepth;
layout(set = 0, binding = kBindingOpacity) uniform sampler2D opacityLayers;

// World position -> (u, v, depth) in the light's maps.
vec3 lightCoords(vec3 world)
{
    vec4 c = frame.lightViewProjection * vec4(world, 1.0);
    return vec3(c.xy / c.w * 0.5 + 0.5, c.z / c.w);
}

// Percentage-closer filtering: the share of the Vogel-disk taps around `coords` whose stored
// depth is not nearer than the point (each tap itself bilinear through the compare sampler).
float pcf(sampler2DShadow map, vec3 coords, float bias, float angle)
{
    uint n = min(frame.pcfSamples, kMaxPcfSamples);
    float texel = 1.0 / frame.shadowMapSize;
    float lit = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec2 uv = coords.xy + vogelDiskTap(i, n, angle) * frame.pcfRadius * texel;
        lit += texture(map, vec3(uv, coords.z - bias));
    }
    return lit / float(n);
}

// Transmittance through the hair in front of the point (deep opacity map).
float hairTransmittance(vec3 coords)
{
    float z0 = texture(hairDepth, coords.xy).r;
    vec4 layers = texture(opacityLayers, coords.xy);
    float opacity = domOpacity(layers, coords.z, z0, frame.domSpacing, frame.domLayers);
    return domTransmittance(opacity, frame.domKappa);
}

// The light's visibility at a point, in two parts: x the head's shadow (PCF), y the hair's
// transmittance, from the deep opacity map when it is on, else PCF over the hair's depth map.
// `hairBias` is larger for hair receiving its own shadow, where the map holds the receiver itself.
vec2 lightVisibilityParts(vec3 world, vec2 pixel, float hairBias)
{
    if (frame.shadowsEnabled == 0u || frame.pcfSamples == 0u)
        return vec2(1.0);
    vec3 coords = lightCoords(world);
    if (any(lessThan(coords, vec3(0.0))) || any(greaterThan(coords, vec3(1.0))))
        return vec2(1.0);  // outside the light's view: nothing there casts
    float angle = 6.2831853 * interleavedGradientNoise(pixel);
    float head = pcf(shadowHead, coords, frame.shadowBias, angle);
    float hair = frame.domLayers > 0u ? hairTransmittance(coords) : pcf(shadowHair, coords, hairBias, angle);
    return vec2(head, hair);
}

float lightVisibility(vec3 world, vec2 pixel, float hairBias)
{
    vec2 v = lightVisibilityParts(world, pixel, hairBias);
    return v.x * v.y;
}
