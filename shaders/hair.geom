#version 460
// hair.geom: each strand segment becomes a camera-facing quad, offset perpendicular to the
// segment's projected tangent in screen space (so a horizontal strand keeps its width), its width
// tapering toward the tip. A ribbon narrower than push.minPixelWidth is drawn that wide with its
// alpha scaled by the true coverage (TressFX), so thin hair fades instead of breaking up.
// With HAIR_FROM_LIGHT (hair_light.geom) the same ribbons face the light for its maps.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/strands.h"

layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
layout(push_constant) uniform PushBlock { HairPush push; };
layout(set = 0, binding = kHairBindingFrame) uniform FrameBlock { FrameParams frame; };

layout(location = 0) in vec3 inWorld[];
layout(location = 1) in vec3 inTangent[];
layout(location = 2) in float inT[];
layout(location = 3) flat in uint inStrand[];
layout(location = 4) in float inLodAlpha[];
layout(location = 5) in vec2 inVisibility[];
layout(location = 6) in float inWidthScale[];

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outTangent;
layout(location = 2) out float outT;
layout(location = 3) flat out uint outStrand;
layout(location = 4) out float outAlpha;
layout(location = 5) out vec2 outVisibility;

void main()
{
#ifdef HAIR_FROM_LIGHT
    // Drawn from the light (orthographic): ribbons face it, at least a texel wide.
    vec2 halfViewport = vec2(0.5 * frame.shadowMapSize);
    float pixelsPerUnit = frame.lightTexelsPerUnit;
#else
    vec2 halfViewport = 0.5 * vec2(frame.viewportWidth, frame.viewportHeight);
    float pixelsPerUnit = abs(frame.projection[1][1]) * halfViewport.y;  // at w = 1 (y is flipped for Vulkan)
#endif
    vec4 c0 = gl_in[0].gl_Position;
    vec4 c1 = gl_in[1].gl_Position;
    if (c0.w <= 0.0 || c1.w <= 0.0)
        return;  // behind the camera
    vec2 s0 = c0.xy / c0.w * halfViewport;
    vec2 s1 = c1.xy / c1.w * halfViewport;
    vec2 along = s1 - s0;
    vec2 dir = dot(along, along) > 1e-12 ? normalize(along) : vec2(1.0, 0.0);
    vec2 perp = vec2(-dir.y, dir.x);

    for (int i = 0; i < 2; ++i) {
        vec4 c = i == 0 ? c0 : c1;
        float worldWidth = strandWidthAt(push.width * push.lodWidthScale * inWidthScale[i], inT[i]);
        float pixels = worldWidth * pixelsPerUnit / c.w;
        float drawn = max(pixels, push.minPixelWidth);
        float coverage = pixels / drawn;
        vec2 offset = perp * (0.5 * drawn) / halfViewport * c.w;
        for (int side = -1; side <= 1; side += 2) {
            gl_Position = c + vec4(float(side) * offset, 0.0, 0.0);
            outWorld = inWorld[i];
            outTangent = inTangent[i];
            outT = inT[i];
            outStrand = inStrand[i];
            outAlpha = coverage * inLodAlpha[i];
            outVisibility = inVisibility[i];
            EmitVertex();
        }
    }
    EndPrimitive();
}
