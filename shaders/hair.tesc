#version 460
// hair.tesc: sets each patch's isolines: as many lines (strands) as this instance's chunk of the
// strands per guide holds after level of detail (push.strandsPerPatch, at most 64), and this length
// chunk's share of the divisions (at most 64). Patches with no strand left are culled (level 0).
#extension GL_GOOGLE_include_directive : require
#include "shared/strands.h"

layout(vertices = 1) out;
layout(push_constant) uniform PushBlock { HairPush push; };

layout(location = 0) flat in uint inPatch[];
layout(location = 1) flat in uint inChunk[];
layout(location = 0) patch out uint patchGuide;
layout(location = 1) patch out uint patchStrandBase;
layout(location = 2) patch out uint patchLines;
layout(location = 3) patch out uint patchDivisionBase;
layout(location = 4) patch out uint patchDivisions;

void main()
{
    uint guide = inPatch[0] / push.lengthChunks;
    uint chunk = inPatch[0] % push.lengthChunks;
    uint strandBase = inChunk[0] * push.strandsPerPatch;
    uint wanted = min(push.strandsPerGuide, uint(ceil(push.lodStrands)));
    uint lines = wanted > strandBase ? min(push.strandsPerPatch, wanted - strandBase) : 0u;
    uint base = push.divisions / push.lengthChunks;
    uint extra = push.divisions % push.lengthChunks;
    uint divisions = base + (chunk < extra ? 1u : 0u);

    patchGuide = guide;
    patchStrandBase = strandBase;
    patchLines = lines;
    patchDivisionBase = chunk * base + min(chunk, extra);
    patchDivisions = divisions;
    gl_TessLevelOuter[0] = float(lines);
    gl_TessLevelOuter[1] = float(divisions);
}
