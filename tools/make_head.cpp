// tools/make_head.cpp: generates Wisp's default head, a smooth mannequin bust, into models/.
// The shape is a signed distance field of smooth-blended ellipsoids and capsules, meshed with
// naive surface nets; the program also writes head.json (scalp rule, colliders, bbox) and,
// with --preview DIR, PNG renders from a small CPU rasterizer so the shape can be judged.
// Usage: make_head --out-dir models [--resolution N] [--preview DIR]
//
// Conventions: metres, y up, the face looks toward +z. OBJ triangles wind counter-clockwise
// seen from outside; vertex normals are the normalized SDF gradient.
//
// Scalp rule (head.json "scalp"): a triangle (a, b, c) with centroid m = (a + b + c) / 3 and unit
// normal n = normalize(cross(b - a, c - a)) is scalp when both hold:
//     dot(m - plane_point, plane_normal) > 0       above the hairline plane, which is tilted
//                                                  (normal up and back) to pass over the forehead
//                                                  hairline, through the upper ears and
//                                                  through the nape;
//     dot(n, face_direction) <= face_max_dot       not facing forward: trims the forehead above
//                                                  the plane into a rounded hairline, keeping the
//                                                  temples, the crown and the back.
//
// Colliders (head.json "colliders"): ellipsoids. A point p is inside one when |q / radii| < 1 with
// q = transpose(R) * (p - center) and R = Rz(az) * Ry(ay) * Rx(ax) from "rotation_deg" =
// [ax, ay, az] in degrees (right-handed rotations; the ellipsoid's local axes are R's columns).
// Every mesh vertex lies at least 2 mm inside their union, except the nose, ears and flat base.
// models/README.md says the same for the readers of the files.

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include "core/atomic_file.h"
#include "core/rotation.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using glm::dvec3;
using wisp::rotationXyzDegrees;
using wisp::writeFileAtomically;

