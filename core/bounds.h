// core/bounds.h: an axis-aligned box (meshes' and grooms' extents, the camera's framing, the
// light's fit). Plain math over GLM, no graphics.
#pragma once

#include <glm/glm.hpp>

namespace wisp {

struct Bounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 size() const { return max - min; }
    float diagonal() const { return glm::length(max - min); }
};

} // namespace wisp
