// shaders/shared/mesh_sdf_sample.h: the mesh's signed distance field (mesh_sdf.h) read at any
// point: trilinear between its nodes, its gradient by central differences. In GLSL the including
// shader defines `float sdfFieldAt(uint node)` before including this; in C++ the functions take the
// values as their first parameter.
#ifndef WISP_SHARED_MESH_SDF_SAMPLE_H
#define WISP_SHARED_MESH_SDF_SAMPLE_H
#include "mesh_sdf.h"

GPU_NAMESPACE_BEGIN

#ifdef __cplusplus
#define SDF_FIELD_PARAM const float *field,
#define SDF_FIELD_ARG field,
#define SDF_FIELD_AT(i) field[i]
#else
#define SDF_FIELD_PARAM
#define SDF_FIELD_ARG
#define SDF_FIELD_AT(i) sdfFieldAt(i)
#endif

// The field at p, trilinear between the nodes; +band outside the grid.
GPU_FN float sdfSample(SDF_FIELD_PARAM SdfGrid g, vec3 p)
{
    uvec3 b = uvec3(0u);
    vec3 f = vec3(0.0f);
    if (!sdfCell(g, p, b, f))
        return g.band.x;
    uint i = sdfNodeIndex(g, b);
    uint sy = g.dims.x, sz = g.dims.x * g.dims.y;
    float c00 = mix(SDF_FIELD_AT(i), SDF_FIELD_AT(i + 1u), f.x);
    float c10 = mix(SDF_FIELD_AT(i + sy), SDF_FIELD_AT(i + sy + 1u), f.x);
    float c01 = mix(SDF_FIELD_AT(i + sz), SDF_FIELD_AT(i + sz + 1u), f.x);
    float c11 = mix(SDF_FIELD_AT(i + sz + sy), SDF_FIELD_AT(i + sz + sy + 1u), f.x);
    return mix(mix(c00, c10, f.y), mix(c01, c11, f.y), f.z);
}

// The field's gradient at p by central differences of sdfSample, half a cell either side (not
// normalized; zero where the samples agree, as outside the band).
GPU_FN vec3 sdfGradient(SDF_FIELD_PARAM SdfGrid g, vec3 p)
{
    float e = 0.5f * g.origin.w;
    return vec3(sdfSample(SDF_FIELD_ARG g, p + vec3(e, 0.0f, 0.0f)) -
                    sdfSample(SDF_FIELD_ARG g, p - vec3(e, 0.0f, 0.0f)),
                sdfSample(SDF_FIELD_ARG g, p + vec3(0.0f, e, 0.0f)) -
                    sdfSample(SDF_FIELD_ARG g, p - vec3(0.0f, e, 0.0f)),
                sdfSample(SDF_FIELD_ARG g, p + vec3(0.0f, 0.0f, e)) -
                    sdfSample(SDF_FIELD_ARG g, p - vec3(0.0f, 0.0f, e))) /
           (2.0f * e);
}

GPU_NAMESPACE_END

#endif
