// assets/placement.h: where a groom's roots lie against a head, and placing a groom on a head
// whose units, axes or position differ from the one it was made for. The distance of a point to
// the head's surface (a bounding-volume hierarchy over its triangles), the roots' figures as
// fractions of the head's size, and the choice of scale, axes and offset: as in the file when
// the roots are already on the head, else fitted to the scalp (the roots' sphere onto the
// cranium's, then moved onto the surface) and turned to face the way the head faces.
#pragma once

#include "assets/hair_asset.h"
#include "assets/mesh.h"

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace wisp {

// The head part of a bust (y up): its top, and the neck (the narrowest slice between the skull's
// widest and the shoulders; the bottom of a mesh without shoulders).
struct HeadRegion {
    float top = 0.0f;
    float neck = 0.0f;
};
HeadRegion headRegion(const Mesh& mesh);

// Closest points on a triangle mesh (all of it, or some of its triangles: the scalp), through a
// bounding-volume hierarchy over its triangles.
class MeshDistance {
public:
    explicit MeshDistance(const Mesh& mesh);
    MeshDistance(const Mesh& mesh, std::vector<uint32_t> triangles);
    struct Closest {
        glm::vec3 point{0.0f};
        float distance = 0.0f;
        uint32_t triangle = UINT32_MAX; // the triangle holding `point` (UINT32_MAX: an empty mesh)
    };
    Closest closest(glm::vec3 p) const;
    // The surface's normal at a closest point: the unit angle-weighted pseudonormal there (below),
    // from the triangles' winding, not the file's shading normals.
    glm::vec3 normal(const Closest& c) const;
    // Whether the ray from `origin` along `direction` meets a triangle before `length` (in units of
    // `direction`; Moeller and Trumbore 1997).
    bool hits(glm::vec3 origin, glm::vec3 direction, float length) const;

private:
    struct Node {
        glm::vec3 lo, hi;
        uint32_t first = 0; // leaf: first triangle in order_; inner: the right child (left is next)
        uint32_t count = 0; // triangles in a leaf; 0 for an inner node
    };
    void init();
    // The sum of the normals of the triangles within `tolerance` of q, each weighted by its angle
    // at q (pi where q lies inside it or on an edge; the corner's angle at a corner).
    glm::vec3 pseudonormal(glm::vec3 q, float tolerance) const;
    // Calls visit(triangle) for every triangle in a leaf whose box lies within sqrt(radius2) of p.
    template <typename Visit> void within(glm::vec3 p, float radius2, Visit&& visit) const;
    uint32_t build(uint32_t begin, uint32_t end, std::vector<glm::vec3>& centroids);
    const Mesh& mesh_;
    std::vector<uint32_t> order_; // triangle indices, grouped by leaf
    std::vector<Node> nodes_;
};

// A root is on the head when it lies within this fraction of the head's bounding-box diagonal of
// its surface (Sintel's roots: 0.4 mm on a bust of 0.74 m).
inline constexpr float kRootOnSurface = 0.02f;
// A groom is on the head when at least this share of its roots is (an automatic placement must
// reach it); below kRootsOffHead it is not on it at all.
inline constexpr float kRootsOnHead = 0.9f;
inline constexpr float kRootsOffHead = 0.5f;

// The roots against the head's surface, every distance a fraction of the head's diagonal.
struct RootFit {
    size_t roots = 0;
    float median = 0.0f;
    float p90 = 0.0f;
    float max = 0.0f;
    float onSurface = 0.0f; // share of the roots within kRootOnSurface
    bool onHead() const { return onSurface >= kRootsOnHead; }
    bool offHead() const { return onSurface < kRootsOffHead; }
};
RootFit measureRoots(const std::vector<glm::vec3>& roots, const MeshDistance& head, float headDiagonal);

// What the user fixed of the placement (--hair-scale, --hair-offset, --hair-z-up,
// --hair-mirror-z, --hair-half-turn); the rest is chosen.
struct PlacementRequest {
    std::optional<float> scale;
    std::optional<glm::vec3> offset;
    std::optional<bool> zUp;
    std::optional<bool> mirrorZ;
    std::optional<bool> halfTurn;
    // Scale or offset given: the placement is the user's (axes default to the format's).
    bool placesByHand() const { return scale.has_value() || offset.has_value(); }
};

// Which way round a groom is, once placed, against the head's face (its direction from the head
// description, the face the part of the head in front between the chin and the brow):
// `overFace` the share of the groom's points in front of the face (hair hanging over it),
// `longAtBack` from -1 to 1, how much the longer strands grow from the back of the roots' spread
// (1: every strand longer than the mean grows behind the centre, every shorter one in front).
struct GroomFacing {
    float overFace = 0.0f;
    float longAtBack = 0.0f;
};
// A fitted groom's turned-round twin is taken, or the fit kept, when one puts clearly more roots on
// the surface (kFacingRoots more of them), else when the hair over the face differs clearly (at
// least kFacingOverFace of the points on the worse side, twice the other), else when the long
// strands tell (|longAtBack| at least kFacingLongAtBack); else it is ambiguous.
inline constexpr float kFacingRoots = 0.1f;
inline constexpr float kFacingOverFace = 0.02f;
inline constexpr float kFacingLongAtBack = 0.15f;

// How a groom was placed, and its roots against the head afterwards.
struct GroomPlacement {
    enum class Method { File, Units, Fitted, Given };
    // How the front was told from the back: the file's (or the user's) orientation, the roots
    // (one way fits clearly better), the hair over the face, the long strands, or not at all (both
    // ways fit, neither tells: the file's is kept).
    enum class Front { AsPlaced, Roots, Face, LongStrands, Ambiguous };
    HairPlacement placement;
    Method method = Method::File;
    RootFit fit;
    Front front = Front::AsPlaced;
    GroomFacing facing;                // as placed (with Front::AsPlaced and no strands: zeros)
    std::optional<GroomFacing> turned; // its turned-round twin, when one was weighed
    std::optional<RootFit> turnedFit;  // and that twin's roots
    std::string describe() const;      // "fitted to the scalp: scale 0.4, offset (0, 1.2, -3), z-up turned y-up"
    // With Front::Ambiguous: the sentence that says so and how to choose (empty otherwise).
    std::string ambiguity() const;
    nlohmann::json toJson() const;
};

// The groom as placement sees it: every root (as the files store them), and a sample of whole
// strands (roots first) that tells its front from its back against the head's face direction
// (HeadDescription::front; +z for a bare mesh). No strands: roots alone decide, as in the file's
// orientation.
struct GroomShape {
    std::vector<glm::vec3> roots;
    std::vector<std::vector<glm::vec3>> strands;
    glm::vec3 headFront{0.0f, 0.0f, 1.0f};
};

// A groom fitted to a head it was not made for (or placed by hand): a root the fit leaves farther
// than this fraction of the head's diagonal from its surface is moved onto the scalp (Sintel's
// roots on her own bust: median 0.06%, 90% within 0.4%). A groom as in its file (on its own head,
// perhaps in other units) moves only the roots off the head (kRootOnSurface), and its strands
// stay as they are.
inline constexpr float kRootMoved = 0.002f;
// A moved strand's vertex deeper than this fraction of the head's diagonal is inside the head.
inline constexpr float kStrandInside = 0.0005f;

// What transferStrands did, every length a fraction of the head's diagonal.
struct GroomTransfer {
    size_t roots = 0;    // the roots weighed
    float beyond = 0.0f; // a root farther than this from the surface was moved
    size_t moved = 0;    // moved onto the scalp
    float median = 0.0f; // the moved roots' displacement
    float max = 0.0f;
    size_t turned = 0;            // strands turned about their root until no vertex is inside the head
    size_t lifted = 0;            // strands that no turn put out, lifted along the root's normal
    float liftMax = 0.0f;         // the largest lift
    std::string describe() const; // "312 of 3000 roots moved onto the scalp (farther than ...), by median 0.6%, ..."
    nlohmann::json toJson() const;
};

// Moves a groom onto a head, after its rigid fit, as a groom binding carries strands to another
// mesh: each strand whose root lies farther than `beyond` (a fraction of the head's diagonal) from
// the surface gets its root at the closest point of the scalp (of `scalp`, triangles of `head`,
// those on the skin, facing out and seen from outside), and its points carried rigidly in its
// root's frame: the frame at the old root is the head's normal at the surface point nearest it and
// a tangent, the new frame the normal at the new root and that tangent moved with it (the least
// rotation between the normals), so every segment keeps its length and every angle its size. A
// moved strand with a vertex inside the head (past the root, deeper than kStrandInside) is turned
// about its root toward the normal by the least angle that puts it out, or, where standing along
// the normal does not, lifted along the normal by the least distance that does; with `keepAllOut`
// (a groom on a head it was not made for, whose every strand may now cross it) the strands left in
// place are too. `movable`: which strands may move (empty: all).
GroomTransfer transferStrands(std::vector<std::vector<glm::vec3>>& strands, const Mesh& head,
                              const std::vector<uint32_t>& scalp, float beyond, bool keepAllOut,
                              const std::vector<bool>& movable = {});

// The groom placed on `head`. With nothing requested: as in the file (with the power-of-ten scale
// when units clearly differ) where that puts the roots on the head, with either up axis and either
// handedness; else fitted to the scalp, with either up axis; the best by the share of roots on the
// surface. A fitted groom is weighed against its twin turned round about the up axis (root
// distance alone cannot tell a front from a back): by the roots when they clearly differ, else by
// the hair over the face and the long strands (GroomFacing). What the request fixes is kept. The
// caller decides what an off-head result means (GroomedHead refuses an automatic one) and passes on
// an ambiguity. `defaults`: the format's axes (cyHair z-up, TressFX 3 mirrored).
GroomPlacement placeGroom(const GroomShape& groom, const Bounds& groomBounds, const HairPlacement& defaults,
                          const Mesh& head, const PlacementRequest& request = {});
// The figures of GroomFacing for `strands` placed by `placement` on `head`.
GroomFacing measureFacing(const std::vector<std::vector<glm::vec3>>& strands, const HairPlacement& placement,
                          const Mesh& head, glm::vec3 headFront);

} // namespace wisp
