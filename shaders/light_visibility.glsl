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

// Percentage-closer filtering: the share of the Vogel-disk taps (`radius` texels) around `coords`
// whose stored depth is not nearer than the point (each tap itself bilinear through the compare
// sampler).
float pcf(sampler2DShadow map, vec3 coords, float bias, float angle, float radius)
{
    uint n = min(frame.pcfSamples, kMaxPcfSamples);
    float texel = 1.0 / frame.shadowMapSize;
    float lit = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec2 uv = coords.xy + vogelDiskTap(i, n, angle) * radius * texel;
        lit += texture(map, vec3(uv, coords.z - bias));
    }
    return lit / float(n);
}

// Transmittance through the hair in front of the point, one lookup of the deep opacity map.
float hairTransmittanceAt(vec3 coords)
{
    float z0 = texture(hairDepth, coords.xy).r;
    vec4 layers = texture(opacityLayers, coords.xy);
    return domTransmittance(domOpacity(layers, coords.z, z0, frame.domSpacing, frame.domLayers), frame.domKappa);
}

// Transmittance through the hair in front of the point (deep opacity map), averaged over the same
// Vogel disk as PCF. The map's texels are finer than a strand's shadow and than the receiver's
// pixel at a portrait's distance (2048 texels over the scene: about 0.4 mm, against 1.4 mm a pixel
// at 480 x 360 and 0.5 mm at 1920 x 1080): one point-sampled lookup would draw the shadow of a
// sparse curtain of strands on the face or the neck as dots, the texels each pixel happened to hit.
float hairTransmittance(vec3 coords, float radius, float angle)
{
    uint n = min(frame.pcfSamples, kMaxPcfSamples);
    float texel = 1.0 / frame.shadowMapSize;
    float sum = 0.0;
    for (uint i = 0u; i < n; ++i)
        sum += hairTransmittanceAt(vec3(coords.xy + vogelDiskTap(i, n, angle) * radius * texel, coords.z));
    return sum / float(n);
}

// The radius (texels of the light's maps) the lookups for a receiver at `world` average over: the
// PCF radius, or the receiver's camera pixel's footprint in the maps if that is larger (a disk of
// 0.7 pixels covers the pixel's square), so a pixel's shadow is its area's, not one texel's.
float shadowFilterRadius(vec3 world)
{
    float w = (frame.viewProjection * vec4(world, 1.0)).w;
    float pixelsPerUnit = abs(frame.projection[1][1]) * 0.5 * frame.viewportHeight; // at w = 1
    float pixelTexels = w / max(pixelsPerUnit, 1e-12) * frame.lightTexelsPerUnit;
    return max(frame.pcfRadius, 0.7 * pixelTexels);
}

// The light's visibility at a point, in two parts: x the head's shadow (PCF), y the hair's
// transmittance, from the deep opacity map when it is on, else PCF over the hair's depth map.
// `hairBias` is larger for hair receiving its own shadow, where the map holds the receiver itself.
// `overPixel`: a surface's pixel (the meshes) averages both over its footprint in the maps
// (shadowFilterRadius); a strand vertex (the hair) takes the PCF radius and one lookup of the deep
// opacity map, as the hair's own shadow needs no more and each of its many vertices pays for it
// (averaged there too, the H100's strands.generate took 0.64 ms where it takes 0.21, Sintel x 8).
vec2 lightVisibilityParts(vec3 world, vec2 pixel, float hairBias, bool overPixel)
{
    if (frame.shadowsEnabled == 0u || frame.pcfSamples == 0u)
        return vec2(1.0);
    vec3 coords = lightCoords(world);
    if (any(lessThan(coords, vec3(0.0))) || any(greaterThan(coords, vec3(1.0))))
        return vec2(1.0);  // outside the light's view: nothing there casts
    float angle = 6.2831853 * interleavedGradientNoise(pixel);
    float radius = overPixel ? shadowFilterRadius(world) : frame.pcfRadius;
    float head = pcf(shadowHead, coords, frame.shadowBias, angle, radius);
    float hair;
    if (frame.domLayers == 0u)
        hair = pcf(shadowHair, coords, hairBias, angle, radius);
    else
        hair = overPixel ? hairTransmittance(coords, radius, angle) : hairTransmittanceAt(coords);
    return vec2(head, hair);
}