namespace {

constexpr int kDefaultResolution = 96; // fine cell = 0.45 m / resolution; 96 keeps the OBJ < 2 MB
constexpr int kMinResolution = 48;
constexpr int kMaxResolution = 512;
constexpr int kRefineSteps = 3;       // gradient steps that pull each cell vertex onto the surface
constexpr double kBottomCutY = -0.12; // flat base of the bust (m)
constexpr int kPreviewSize = 512;

// ---------------------------------------------------------------------------------------------
// Signed distance primitives (negative inside). All lengths in metres.

double sdEllipsoid(dvec3 p, dvec3 c, dvec3 r)
{
    // Bound by scaling: exact on the surface, gradient well behaved near it.
    dvec3 q = p - c;
    double k0 = glm::length(q / r);
    double k1 = glm::length(q / (r * r));
    if (k1 < 1e-12)
        return -glm::min(r.x, glm::min(r.y, r.z));
    return k0 * (k0 - 1.0) / k1;
}

// Ellipsoid with centre c and radii r along the columns of the rotation whose transpose is rt.
double sdOrientedEllipsoid(dvec3 p, dvec3 c, dvec3 r, const glm::dmat3& rt)
{
    return sdEllipsoid(rt * (p - c), dvec3(0.0), r);
}

// Capsule from a (radius ra) to b (radius rb), radius interpolated along the segment.
double sdTaperedCapsule(dvec3 p, dvec3 a, dvec3 b, double ra, double rb)
{
    dvec3 ab = b - a;
    double t = glm::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
    return glm::length(p - (a + t * ab)) - glm::mix(ra, rb, t);
}

double sdCapsule(dvec3 p, dvec3 a, dvec3 b, double r)
{
    return sdTaperedCapsule(p, a, b, r, r);
}

// Polynomial smooth minimum (blend width k): the union with a fillet of size ~k.
double smin(double a, double b, double k)
{
    double h = glm::max(k - std::abs(a - b), 0.0) / k;
    return glm::min(a, b) - h * h * k * 0.25;
}
double smax(double a, double b, double k)
{
    return -smin(-a, -b, k);
}

dvec3 mirrorX(dvec3 p)
{
    return {std::abs(p.x), p.y, p.z};
}

// ---------------------------------------------------------------------------------------------
// The bust. Left/right symmetric features are evaluated on |x|.

double headSdf(dvec3 p)
{
    dvec3 m = mirrorX(p);

    // Cranium and forehead.
    double d = sdEllipsoid(p, {0.0, 0.150, -0.015}, {0.077, 0.100, 0.097});
    d = smin(d, sdEllipsoid(p, {0.0, 0.158, 0.018}, {0.067, 0.072, 0.072}), 0.03);

    // Face: an egg, narrowing from the cheekbones down to the chin (x squeezed below y = 0.11).
    dvec3 e = p;
    double taper = glm::clamp((0.11 - p.y) / 0.09, 0.0, 1.0);
    e.x *= 1.0 + 0.42 * taper * taper;
    d = smin(d, sdEllipsoid(e, {0.0, 0.100, 0.018}, {0.066, 0.086, 0.070}), 0.03);
    d = smin(d, sdEllipsoid(p, {0.0, 0.036, 0.068}, {0.021, 0.019, 0.018}), 0.02);
    d = smin(d, sdEllipsoid(m, {0.034, 0.088, 0.046}, {0.022, 0.022, 0.027}), 0.03); // soft cheeks

    // Brow ridge; eye sockets with the closed lids of a mannequin bulging inside them.
    d = smin(d, sdCapsule(p, {-0.036, 0.142, 0.078}, {0.036, 0.142, 0.078}, 0.011), 0.02);
    d = smax(d, -sdEllipsoid(m, {0.031, 0.124, 0.099}, {0.016, 0.010, 0.011}), 0.010);
    d = smin(d, sdEllipsoid(m, {0.031, 0.122, 0.077}, {0.012, 0.010, 0.010}), 0.005);

    // Nose: bridge to tip, with the wings (alae) either side of the tip.
    d = smin(d, sdTaperedCapsule(p, {0.0, 0.132, 0.088}, {0.0, 0.091, 0.105}, 0.007, 0.011), 0.012);
    d = smin(d, sdEllipsoid(m, {0.011, 0.091, 0.096}, {0.0065, 0.0055, 0.0065}), 0.006);

    // Mouth: the rounded muzzle over the teeth, two lips, the dip above the chin.
    d = smin(d, sdEllipsoid(p, {0.0, 0.067, 0.068}, {0.026, 0.020, 0.019}), 0.015);
    d = smin(d, sdEllipsoid(p, {0.0, 0.0715, 0.0855}, {0.015, 0.0045, 0.0065}), 0.006);
    d = smin(d, sdEllipsoid(p, {0.0, 0.0605, 0.0835}, {0.013, 0.0055, 0.0065}), 0.006);
    d = smax(d, -sdEllipsoid(p, {0.0, 0.049, 0.093}, {0.014, 0.004, 0.007}), 0.006);

    // Ears: stylized, flattened against the head.
    d = smin(d, sdEllipsoid(m, {0.074, 0.112, -0.012}, {0.011, 0.028, 0.018}), 0.012);

    // Neck: a long ellipsoid leaning slightly forward as it rises.
    static const glm::dmat3 neckTilt = glm::transpose(rotationXyzDegrees(dvec3(7.0, 0.0, 0.0)));
    d = smin(d, sdOrientedEllipsoid(p, {0.0, 0.005, -0.020}, {0.050, 0.120, 0.053}, neckTilt), 0.022);

    // Shoulders and upper chest: two overlapping ellipsoids, each tilted so its outer end drops
    // toward the shoulder; the neck blend forms the trapezius slope.
    static const glm::dmat3 shoulderTilt = glm::transpose(rotationXyzDegrees(dvec3(0.0, 0.0, -7.0)));
    auto shoulder = [](dvec3 q) {
        return sdOrientedEllipsoid(q, {0.065, -0.118, -0.006}, {0.140, 0.075, 0.098}, shoulderTilt);
    };
    double torso = smin(shoulder(p), shoulder({-p.x, p.y, p.z}), 0.02);
    d = smin(d, torso, 0.035);

    // Flat base, softly rounded rim.
    return smax(d, kBottomCutY - p.y, 0.016);
}

dvec3 sdfGradient(dvec3 p)
{
    constexpr double h = 1e-5;
    return dvec3(headSdf(p + dvec3(h, 0, 0)) - headSdf(p - dvec3(h, 0, 0)),
                 headSdf(p + dvec3(0, h, 0)) - headSdf(p - dvec3(0, h, 0)),
                 headSdf(p + dvec3(0, 0, h)) - headSdf(p - dvec3(0, 0, h))) /
           (2.0 * h);
}

// ---------------------------------------------------------------------------------------------
// Naive surface nets.

struct Mesh {
    std::vector<dvec3> positions;
    std::vector<dvec3> normals;
    std::vector<std::array<int, 3>> triangles;
};

// Grid coordinates from `anchor` outwards, each step spacing(coordinate) long, until a whole
// cell lies beyond lo and beyond hi (the outermost cells must stay empty of surface).
template <typename Spacing> std::vector<double> gridAxis(double lo, double hi, double anchor, Spacing spacing)
{
    std::vector<double> below, axis;
    for (double x = anchor; below.size() < 2 || below[below.size() - 2] > lo;)
        below.push_back(x -= spacing(x));
    axis.assign(below.rbegin(), below.rend());
    axis.push_back(anchor);
    for (double x = anchor; axis[axis.size() - 2] < hi;)
        axis.push_back(x += spacing(x));
    return axis;
}

// The grid is rectilinear: cells are fine (0.45 m / resolution) over the head, face and neck,
// and kCoarseFactor times longer in x and y out on the shoulders and chest, where the surface is
// plain and would otherwise spend most of the vertex budget.
constexpr double kCoarseFactor = 3.0;

Mesh buildSurfaceNets(int resolution)
{
    const double fine = 0.45 / resolution, coarse = kCoarseFactor * fine;
    auto ramp = [](double a, double b, double x) {
        double t = glm::clamp((x - a) / (b - a), 0.0, 1.0);
        return t * t * (3.0 - 2.0 * t);
    };
    // x is built from 0 out on both sides, so the grid is mirror symmetric.
    const std::vector<double> xs =
        gridAxis(-0.225, 0.225, 0.0, [&](double x) { return glm::mix(fine, coarse, ramp(0.095, 0.135, std::abs(x))); });
    const std::vector<double> ys = gridAxis(kBottomCutY - 0.012, 0.265, 0.005, [&](double y) {
        return glm::mix(fine, coarse, ramp(0.005, -0.045, y) * ramp(-0.112, -0.085, y)); // fine at the base rim
    });
    const std::vector<double> zs = gridAxis(-0.140, 0.140, 0.0, [&](double) { return fine; });
    const int nx = int(xs.size()), ny = int(ys.size()), nz = int(zs.size());

    auto pointIndex = [&](int i, int j, int k) { return (size_t(k) * ny + j) * nx + i; };
    auto gridPoint = [&](int i, int j, int k) { return dvec3(xs[i], ys[j], zs[k]); };

    std::vector<double> field(size_t(nx) * ny * nz);
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                field[pointIndex(i, j, k)] = headSdf(gridPoint(i, j, k));

    // One vertex per cell whose corners change sign.
    static constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                          {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
    static constexpr int kEdge[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                         {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    Mesh mesh;
    auto cellIndex = [&](int i, int j, int k) { return (size_t(k) * (ny - 1) + j) * (nx - 1) + i; };
    std::vector<int> cellVertex(size_t(nx - 1) * (ny - 1) * (nz - 1), -1);
    for (int k = 0; k + 1 < nz; ++k)
        for (int j = 0; j + 1 < ny; ++j)
            for (int i = 0; i + 1 < nx; ++i) {
                double v[8];
                int inside = 0;
                for (int c = 0; c < 8; ++c) {
                    v[c] = field[pointIndex(i + kCorner[c][0], j + kCorner[c][1], k + kCorner[c][2])];
                    inside += v[c] < 0.0;
                }
                if (inside == 0 || inside == 8)
                    continue;
                dvec3 sum(0.0);
                int crossings = 0;
                for (const auto& e : kEdge) {
                    double a = v[e[0]], b = v[e[1]];
                    if ((a < 0.0) == (b < 0.0))
                        continue;
                    double t = a / (a - b);
                    dvec3 pa = gridPoint(i + kCorner[e[0]][0], j + kCorner[e[0]][1], k + kCorner[e[0]][2]);
                    dvec3 pb = gridPoint(i + kCorner[e[1]][0], j + kCorner[e[1]][1], k + kCorner[e[1]][2]);
                    sum += glm::mix(pa, pb, t);
                    ++crossings;
                }
                dvec3 p = sum / double(crossings);
                const double cell = std::min({xs[i + 1] - xs[i], ys[j + 1] - ys[j], zs[k + 1] - zs[k]});
                // Pull the mean of the crossings onto the zero set; a step never exceeds one cell.
                for (int s = 0; s < kRefineSteps; ++s) {
                    dvec3 g = sdfGradient(p);
                    double g2 = glm::dot(g, g);
                    if (g2 < 1e-12)
                        break;
                    dvec3 step = headSdf(p) * g / g2;
                    double len = glm::length(step);
                    if (len > cell)
                        step *= cell / len;
                    p -= step;
                }
                cellVertex[cellIndex(i, j, k)] = int(mesh.positions.size());
                mesh.positions.push_back(p);
                mesh.normals.push_back(glm::normalize(sdfGradient(p)));
            }

    // One quad per sign-changing grid edge, joining the four cells around it.
    auto emitQuad = [&](int a, int b, int c, int d) {
        const auto& P = mesh.positions;
        if (glm::distance(P[a], P[c]) <= glm::distance(P[b], P[d])) {
            mesh.triangles.push_back({a, b, c});
            mesh.triangles.push_back({a, c, d});
        } else {
            mesh.triangles.push_back({a, b, d});
            mesh.triangles.push_back({b, c, d});
        }
    };
    for (int k = 1; k + 1 < nz; ++k)
        for (int j = 1; j + 1 < ny; ++j)
            for (int i = 1; i + 1 < nx; ++i) {
                double d0 = field[pointIndex(i, j, k)];
                for (int axis = 0; axis < 3; ++axis) {
                    int di = axis == 0, dj = axis == 1, dk = axis == 2;
                    double d1 = field[pointIndex(i + di, j + dj, k + dk)];
                    if ((d0 < 0.0) == (d1 < 0.0))
                        continue;
                    // The four cells around the edge, ordered (in the two axes that follow `axis`
                    // cyclically) so that the quad faces +axis.
                    int q[4];
                    static constexpr int kAround[4][2] = {{-1, -1}, {0, -1}, {0, 0}, {-1, 0}};
                    for (int n = 0; n < 4; ++n) {
                        int off[3] = {0, 0, 0};
                        off[(axis + 1) % 3] = kAround[n][0];
                        off[(axis + 2) % 3] = kAround[n][1];
                        q[n] = cellVertex[cellIndex(i + off[0], j + off[1], k + off[2])];
                    }
                    if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[3] < 0)
                        continue;
                    if (d0 < 0.0)
                        emitQuad(q[0], q[1], q[2], q[3]); // inside at the low end: outward is +axis
                    else
                        emitQuad(q[0], q[3], q[2], q[1]);
                }
            }
    return mesh;
}

struct MeshStats {
    int boundaryEdges = 0;    // undirected edges used by one triangle
    int nonManifoldEdges = 0; // used by more than two
    int misorientedEdges = 0; // a directed edge used twice: neighbours wound inconsistently
    int flippedTriangles = 0; // face normal disagrees with its vertex normals
};

MeshStats checkMesh(const Mesh& mesh)
{
    MeshStats stats;
    std::map<std::pair<int, int>, int> directed;
    for (const auto& t : mesh.triangles)
        for (int e = 0; e < 3; ++e)
            ++directed[{t[e], t[(e + 1) % 3]}];
    for (const auto& [edge, count] : directed) {
        if (count > 1)
            stats.misorientedEdges += 1;
        auto it = directed.find({edge.second, edge.first});
        int total = count + (it == directed.end() ? 0 : it->second);
        if (edge.first < edge.second || it == directed.end()) {
            if (total == 1)
                ++stats.boundaryEdges;
            if (total > 2)
                ++stats.nonManifoldEdges;
        }
    }
    for (const auto& t : mesh.triangles) {
        const auto& P = mesh.positions;
        dvec3 n = glm::cross(P[t[1]] - P[t[0]], P[t[2]] - P[t[0]]);
        dvec3 vn = mesh.normals[t[0]] + mesh.normals[t[1]] + mesh.normals[t[2]];
        if (glm::dot(n, vn) <= 0.0)
            ++stats.flippedTriangles;
    }
    return stats;
}

// ---------------------------------------------------------------------------------------------
// Scalp: a hairline plane through the forehead and the nape, plus a forward-facing cut.

struct Scalp {
    dvec3 planePoint;
    dvec3 planeNormal;
    dvec3 faceDirection{0.0, 0.0, 1.0};
    double faceMaxDot;
};

Scalp makeScalp()
{
    // Hairline heights on the midline (m): forehead at the front, nape at the back.
    const dvec3 forehead(0.0, 0.198, 0.090);
    const dvec3 nape(0.0, 0.055, -0.105);
    dvec3 along = forehead - nape;
    Scalp scalp;
    scalp.planePoint = 0.5 * (forehead + nape);
    scalp.planeNormal = glm::normalize(dvec3(0.0, along.z, -along.y)); // up and back
    scalp.faceMaxDot = 0.80;
    return scalp;
}

dvec3 triangleCentroid(const Mesh& mesh, const std::array<int, 3>& t)
{
    return (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
}

// The unit geometric normal of a CCW triangle, pointing out of the head.
dvec3 triangleNormal(const Mesh& mesh, const std::array<int, 3>& t)
{
    const auto& P = mesh.positions;
    return glm::normalize(glm::cross(P[t[1]] - P[t[0]], P[t[2]] - P[t[0]]));
}

bool isScalp(const Scalp& scalp, dvec3 centroid, dvec3 normal)
{
    return glm::dot(centroid - scalp.planePoint, scalp.planeNormal) > 0.0 &&
           glm::dot(normal, scalp.faceDirection) <= scalp.faceMaxDot;
}

// ---------------------------------------------------------------------------------------------
// Colliders: ellipsoids whose union hugs the mesh a few millimetres outside it.
//
// The clearance at a vertex is its depth inside the union (the largest depth over the
// ellipsoids, a lower bound of the distance to the union's surface). All ellipsoid parameters are
// fitted together by a pattern search that pulls the clearance toward kColliderTarget, then radii
// grow until it is at least kColliderMin everywhere. Nose, ears and the flat base are left out:
// hair does not rest there, and covering the nose would balloon the face ellipsoid.

constexpr double kColliderTarget = 0.0035; // wanted clearance (m)
constexpr double kColliderMin = 0.002;     // least clearance allowed (m)

struct Collider {
    std::string name;
    dvec3 center;
    dvec3 radii;
    dvec3 rotationDeg; // R = Rz * Ry * Rx, degrees
};

// A collider in its own frame: R^T (p - center) is the point in ellipsoid coordinates.
struct LocalFrame {
    glm::dmat3 rt;
    dvec3 center, radii;
    explicit LocalFrame(const Collider& c)
        : rt(glm::transpose(rotationXyzDegrees(c.rotationDeg))), center(c.center), radii(c.radii)
    {
    }
    // How deep p lies inside the ellipsoid (negative outside), from the scaled-sphere bound.
    double depth(dvec3 p) const { return -sdEllipsoid(rt * (p - center), dvec3(0.0), radii); }
};

// The clearance at a mesh point: how far the surface of the collider union lies outside it
// (its depth inside the union; negative where the mesh pokes out of every collider).
double unionClearance(const std::vector<LocalFrame>& frames, dvec3 p)
{
    double best = -1.0;
    for (const auto& f : frames)
        best = std::max(best, f.depth(p));
    return best;
}

// Parameters of the fit: cranium, face and neck (centre y z, radii, tilt about x each) and a
// mirrored pair of shoulder ellipsoids (centre x y z, radii, rotation about x and z).
constexpr int kColliderParams = 3 * 6 + 8;

std::vector<Collider> collidersFromParams(const std::array<double, kColliderParams>& q)
{
    std::vector<Collider> c;
    const char* names[3] = {"cranium", "face", "neck"};
    for (int i = 0; i < 3; ++i) {
        const double* k = &q[size_t(i) * 6];
        c.push_back({names[i], {0.0, k[0], k[1]}, {k[2], k[3], k[4]}, {k[5], 0.0, 0.0}});
    }
    const double* s = &q[18];
    c.push_back({"shoulder_left", {s[0], s[1], s[2]}, {s[3], s[4], s[5]}, {s[6], 0.0, s[7]}});
    c.push_back({"shoulder_right", {-s[0], s[1], s[2]}, {s[3], s[4], s[5]}, {s[6], 0.0, -s[7]}});
    return c;
}

bool fittedByColliders(dvec3 p, dvec3 n)
{
    bool ear = std::abs(p.x) > 0.068 && p.y > 0.078 && p.y < 0.148 && p.z > -0.04 && p.z < 0.016;
    bool nose = std::abs(p.x) < 0.024 && p.y > 0.08 && p.y < 0.14 && p.z > 0.088;
    bool base = p.y < kBottomCutY + 0.01 && n.y < -0.5;
    return !ear && !nose && !base;
}

struct ColliderFit {
    std::vector<Collider> colliders;
    double minClearance, medianClearance, p90Clearance; // over the fitted vertices (m)
    std::vector<double> vertexClearance;                // every vertex; NaN where not fitted
};

ColliderFit fitColliders(const Mesh& mesh, const Scalp& scalp)
{
    std::vector<int> fitted, sample;
    for (size_t v = 0; v < mesh.positions.size(); ++v)
        if (fittedByColliders(mesh.positions[v], mesh.normals[v]))
            fitted.push_back(int(v));
    for (size_t i = 0; i < fitted.size(); i += 2)
        sample.push_back(fitted[i]);
    // The scalp counts twice: hair roots and the hair lying on them should sit close.
    std::vector<double> weight(mesh.positions.size(), 1.0);
    for (size_t v = 0; v < mesh.positions.size(); ++v)
        if (glm::dot(mesh.positions[v] - scalp.planePoint, scalp.planeNormal) > 0.0)
            weight[v] = 2.0;

    // Initial guesses and bounds (m, degrees), in collidersFromParams order.
    struct Param {
        double start, lo, hi;
    };
    // clang-format off
    const std::array<Param, kColliderParams> params = {{
        // cranium: centre y z, radii x y z, tilt about x
        {0.150, 0.12, 0.17}, {-0.012, -0.03, 0.01},
        {0.082, 0.06, 0.12}, {0.104, 0.06, 0.14}, {0.100, 0.06, 0.14}, {0.0, -80.0, 80.0},
        // face
        {0.090, 0.05, 0.12}, {0.020, 0.0, 0.05},
        {0.065, 0.04, 0.09}, {0.080, 0.05, 0.11}, {0.075, 0.04, 0.10}, {0.0, -60.0, 60.0},
        // neck
        {0.020, -0.04, 0.06}, {-0.018, -0.04, 0.0},
        {0.052, 0.04, 0.08}, {0.080, 0.04, 0.12}, {0.055, 0.04, 0.08}, {8.0, -20.0, 25.0},
        // left shoulder: centre x y z, radii x y z, rotation about x and z
        {0.065, 0.0, 0.12}, {-0.118, -0.14, -0.06}, {-0.006, -0.03, 0.02},
        {0.1435, 0.08, 0.25}, {0.0785, 0.04, 0.12}, {0.1015, 0.07, 0.14}, {0.0, -20.0, 20.0}, {-7.0, -30.0, 30.0},
    }};
    // clang-format on
    auto isAngle = [](size_t i) { return (i < 18 && i % 6 == 5) || i >= 24; };

    // Mean squared clearance beyond the target, plus a steep penalty for any shortfall.
    auto cost = [&](const std::array<double, kColliderParams>& q) {
        for (size_t i = 0; i < q.size(); ++i)
            if (q[i] < params[i].lo || q[i] > params[i].hi)
                return 1e30;
        std::vector<Collider> cs = collidersFromParams(q);
        std::vector<LocalFrame> frames(cs.begin(), cs.end());
        double sum = 0.0;
        for (int v : sample) {
            double t = unionClearance(frames, mesh.positions[v]);
            double excess = std::max(0.0, t - kColliderTarget), shortfall = std::max(0.0, kColliderMin - t);
            sum += weight[size_t(v)] * (excess * excess + 1000.0 * shortfall * shortfall);
        }
        return sum / double(sample.size());
    };

    // Pattern search: axis steps, then seeded random directions, halving the step when stuck.
    std::array<double, kColliderParams> q, step;
    for (size_t i = 0; i < q.size(); ++i)
        q[i] = params[i].start, step[i] = isAngle(i) ? 4.0 : 0.004;
    double best = cost(q);
    uint32_t seed = 12345u;
    auto random = [&seed]() { // deterministic LCG in [-1, 1]
        seed = seed * 1664525u + 1013904223u;
        return double(seed >> 8) / double(1u << 23) - 1.0;
    };
    for (int round = 0; round < 8; ++round) {
        bool improved = true;
        for (int sweep = 0; improved && sweep < 60; ++sweep) {
            improved = false;
            for (size_t i = 0; i < q.size(); ++i)
                for (double dir : {1.0, -1.0}) {
                    auto trial = q;
                    trial[i] += dir * step[i];
                    double c = cost(trial);
                    if (c < best)
                        best = c, q = trial, improved = true;
                }
            for (int r = 0; r < 40; ++r) {
                auto trial = q;
                for (size_t i = 0; i < q.size(); ++i)
                    trial[i] += random() * step[i];
                double c = cost(trial);
                if (c < best)
                    best = c, q = trial, improved = true;
            }
        }
        for (double& s : step)
            s *= 0.5;
    }

    // Tidy numbers (0.1 mm, 0.1 degree), then grow radii until every fitted vertex is clear.
    for (size_t i = 0; i < q.size(); ++i) {
        q[i] = isAngle(i) ? std::round(q[i] * 10.0) / 10.0 : std::round(q[i] * 1e4) / 1e4;
    }
    ColliderFit fit;
    fit.colliders = collidersFromParams(q);
    std::vector<double> t(fitted.size());
    for (int pass = 0;; ++pass) {
        std::vector<LocalFrame> frames(fit.colliders.begin(), fit.colliders.end());
        std::vector<int> owner(fit.colliders.size(), 0);
        for (size_t i = 0; i < fitted.size(); ++i)
            t[i] = unionClearance(frames, mesh.positions[fitted[i]]);
        // Each collider that is the outermost at some vertex short of kColliderMin grows 0.1 mm.
        bool grew = false;
        for (size_t i = 0; i < fitted.size(); ++i) {
            if (t[i] >= kColliderMin)
                continue;
            dvec3 p = mesh.positions[fitted[i]];
            size_t k = 0;
            for (size_t j = 1; j < frames.size(); ++j)
                if (frames[j].depth(p) > frames[k].depth(p))
                    k = j;
            owner[k] = 1;
        }
        owner[3] = owner[4] = owner[3] | owner[4]; // the shoulders stay mirror images
        for (size_t k = 0; k < owner.size(); ++k)
            if (owner[k])
                fit.colliders[k].radii += dvec3(1e-4), grew = true;
        if (!grew || pass > 200)
            break;
    }
    std::vector<double> sorted = t;
    std::sort(sorted.begin(), sorted.end());
    fit.minClearance = sorted.front();
    fit.medianClearance = sorted[sorted.size() / 2];
    fit.p90Clearance = sorted[sorted.size() * 9 / 10];
    fit.vertexClearance.assign(mesh.positions.size(), std::nan(""));
    for (size_t i = 0; i < fitted.size(); ++i)
        fit.vertexClearance[size_t(fitted[i])] = t[i];
    return fit;
}

// ---------------------------------------------------------------------------------------------
// Output: every file is written to a temporary name beside its target, then renamed over it
// (core/atomic_file.h).

void appendFixed(std::string& out, double x)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.5f", x);
    out += std::string(buf) == "-0.00000" ? "0.00000" : buf;
}

std::string objText(const Mesh& mesh, int resolution)
{
    std::string out;
    out.reserve(mesh.positions.size() * 64 + mesh.triangles.size() * 44);
    out += "# Wisp mannequin bust, generated by tools/make_head (surface nets, resolution " +
           std::to_string(resolution) + ").\n# Metres, y up, face toward +z, CCW triangles.\n";
    for (const auto& p : mesh.positions) {
        out += "v ";
        appendFixed(out, p.x), out += ' ', appendFixed(out, p.y), out += ' ', appendFixed(out, p.z);
        out += '\n';
    }
    for (const auto& n : mesh.normals) {
        out += "vn ";
        appendFixed(out, n.x), out += ' ', appendFixed(out, n.y), out += ' ', appendFixed(out, n.z);
        out += '\n';
    }
    for (const auto& t : mesh.triangles) {
        out += 'f';
        for (int i : t)
            out += ' ' + std::to_string(i + 1) + "//" + std::to_string(i + 1);
        out += '\n';
    }
    return out;
}

double round5(double x)
{
    double r = std::round(x * 1e5) / 1e5;
    return r == 0.0 ? 0.0 : r;
}
nlohmann::ordered_json vec(dvec3 v)
{
    return {round5(v.x), round5(v.y), round5(v.z)};
}

// nlohmann's indented dump puts every number on its own line; keep flat number arrays on one.
std::string compactArrays(const std::string& text)
{
    std::string out;
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '[') {
            size_t close = text.find(']', i);
            std::string inner = text.substr(i + 1, close - i - 1);
            if (inner.find('[') == std::string::npos && inner.find('{') == std::string::npos) {
                std::string flat;
                for (char ch : inner)
                    if (ch != '\n' && ch != ' ')
                        flat += ch == ',' ? std::string(", ") : std::string(1, ch);
                out += '[' + flat + ']';
                i = close;
                continue;
            }
        }
        out += text[i];
    }
    return out;
}

std::string jsonText(const Mesh& mesh, const Scalp& scalp, const std::vector<Collider>& colliders)
{
    dvec3 lo(1e9), hi(-1e9);
    for (const auto& p : mesh.positions)
        lo = glm::min(lo, p), hi = glm::max(hi, p);
    nlohmann::ordered_json j;
    j["name"] = "Wisp mannequin";
    j["mesh"] = "head.obj";
    j["units"] = "m";
    j["up"] = {0, 1, 0};
    j["front"] = {0, 0, 1};
    j["scalp"] = {{"plane_point", vec(scalp.planePoint)},
                  {"plane_normal", vec(scalp.planeNormal)},
                  {"face_direction", vec(scalp.faceDirection)},
                  {"face_max_dot", round5(scalp.faceMaxDot)}};
    j["colliders"] = nlohmann::ordered_json::array();
    for (const auto& c : colliders)
        j["colliders"].push_back({{"name", c.name},
                                  {"center", vec(c.center)},
                                  {"radii", vec(c.radii)},
                                  {"rotation_deg", vec(c.rotationDeg)}});
    j["bbox"] = {vec(lo), vec(hi)};
    return compactArrays(j.dump(2)) + "\n";
}

// ---------------------------------------------------------------------------------------------
// Preview: an orthographic z-buffered rasterizer with Lambert shading; scalp tinted red.

struct View {
    const char* file;
    double yawDeg;     // camera position rotated about +y from the +z (front) axis
    dvec3 centre;      // world point at the image centre (m)
    double halfExtent; // world distance from the centre to the image edge (m)
};

std::string renderPng(const Mesh& mesh, const std::vector<dvec3>& triangleColour, const View& view)
{
    constexpr int kSuper = 2;
    constexpr int size = kPreviewSize * kSuper;
    const double yaw = glm::radians(view.yawDeg);
    const dvec3 toCamera(std::sin(yaw), 0.0, std::cos(yaw));
    const dvec3 right(std::cos(yaw), 0.0, -std::sin(yaw));
    const dvec3 up(0.0, 1.0, 0.0);
    const dvec3 light = glm::normalize(-0.45 * right + 0.6 * up + 0.75 * toCamera);
    const dvec3 centre = view.centre;
    const double scale = 0.5 * size / view.halfExtent;

    std::vector<double> depth(size_t(size) * size, -1e9);
    std::vector<dvec3> colour(size_t(size) * size, dvec3(0.16, 0.17, 0.19));
    std::vector<dvec3> screen(mesh.positions.size());
    for (size_t v = 0; v < screen.size(); ++v) {
        dvec3 p = mesh.positions[v] - centre;
        screen[v] = {size * 0.5 + scale * glm::dot(p, right), size * 0.5 - scale * glm::dot(p, up),
                     glm::dot(p, toCamera)};
    }
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        dvec3 a = screen[tri[0]], b = screen[tri[1]], c = screen[tri[2]];
        double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (area >= 0.0)
            continue; // y points down on screen: front faces have negative area
        int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
        int x1 = std::min(size - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
        int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
        int y1 = std::min(size - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
        const dvec3 base = triangleColour[t];
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                double px = x + 0.5, py = y + 0.5;
                double wa = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
                double wb = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
                double wc = 1.0 - wa - wb;
                if (wa < 0.0 || wb < 0.0 || wc < 0.0)
                    continue;
                double z = wa * a.z + wb * b.z + wc * c.z;
                size_t idx = size_t(y) * size + x;
                if (z <= depth[idx])
                    continue;
                depth[idx] = z;
                dvec3 n =
                    glm::normalize(wa * mesh.normals[tri[0]] + wb * mesh.normals[tri[1]] + wc * mesh.normals[tri[2]]);
                double lambert = std::max(0.0, glm::dot(n, light));
                colour[idx] = base * (0.22 + 0.78 * lambert);
            }
    }
    std::vector<unsigned char> pixels(size_t(kPreviewSize) * kPreviewSize * 3);
    for (int y = 0; y < kPreviewSize; ++y)
        for (int x = 0; x < kPreviewSize; ++x) {
            dvec3 sum(0.0);
            for (int sy = 0; sy < kSuper; ++sy)
                for (int sx = 0; sx < kSuper; ++sx)
                    sum += colour[size_t(y * kSuper + sy) * size + (x * kSuper + sx)];
            dvec3 srgb = glm::pow(glm::clamp(sum / double(kSuper * kSuper), 0.0, 1.0), dvec3(1.0 / 2.2));
            for (int ch = 0; ch < 3; ++ch)
                pixels[(size_t(y) * kPreviewSize + x) * 3 + ch] =
                    static_cast<unsigned char>(std::lround(srgb[ch] * 255.0));
        }
    std::string png;
    auto sink = [](void* context, void* data, int bytes) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(bytes));
    };
    if (!stbi_write_png_to_func(sink, &png, kPreviewSize, kPreviewSize, 3, pixels.data(), kPreviewSize * 3))
        throw std::runtime_error(std::string("cannot encode ") + view.file);
    return png;
}

