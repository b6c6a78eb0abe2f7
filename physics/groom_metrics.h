// physics/groom_metrics.h: figures of a groom's shape and motion against its head, on the CPU:
// the side standoff (how far the hair stands off the head's silhouette seen from the side, as a
// fraction of the head's width: a wig-like wedge scores high, hair lying on the head low) and the
// tips' lag behind a turn of the head (degrees about the turn axis: a rigid shell lags about 0),
// and the hair inside the head's mesh itself (not its colliders).
#pragma once

#include "assets/mesh.h"
#include "assets/signed_distance.h"
#include "physics/strand_set.h"

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace wisp {

// ---- Side standoff ------------------------------------------------------------------------------
// Seen from the side: orthographic along the head's x axis, y up, the face toward +z (head space).
// The skull's rows are kSideStandoffRows bands of equal height from the head mesh's top (its
// largest y) down kSideStandoffDepthMetres (in head units through unitsPerMetre). In each band, the
// head's extent in z is that of every part of its triangles inside the band, and the hair's that of
// every part of its strand segments inside the band (segments clipped exactly, so a segment
// crossing a band counts even with no vertex in it). Where a band holds both:
//   beyond = max(0, headMinZ - hairMinZ) + max(0, hairMaxZ - headMaxZ)
// and the standoff is the mean of `beyond` over those bands divided by the head's width, the
// largest head extent in z over the same bands. No band with both: 0 (rows = 0). Hair above the
// head's top and below the bands is not counted.
inline constexpr float kSideStandoffDepthMetres = 0.12f;
inline constexpr uint32_t kSideStandoffRows = 48; // 2.5 mm bands over 12 cm

struct SideStandoff {
    double value = 0.0;      // mean hair beyond the head's silhouette / the head's width
    uint32_t rows = 0;       // bands holding both head and hair
    double headWidth = 0.0;  // the head's largest extent in z over those bands, head units
    double meanBeyond = 0.0; // head units
};

// `positions`: strands of `verticesPerStrand` points each, root first, in head space.
SideStandoff sideStandoff(const Mesh& head, const std::vector<glm::vec3>& positions, uint32_t verticesPerStrand,
                          float unitsPerMetre);
// The rest pose of `strands`.
SideStandoff sideStandoff(const Mesh& head, const StrandSet& strands, float unitsPerMetre);

// ---- Inside the mesh -------------------------------------------------------------------------------
// The hair against the head's mesh itself (its exact signed distance, assets/signed_distance.h),
// not the colliders the solver pushes it out of. A vertex counts when it lies past the first
// kInsideSkippedVertices of its strand (the roots, which sit on the scalp) and deeper inside the mesh
// than kInsideDepth of the mesh's bounding-box diagonal; a strand counts when any of its vertices
// does. `deepest` is the largest depth of any vertex past the roots (0 when none is inside), as a
// fraction of the diagonal.
inline constexpr uint32_t kInsideSkippedVertices = 2;
inline constexpr float kInsideDepth = 0.005f;

struct InsideMesh {
    size_t strands = 0;
    size_t vertices = 0; // those past the first kInsideSkippedVertices of each strand
    size_t strandsInside = 0;
    size_t verticesInside = 0;
    double deepest = 0.0;
    double strandShare() const { return strands > 0 ? double(strandsInside) / double(strands) : 0.0; }
    double vertexShare() const { return vertices > 0 ? double(verticesInside) / double(vertices) : 0.0; }
    // {"strands": share, "vertices": share, "deepest": fraction of the diagonal}
    nlohmann::json toJson() const;
    std::string describe() const; // "12.5% of strands, 1.3% of vertices, deepest 0.021 of the diagonal"
};

// `positions`: strands of `verticesPerStrand` points each, root first, in head space;
// `diagonal`: the mesh's bounding-box diagonal.
InsideMesh insideMesh(const MeshSignedDistance& head, float diagonal, const std::vector<glm::vec3>& positions,
                      uint32_t verticesPerStrand);
// The rest pose of `strands`.
InsideMesh insideMesh(const MeshSignedDistance& head, float diagonal, const StrandSet& strands);

// ---- Tip lag --------------------------------------------------------------------------------------
// The turn axis is the head's up axis (head-space y, as the head is posed at the first sample)
// through `pivot` (head space; the head turns about its bounds' centre, app/scene/scene_timeline.h
// headYawTransform). At each sample, with the head's transform M:
//   head yaw = the rotation of M against the first sample's about the axis (continuous: unwrapped
//              from sample to sample);
//   tips' yaw = the least-squares rotation about the axis that takes the tips' first positions to
//              their positions now: atan2(sum a.(r0 x r), sum r0.r) over the free tips (the last
//              vertex of each strand that is neither rigid nor pinned at its tip), r the tip's
//              offset from the axis in the plane across it. It is the tips' mean yaw change
//              weighted by their distance from the axis (a tip on the axis has no yaw), unwrapped
//              from sample to sample;
//   lag = head yaw - tips' yaw.
// peak is the largest |lag| over the samples, final the |lag| at the last one. Samples must come
// often enough that neither turns by 180 degrees between two (Wisp samples every 60 Hz frame).
struct TipLag {
    double peakDeg = 0.0;
    double finalDeg = 0.0;
    double peakAtSeconds = 0.0;
    double largestHeadYawDeg = 0.0; // the head's largest |yaw| from its start
    uint32_t samples = 0;
    size_t tips = 0;
};

class TipLagMeter {
public:
    TipLagMeter(const StrandSet& strands, glm::vec3 pivot);
    // One moment: `positions` strand-major in world space (xyz; w ignored), `head` the head's
    // transform then (head space -> world). The first sample is the start everything is measured from.
    void sample(double seconds, const std::vector<glm::vec4>& positions, const glm::mat4& head);
    const TipLag& result() const { return lag_; }

private:
    std::vector<size_t> tips_; // vertex indices of the free tips
    glm::vec3 pivot_;
    glm::vec3 axis_{0.0f, 1.0f, 0.0f}; // world, from the first sample
    glm::mat3 startRotation_{1.0f};
    std::vector<glm::dvec3> start_; // the tips' offsets across the axis at the first sample
    double headYaw_ = 0.0, tipYaw_ = 0.0;
    TipLag lag_;
};

} // namespace wisp
