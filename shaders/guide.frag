#version 460
// guide.frag: flat colour for guide lines (already linear; the target encodes sRGB).
layout(location = 0) in vec3 inColor;
layout(location = 0) out vec4 outColor;

void main()
{
    outColor = vec4(inColor, 1.0);
}