// ---------------------------------------------------------------------------------------------

constexpr const char* kUsage = "make_head --out-dir DIR [--resolution N] [--preview DIR]";

struct Options {
    bool help = false;
    fs::path outDir;
    fs::path previewDir;
    int resolution = kDefaultResolution;
};

Options parseOptions(int argc, char** argv)
{
    Options options;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc)
                throw std::runtime_error(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--out-dir") {
            options.outDir = value();
        } else if (arg == "--preview") {
            options.previewDir = value();
        } else if (arg == "--resolution") {
            std::string text = value();
            char* end = nullptr;
            long n = std::strtol(text.c_str(), &end, 10);
            if (text.empty() || *end != '\0' || n < kMinResolution || n > kMaxResolution)
                throw std::runtime_error("--resolution must be an integer in [" + std::to_string(kMinResolution) +
                                         ", " + std::to_string(kMaxResolution) + "], got '" + text + "'");
            options.resolution = int(n);
        } else if (arg == "--help" || arg == "-h") {
            options.help = true;
        } else {
            throw std::runtime_error("unknown option '" + arg + "' (usage: " + kUsage + ")");
        }
    }
    if (options.outDir.empty() && !options.help)
        throw std::runtime_error(std::string("--out-dir is required (usage: ") + kUsage + ")");
    return options;
}

