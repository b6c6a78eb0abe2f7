// core/rotation.h: the one Euler rotation of Wisp's files (head.json's colliders, TressFX 2 headers'
// "rotation", the head generator's parts): XYZ angles in degrees, right-handed, applied x first,
// R = Rz * Ry * Rx; an object's local axes are R's columns. In float or double.
#pragma once

#include <glm/glm.hpp>

#include <cmath>

namespace wisp {

template <typename T> glm::mat<3, 3, T> rotationXyzDegrees(const glm::vec<3, T>& degrees)
{
    glm::vec<3, T> r = glm::radians(degrees);
    T cx = std::cos(r.x), sx = std::sin(r.x);
    T cy = std::cos(r.y), sy = std::sin(r.y);
    T cz = std::cos(r.z), sz = std::sin(r.z);
    glm::mat<3, 3, T> rx(1, 0, 0, 0, cx, sx, 0, -sx, cx); // column-major
    glm::mat<3, 3, T> ry(cy, 0, -sy, 0, 1, 0, sy, 0, cy);
    glm::mat<3, 3, T> rz(cz, sz, 0, -sz, cz, 0, 0, 0, 1);
    return rz * ry * rx;
}

} // namespace wisp
