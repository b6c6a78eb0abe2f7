#version 460
// oit_composite.frag: lays the resolved hair (premultiplied colour and alpha from
// oit_resolve.comp) over the target; the pipeline blends src + dst * (1 - alpha).
layout(set = 0, binding = 0) uniform sampler2D hairColor;
layout(location = 0) out vec4 outColor;

void main()
{
    vec4 c = texelFetch(hairColor, ivec2(gl_FragCoord.xy), 0);
    if (c.a <= 0.0)
        discard;
    outColor = c;
}
