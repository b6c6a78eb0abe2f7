// sim_common.glsl: the buffer and parameter declarations every simulation kernel shares.
// Included by the .comp files after their #version line.
#include "shared/sim.h"

layout(set = 0, binding = kSimBindingParams) uniform ParamsBlock { SimParams params; };
layout(push_constant) uniform StepBlock { SimStep step; };
layout(set = 0, binding = kSimBindingPositions, std430) buffer Positions { vec4 positions[]; };
layout(set = 0, binding = kSimBindingVelocities, std430) buffer Velocities { vec4 velocities[]; };
layout(set = 0, binding = kSimBindingRest, std430) readonly buffer Rest { RestVertex rest[]; };
layout(set = 0, binding = kSimBindingStrands, std430) readonly buffer Strands { StrandInfo strands[]; };
layout(set = 0, binding = kSimBindingTangents, std430) writeonly buffer Tangents { vec4 tangents[]; };
layout(set = 0, binding = kSimBindingCounters, std430) buffer Counters { SimCounters counters; };
