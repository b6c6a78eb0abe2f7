// physics/strand_set.h: guide strands ready to simulate: every strand resampled to V vertices,
// rest positions in head space, per-strand attributes (part, pinned vertices, seed), and the
// parts (one per hair source) with their own parameters.
#pragma once

#include "assets/mesh.h"
#include "shaders/shared/sim.h"

#include <string>
#include <vector>

namespace wisp {

inline constexpr uint32_t kMinVerticesPerStrand = 4;
inline constexpr uint32_t kMaxVerticesPerStrand = 64;

struct PartSettings {
    std::string name = "guides";
    float globalStiffness = 0.015f; // per step at the root, [0, 1]
    float localStiffness = 0.04f;   // per step, [0, 1]
    float ftlDamping = 0.9f;        // s_damp, [0.5, 1]
    float drag = 0.6f;              // 1/s
};

struct StrandSet {
    uint32_t verticesPerStrand = 16;
    std::vector<glm::vec3> rest;          // strandCount() * V, head space, root first
    std::vector<gpu::StrandInfo> strands; // one per strand
    std::vector<PartSettings> parts;      // indexed by StrandInfo::part
    // Grown hair: how strongly each vertex of the head is painted under it (physics/scalp.h), from
    // the field its roots were grown at; empty for loaded hair (the renderer paints around the roots).
    std::vector<float> scalpPaint;
    // Each strand's drawn width as a share of the `width` setting (grown hair: finer toward the
    // hairline, GrowthSettings::hairlineWidth); empty: 1 for every strand.
    std::vector<float> widthScale;

    size_t strandCount() const { return strands.size(); }
    size_t vertexCount() const { return rest.size(); }
    float maxLength() const; // longest strand's rest length
    Bounds bounds() const;   // of the rest pose
    // Appends a strand; `points` must already have verticesPerStrand entries.
    void add(const std::vector<glm::vec3>& points, uint32_t part, uint32_t pinnedRoot, bool pinnedTip);
};

// For multi-strand interpolation: each guide with its two nearest neighbours by root distance
// (x: the guide, y, z: the neighbours, w: two halves, packHalf2x16(rest length, width scale): the
// length limits the render-time spread of its strands (placeStrandPoint in shaders/shared/strands.h),
// the width scale is StrandSet::widthScale, read by guideLength and guideWidthScale there), found through a uniform
// grid over the roots, leaving out neighbours whose strands part from the guide's (a third of the way along, farther
// apart than three times the roots' distance plus a tenth of the length: across a parting). A lone guide is its own
// neighbour.
std::vector<glm::uvec4> guideTriangles(const StrandSet& strands);

} // namespace wisp