// Creates dir if needed and proves it writable before any work is done.
void makeWritableDirectory(const fs::path& dir)
{
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw std::runtime_error("cannot create directory " + dir.string());
    fs::path probe = dir / ".make_head_probe";
    bool ok = static_cast<bool>(std::ofstream(probe));
    fs::remove(probe, ec);
    if (!ok)
        throw std::runtime_error("cannot write in directory " + dir.string());
}

int run(const Options& options)
{
    if (options.help) {
        std::printf("usage: %s\n", kUsage);
        return 0;
    }
    makeWritableDirectory(options.outDir);
    if (!options.previewDir.empty())
        makeWritableDirectory(options.previewDir);

    Mesh mesh = buildSurfaceNets(options.resolution);
    MeshStats stats = checkMesh(mesh);
    Scalp scalp = makeScalp();
    std::vector<char> scalpTriangle(mesh.triangles.size());
    size_t scalpCount = 0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        scalpTriangle[t] =
            isScalp(scalp, triangleCentroid(mesh, mesh.triangles[t]), triangleNormal(mesh, mesh.triangles[t]));
        scalpCount += scalpTriangle[t];
    }
    ColliderFit fit = fitColliders(mesh, scalp);

    std::string obj = objText(mesh, options.resolution);
    writeFileAtomically(options.outDir / "head.obj", obj);
    writeFileAtomically(options.outDir / "head.json", jsonText(mesh, scalp, fit.colliders));

    std::printf("head.obj: %zu vertices, %zu triangles, %zu bytes; scalp %zu triangles\n", mesh.positions.size(),
                mesh.triangles.size(), obj.size(), scalpCount);
    std::printf("mesh check: %d boundary, %d non-manifold, %d misoriented edges; %d flipped triangles\n",
                stats.boundaryEdges, stats.nonManifoldEdges, stats.misorientedEdges, stats.flippedTriangles);
    std::printf("collider clearance outside the mesh: min %.1f mm, median %.1f mm, 90%% %.1f mm\n",
                fit.minClearance * 1e3, fit.medianClearance * 1e3, fit.p90Clearance * 1e3);

    if (!options.previewDir.empty()) {
        // Scalp views: scalp triangles red on a pale mannequin.
        std::vector<dvec3> scalpColour(mesh.triangles.size());
        for (size_t t = 0; t < mesh.triangles.size(); ++t)
            scalpColour[t] = scalpTriangle[t] ? dvec3(0.86, 0.40, 0.34) : dvec3(0.88, 0.86, 0.82);
        // Collider views: clearance of the collider union, blue under kColliderMin, green to 5 mm,
        // yellow to 10 mm, red beyond; grey where the fit ignores the mesh (nose, ears, base).
        std::vector<dvec3> clearanceColour(mesh.triangles.size());
        for (size_t t = 0; t < mesh.triangles.size(); ++t) {
            double sum = 0.0;
            bool ignored = false;
            for (int v : mesh.triangles[t]) {
                double c = fit.vertexClearance[size_t(v)];
                ignored |= std::isnan(c);
                sum += c;
            }
            double c = sum / 3.0;
            clearanceColour[t] = ignored                   ? dvec3(0.6)
                                 : c < kColliderMin - 1e-4 ? dvec3(0.3, 0.45, 0.95)
                                 : c < 0.005               ? dvec3(0.35, 0.85, 0.4)
                                 : c < 0.010               ? dvec3(0.95, 0.85, 0.3)
                                                           : dvec3(0.95, 0.3, 0.25);
        }
        const dvec3 bust(0.0, 0.065, 0.0), head(0.0, 0.135, 0.0);
        const View views[] = {{"front.png", 0.0, bust, 0.26},
                              {"side.png", 90.0, bust, 0.26},
                              {"three_quarter.png", 40.0, bust, 0.26},
                              {"back.png", 180.0, bust, 0.26},
                              {"head_three_quarter.png", 40.0, head, 0.14}};
        for (const auto& view : views)
            writeFileAtomically(options.previewDir / view.file, renderPng(mesh, scalpColour, view));
        const View clearanceViews[] = {{"clearance_three_quarter.png", 40.0, bust, 0.26},
                                       {"clearance_back.png", 200.0, bust, 0.26}};
        for (const auto& view : clearanceViews)
            writeFileAtomically(options.previewDir / view.file, renderPng(mesh, clearanceColour, view));
    }
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    try {
        return run(parseOptions(argc, argv));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_head: %s\n", e.what());
        return 2;
    }
}
