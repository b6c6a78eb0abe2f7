// shaders/shared/prelude.h: lets one header be compiled as GLSL and as C++. In C++ the GLSL
// vector and matrix types map to GLM inside namespace gpu, and GPU_FN marks shared functions
// inline. Every header in shaders/shared/ includes this first.
#ifndef WISP_SHARED_PRELUDE_H
#define WISP_SHARED_PRELUDE_H

#ifdef __cplusplus
#include <cstddef> // offsetof, in the headers' layout checks
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>
#define GPU_NAMESPACE_BEGIN namespace gpu {
#define GPU_NAMESPACE_END }
#define GPU_FN inline
#define GPU_CONST constexpr
GPU_NAMESPACE_BEGIN
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using uvec3 = glm::uvec3;
using ivec3 = glm::ivec3;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using ivec2 = glm::ivec2;
using mat3 = glm::mat3;
using mat4 = glm::mat4;
using uint = std::uint32_t;
using glm::abs;
using glm::acos;
using glm::asin;
using glm::bitCount;
using glm::ceil;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::exp2;
using glm::floor;
using glm::fract;
using glm::length;
using glm::log;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::packHalf2x16;
using glm::packUnorm4x8;
using glm::pow;
using glm::sin;
using glm::sqrt;
using glm::transpose;
using glm::unpackHalf2x16;
using glm::unpackUnorm4x8;
GPU_NAMESPACE_END
#define GPU_UNROLL
#else
#extension GL_EXT_control_flow_attributes : require
#define GPU_NAMESPACE_BEGIN
#define GPU_NAMESPACE_END
#define GPU_FN
#define GPU_CONST const
// Before a loop of a constant count over a small array: unrolled, its indices become constants
// and the array stays in registers (a loop the compiler keeps would index it, and put it in
// local memory).
#define GPU_UNROLL [[unroll]]
#endif

#endif
