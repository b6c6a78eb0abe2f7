// assets/placement.cpp: closest points on a mesh (a bounding-volume hierarchy of its triangles),
// the roots' distances to the head, and placing a groom: as in the file, in other units, or
// fitted to the scalp (sphere fits of the roots and the cranium, then the roots moved onto the
// surface by iterated closest points), a fitted groom turned to face the way the head faces.
#include "assets/placement.h"

#include "assets/signed_distance.h"
#include "shaders/shared/mesh_sdf.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <tuple>

namespace wisp {

namespace {

// Closest point of triangle abc to p: the shared header's (Ericson, Real-Time Collision Detection,
// 5.1.5), which the mesh's distance field computes on the GPU too.
glm::vec3 closestOnTriangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c)
{
    return glm::vec3(gpu::sdfClosestOnTriangle(p, a, b, c));
}

float boxDistance2(glm::vec3 p, glm::vec3 lo, glm::vec3 hi)
{
    glm::vec3 d = glm::max(glm::max(lo - p, p - hi), glm::vec3(0.0f));
    return glm::dot(d, d);
}

// Solves the n x n system m x = r (row-major, n <= 4) by Gaussian elimination with partial
// pivoting; false when it is singular.
template <size_t N>
bool solve(std::array<std::array<double, N>, N> m, std::array<double, N> r, std::array<double, N>& x)
{
    for (size_t col = 0; col < N; ++col) {
        size_t pivot = col;
        for (size_t row = col + 1; row < N; ++row)
            if (std::abs(m[row][col]) > std::abs(m[pivot][col]))
                pivot = row;
        if (!(std::abs(m[pivot][col]) > 1e-12))
            return false;
        std::swap(m[pivot], m[col]);
        std::swap(r[pivot], r[col]);
        for (size_t row = col + 1; row < N; ++row) {
            double f = m[row][col] / m[col][col];
            for (size_t k = col; k < N; ++k)
                m[row][k] -= f * m[col][k];
            r[row] -= f * r[col];
        }
    }
    for (size_t i = N; i-- > 0;) {
        double s = r[i];
        for (size_t k = i + 1; k < N; ++k)
            s -= m[i][k] * x[k];
        x[i] = s / m[i][i];
    }
    return true;
}

// Eigenvalues (descending) and eigenvectors (columns) of a symmetric 3x3 matrix (Jacobi).
void symmetricEigen(glm::dmat3 a, glm::dvec3& values, glm::dmat3& vectors)
{
    vectors = glm::dmat3(1.0);
    for (int sweep = 0; sweep < 32; ++sweep) {
        double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        if (off < 1e-30)
            break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                if (std::abs(a[p][q]) < 1e-300)
                    continue;
                double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                glm::dmat3 j(1.0);
                j[p][p] = c;
                j[q][q] = c;
                j[q][p] = s;  // column q, row p
                j[p][q] = -s; // column p, row q
                a = glm::transpose(j) * a * j;
                vectors = vectors * j;
            }
    }
    values = glm::dvec3(a[0][0], a[1][1], a[2][2]);
    for (int i = 0; i < 2; ++i) // sort descending
        for (int k = 0; k < 2 - i; ++k)
            if (values[k] < values[k + 1]) {
                std::swap(values[k], values[k + 1]);
                std::swap(vectors[k], vectors[k + 1]);
            }
}

struct Sphere {
    glm::vec3 centre{0.0f};
    float radius = 0.0f;
    // The points span enough of the sphere to pin its size down: a cap, not a patch or a strip
    // (their second principal extent at least half the radius) and they lie on it (RMS distance
    // under a tenth of the radius).
    bool reliable = false;
};

// The least-squares sphere through points (algebraic fit: |x|^2 = 2 c.x + k), in coordinates
// centred and scaled for conditioning. Points on a plane (a strip of roots along the midline)
// leave the sphere undetermined: the circle in their plane is fitted instead, its centre and
// radius the sphere's. None when the points lie on a line or the fit is degenerate.
std::optional<Sphere> fitSphere(const std::vector<glm::vec3>& points)
{
    if (points.size() < 4)
        return std::nullopt;
    glm::dvec3 mean(0.0);
    for (const glm::vec3& p : points)
        mean += glm::dvec3(p);
    mean /= double(points.size());
    glm::dmat3 cov(0.0);
    for (const glm::vec3& p : points) {
        glm::dvec3 d = glm::dvec3(p) - mean;
        cov += glm::outerProduct(d, d);
    }
    cov /= double(points.size());
    glm::dvec3 values;
    glm::dmat3 axes;
    symmetricEigen(cov, values, axes);
    if (!(values[0] > 0.0) || values[1] < 1e-4 * values[0])
        return std::nullopt; // a line (or a point)
    double scale = std::sqrt(values[0]);
    bool planar = values[2] < 0.02 * values[0];
    Sphere out;
    if (!planar) {
        std::array<std::array<double, 4>, 4> m{};
        std::array<double, 4> r{}, x{};
        for (const glm::vec3& p : points) {
            glm::dvec3 q = (glm::dvec3(p) - mean) / scale;
            std::array<double, 4> row{2.0 * q.x, 2.0 * q.y, 2.0 * q.z, 1.0};
            double rhs = glm::dot(q, q);
            for (size_t i = 0; i < 4; ++i) {
                for (size_t k = 0; k < 4; ++k)
                    m[i][k] += row[i] * row[k];
                r[i] += row[i] * rhs;
            }
        }
        if (!solve<4>(m, r, x))
            return std::nullopt;
        glm::dvec3 c(x[0], x[1], x[2]);
        double r2 = x[3] + glm::dot(c, c);
        if (!(r2 > 0.0))
            return std::nullopt;
        out.centre = glm::vec3(mean + c * scale);
        out.radius = float(std::sqrt(r2) * scale);
    } else {
        glm::dvec3 e1 = axes[0], e2 = axes[1];
        std::array<std::array<double, 3>, 3> m{};
        std::array<double, 3> r{}, x{};
        for (const glm::vec3& p : points) {
            glm::dvec3 q = (glm::dvec3(p) - mean) / scale;
            double u = glm::dot(q, e1), v = glm::dot(q, e2);
            std::array<double, 3> row{2.0 * u, 2.0 * v, 1.0};
            double rhs = u * u + v * v;
            for (size_t i = 0; i < 3; ++i) {
                for (size_t k = 0; k < 3; ++k)
                    m[i][k] += row[i] * row[k];
                r[i] += row[i] * rhs;
            }
        }
        if (!solve<3>(m, r, x))
            return std::nullopt;
        double r2 = x[2] + x[0] * x[0] + x[1] * x[1];
        if (!(r2 > 0.0))
            return std::nullopt;
        out.centre = glm::vec3(mean + (x[0] * e1 + x[1] * e2) * scale);
        out.radius = float(std::sqrt(r2) * scale);
    }
    // A nearly flat patch fits a sphere far larger than itself: no curvature to match.
    if (!std::isfinite(out.radius) || out.radius > 20.0f * float(scale))
        return std::nullopt;
    double residual = 0.0;
    for (const glm::vec3& p : points) {
        double d = glm::length(glm::dvec3(p) - glm::dvec3(out.centre)) - double(out.radius);
        residual += d * d;
    }
    residual = std::sqrt(residual / double(points.size()));
    out.reliable =
        !planar && 2.0 * std::sqrt(values[1]) >= 0.5 * double(out.radius) && residual < 0.1 * double(out.radius);
    return out;
}

// The axis fixes of a placement (mirror, then z-up to y-up), without scale or offset.
glm::vec3 orient(const HairPlacement& p, glm::vec3 v)
{
    HairPlacement axesOnly = p;
    axesOnly.scale = 1.0f;
    axesOnly.offset = glm::vec3(0.0f);
    return applyPlacement(axesOnly, v);
}

// Up to `most` of the roots, evenly spaced in the list (deterministic).
std::vector<glm::vec3> subsample(const std::vector<glm::vec3>& roots, size_t most)
{
    if (roots.size() <= most)
        return roots;
    std::vector<glm::vec3> out;
    out.reserve(most);
    for (size_t k = 0; k < most; ++k)
        out.push_back(roots[k * roots.size() / most]);
    return out;
}

std::vector<glm::vec3> placed(const HairPlacement& p, const std::vector<glm::vec3>& roots)
{
    std::vector<glm::vec3> out;
    out.reserve(roots.size());
    for (const glm::vec3& r : roots)
        out.push_back(applyPlacement(p, r));
    return out;
}

// Moves the placement's offset so that the roots settle onto the surface: iterated closest points,
// translation only, each step by the mean move of the nearest 70% (the rest may belong elsewhere).
void settleOnSurface(HairPlacement& p, const std::vector<glm::vec3>& roots, const MeshDistance& head)
{
    std::vector<std::pair<float, glm::vec3>> moves(roots.size());
    for (int iteration = 0; iteration < 12; ++iteration) {
        for (size_t k = 0; k < roots.size(); ++k) {
            glm::vec3 q = applyPlacement(p, roots[k]);
            MeshDistance::Closest c = head.closest(q);
            moves[k] = {c.distance, c.point - q};
        }
        size_t keep = std::max<size_t>(1, moves.size() * 7 / 10);
        std::nth_element(moves.begin(), moves.begin() + std::ptrdiff_t(keep - 1), moves.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        glm::vec3 mean(0.0f);
        for (size_t k = 0; k < keep; ++k)
            mean += moves[k].second;
        p.offset += mean / float(keep);
    }
}

// Whether placement a fits the roots better than b: more of them on the surface, then nearer. A
// placement that turns the format's up axis must do clearly better (a tenth more of the roots on
// the surface): a groom of another head fits imperfectly either way, and the format says which
// way is up.
bool better(const RootFit& a, bool aTurned, const RootFit& b, bool bTurned)
{
    float margin = aTurned == bTurned ? 0.0f : aTurned ? 0.1f : -0.1f;
    if (std::abs(a.onSurface - (b.onSurface + margin)) > 1e-6f)
        return a.onSurface > b.onSurface + margin;
    return a.median < b.median;
}

std::string number(float v)
{
    char text[32];
    std::snprintf(text, sizeof(text), "%.4g", double(v));
    return text;
}

std::string percent(float share)
{
    char text[32];
    std::snprintf(text, sizeof(text), "%.3g%%", double(100.0f * share));
    return text;
}

const char* frontName(GroomPlacement::Front f)
{
    switch (f) {
    case GroomPlacement::Front::AsPlaced:
        return "as_placed";
    case GroomPlacement::Front::Roots:
        return "roots";
    case GroomPlacement::Front::Face:
        return "face";
    case GroomPlacement::Front::LongStrands:
        return "long_strands";
    case GroomPlacement::Front::Ambiguous:
        break;
    }
    return "ambiguous";
}

} // namespace

HeadRegion headRegion(const Mesh& mesh)
{
    Bounds b = mesh.bounds();
    HeadRegion r{b.max.y, b.min.y};
    constexpr int kSlices = 48;
    float height = b.size().y;
    if (!(height > 0.0f))
        return r;
    std::array<float, kSlices> lo, hi;
    lo.fill(INFINITY);
    hi.fill(-INFINITY);
    for (const glm::vec3& v : mesh.positions) {
        int k = std::clamp(int((b.max.y - v.y) / height * kSlices), 0, kSlices - 1); // 0: the top slice
        lo[size_t(k)] = std::min(lo[size_t(k)], v.x);
        hi[size_t(k)] = std::max(hi[size_t(k)], v.x);
    }
    auto width = [&](int k) { return hi[size_t(k)] >= lo[size_t(k)] ? hi[size_t(k)] - lo[size_t(k)] : 0.0f; };
    // From the top down: the skull widens to its widest; once a slice is clearly narrower (the jaw,
    // the neck) the narrowest slice follows, until the width passes the skull's by far (the
    // shoulders). That narrowest slice is the neck.
    int widest = 0, neck = -1, k = 0;
    bool shoulders = false;
    for (; k < kSlices && width(k) >= 0.85f * width(widest); ++k)
        widest = width(k) > width(widest) ? k : widest;
    for (; k < kSlices; ++k) {
        if (width(k) > 1.3f * width(widest)) {
            shoulders = true;
            break;
        }
        if (neck < 0 || width(k) < width(neck))
            neck = k;
    }
    // Without shoulders below (a head alone) the neck is the bottom.
    if (neck >= 0 && shoulders)
        r.neck = b.max.y - (float(neck) + 0.5f) / kSlices * height;
    return r;
}

// ---- MeshDistance ---------------------------------------------------------------------------------

MeshDistance::MeshDistance(const Mesh& mesh) : mesh_(mesh)
{
    order_.resize(mesh.triangleCount());
    std::iota(order_.begin(), order_.end(), 0u);
    init();
}

MeshDistance::MeshDistance(const Mesh& mesh, std::vector<uint32_t> triangles)
    : mesh_(mesh), order_(std::move(triangles))
{
    init();
}

void MeshDistance::init()
{
    uint32_t triangles = uint32_t(order_.size());
    std::vector<glm::vec3> centroids(mesh_.triangleCount());
    for (uint32_t t : order_)
        centroids[t] = (mesh_.positions[mesh_.indices[3 * t]] + mesh_.positions[mesh_.indices[3 * t + 1]] +
                        mesh_.positions[mesh_.indices[3 * t + 2]]) /
                       3.0f;
    nodes_.reserve(2 * size_t(triangles) / 2 + 1);
    if (triangles > 0)
        build(0, triangles, centroids);
}

uint32_t MeshDistance::build(uint32_t begin, uint32_t end, std::vector<glm::vec3>& centroids)
{
    uint32_t index = uint32_t(nodes_.size());
    nodes_.push_back({});
    glm::vec3 lo(INFINITY), hi(-INFINITY), clo(INFINITY), chi(-INFINITY);
    for (uint32_t k = begin; k < end; ++k) {
        uint32_t t = order_[k];
        for (int c = 0; c < 3; ++c) {
            lo = glm::min(lo, mesh_.positions[mesh_.indices[3 * t + c]]);
            hi = glm::max(hi, mesh_.positions[mesh_.indices[3 * t + c]]);
        }
        clo = glm::min(clo, centroids[t]);
        chi = glm::max(chi, centroids[t]);
    }
    nodes_[index].lo = lo;
    nodes_[index].hi = hi;
    constexpr uint32_t kLeaf = 4;
    glm::vec3 extent = chi - clo;
    if (end - begin <= kLeaf || !(std::max({extent.x, extent.y, extent.z}) > 0.0f)) {
        nodes_[index].first = begin;
        nodes_[index].count = end - begin;
        return index;
    }
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    uint32_t middle = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                     [&](uint32_t a, uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
    build(begin, middle, centroids);
    uint32_t right = build(middle, end, centroids);
    nodes_[index].first = right;
    nodes_[index].count = 0;
    return index;
}

MeshDistance::Closest MeshDistance::closest(glm::vec3 p) const
{
    Closest best{p, INFINITY};
    if (nodes_.empty())
        return best;
    float best2 = INFINITY;
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (boxDistance2(p, node.lo, node.hi) >= best2)
            continue;
        if (node.count > 0) {
            for (uint32_t k = node.first; k < node.first + node.count; ++k) {
                uint32_t t = order_[k];
                glm::vec3 q = closestOnTriangle(p, mesh_.positions[mesh_.indices[3 * t]],
                                                mesh_.positions[mesh_.indices[3 * t + 1]],
                                                mesh_.positions[mesh_.indices[3 * t + 2]]);
                float d2 = glm::dot(q - p, q - p);
                if (d2 < best2) {
                    best2 = d2;
                    best.point = q;
                    best.triangle = t;
                }
            }
            continue;
        }
        uint32_t left = uint32_t(&node - nodes_.data()) + 1, right = node.first;
        float dl = boxDistance2(p, nodes_[left].lo, nodes_[left].hi);
        float dr = boxDistance2(p, nodes_[right].lo, nodes_[right].hi);
        if (top + 2 > 64)
            continue;  // deeper than any tree of 2^32 triangles: cannot happen
        if (dl < dr) { // the nearer child is popped first
            stack[top++] = right;
            stack[top++] = left;
        } else {
            stack[top++] = left;
            stack[top++] = right;
        }
    }
    best.distance = std::sqrt(best2);
    return best;
}

template <typename Visit> void MeshDistance::within(glm::vec3 p, float radius2, Visit&& visit) const
{
    if (nodes_.empty())
        return;
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (boxDistance2(p, node.lo, node.hi) > radius2)
            continue;
        if (node.count > 0) {
            for (uint32_t k = node.first; k < node.first + node.count; ++k)
                visit(order_[k]);
            continue;
        }
        if (top + 2 > 64)
            continue;
        stack[top++] = uint32_t(&node - nodes_.data()) + 1;
        stack[top++] = node.first;
    }
}

bool MeshDistance::hits(glm::vec3 origin, glm::vec3 direction, float length) const
{
    if (nodes_.empty())
        return false;
    glm::vec3 inverse = 1.0f / direction; // infinities where a component is 0: the slabs still work
    auto entersBox = [&](const Node& node) {
        glm::vec3 t0 = (node.lo - origin) * inverse, t1 = (node.hi - origin) * inverse;
        glm::vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
        float enter = std::max({near.x, near.y, near.z, 0.0f}), leave = std::min({far.x, far.y, far.z, length});
        return !(enter > leave); // NaN (a 0 * infinity on a slab's face) counts as a crossing
    };
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (!entersBox(node))
            continue;
        if (node.count > 0) {
            for (uint32_t k = node.first; k < node.first + node.count; ++k) {
                uint32_t t = order_[k];
                glm::vec3 a = mesh_.positions[mesh_.indices[3 * t]], b = mesh_.positions[mesh_.indices[3 * t + 1]],
                          c = mesh_.positions[mesh_.indices[3 * t + 2]];
                glm::vec3 e1 = b - a, e2 = c - a, h = glm::cross(direction, e2);
                float det = glm::dot(e1, h);
                if (!(std::abs(det) > 0.0f))
                    continue;
                glm::vec3 s = (origin - a) / det;
                float u = glm::dot(s, h);
                if (u < 0.0f || u > 1.0f)
                    continue;
                glm::vec3 q = glm::cross(s, e1);
                float v = glm::dot(direction, q);
                if (v < 0.0f || u + v > 1.0f)
                    continue;
                float along = glm::dot(e2, q);
                if (along > 0.0f && along <= length)
                    return true;
            }
            continue;
        }
        if (top + 2 > 64)
            continue;
        stack[top++] = uint32_t(&node - nodes_.data()) + 1;
        stack[top++] = node.first;
    }
    return false;
}

glm::vec3 MeshDistance::pseudonormal(glm::vec3 q, float tolerance) const
{
    glm::vec3 sum(0.0f);
    within(q, tolerance * tolerance, [&](uint32_t t) {
        glm::vec3 v[3] = {mesh_.positions[mesh_.indices[3 * t]], mesh_.positions[mesh_.indices[3 * t + 1]],
                          mesh_.positions[mesh_.indices[3 * t + 2]]};
        if (glm::length(closestOnTriangle(q, v[0], v[1], v[2]) - q) > tolerance)
            return;
        glm::vec3 face = glm::cross(v[1] - v[0], v[2] - v[0]);
        float length = glm::length(face);
        if (!(length > 0.0f))
            return;
        float angle = 3.14159265f;
        for (int k = 0; k < 3; ++k)
            if (glm::length(q - v[k]) <= tolerance) {
                glm::vec3 e1 = v[(k + 1) % 3] - v[k], e2 = v[(k + 2) % 3] - v[k];
                float l1 = glm::length(e1), l2 = glm::length(e2);
                angle =
                    l1 > 0.0f && l2 > 0.0f ? std::acos(std::clamp(glm::dot(e1, e2) / (l1 * l2), -1.0f, 1.0f)) : 0.0f;
                break;
            }
        sum += angle * face / length;
    });
    return sum;
}

namespace {

// How far apart two closest points may be and be one: a float's rounding at their coordinates,
// and a ten-thousandth of the distance they were found from.
float samePoint(glm::vec3 q, float distance)
{
    return 1e-4f * distance +
           16.0f * std::numeric_limits<float>::epsilon() * (std::abs(q.x) + std::abs(q.y) + std::abs(q.z));
}

} // namespace

glm::vec3 MeshDistance::normal(const Closest& c) const
{
    if (c.triangle == UINT32_MAX)
        return glm::vec3(0.0f, 1.0f, 0.0f);
    glm::vec3 n = pseudonormal(c.point, samePoint(c.point, 0.0f));
    if (!(glm::length(n) > 0.0f)) // a triangle of no area: its corners' normals
        n = mesh_.normals[mesh_.indices[3 * c.triangle]] + mesh_.normals[mesh_.indices[3 * c.triangle + 1]] +
            mesh_.normals[mesh_.indices[3 * c.triangle + 2]];
    float length = glm::length(n);
    return length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
}

// ---- Roots against the head ------------------------------------------------------------------------

RootFit measureRoots(const std::vector<glm::vec3>& roots, const MeshDistance& head, float headDiagonal)
{
    RootFit fit;
    fit.roots = roots.size();
    if (roots.empty() || !(headDiagonal > 0.0f))
        return fit;
    std::vector<float> d;
    d.reserve(roots.size());
    size_t on = 0;
    for (const glm::vec3& r : roots) {
        float f = head.closest(r).distance / headDiagonal;
        d.push_back(std::isfinite(f) ? f : INFINITY);
        on += d.back() <= kRootOnSurface ? 1 : 0;
    }
    std::sort(d.begin(), d.end());
    fit.median = d[d.size() / 2];
    fit.p90 = d[std::min(d.size() - 1, d.size() * 9 / 10)];
    fit.max = d.back();
    fit.onSurface = float(on) / float(roots.size());
    return fit;
}

// ---- Placing a groom ---------------------------------------------------------------------------------

std::string GroomPlacement::describe() const
{
    std::string how = method == Method::File     ? "as in the file"
                      : method == Method::Units  ? "in the head's units"
                      : method == Method::Fitted ? "fitted to the scalp"
                                                 : "as given";
    std::string text = how + ": scale " + number(placement.scale) + ", offset (" + number(placement.offset.x) + ", " +
                       number(placement.offset.y) + ", " + number(placement.offset.z) + ")";
    text += placement.zUpToYUp ? ", z-up turned y-up" : ", y-up";
    if (placement.mirrorZ)
        text += ", z mirrored";
    if (placement.halfTurn)
        text += ", turned round";
    if (front == Front::Face)
        text += " (its front by the hair over the face)";
    else if (front == Front::LongStrands)
        text += " (its front by its long strands)";
    return text;
}

std::string GroomPlacement::ambiguity() const
{
    if (front != Front::Ambiguous || !turned || !turnedFit)
        return "";
    return "which way round the groom goes is ambiguous: as placed and turned round, " + percent(fit.onSurface) +
           " and " + percent(turnedFit->onSurface) + " of its roots lie on the head, " + percent(facing.overFace) +
           " and " + percent(turned->overFace) + " of its points hang over the face, and its long strands grow " +
           "on neither side (" + number(facing.longAtBack) + " of -1 front .. 1 back); kept " +
           (placement.halfTurn ? "turned round" : "as the file faces") + ": --hair-half-turn " +
           (placement.halfTurn ? "false" : "true") + " turns it the other way (in a scene: hair's half_turn)";
}

nlohmann::json GroomPlacement::toJson() const
{
    const char* how = method == Method::File     ? "file"
                      : method == Method::Units  ? "units"
                      : method == Method::Fitted ? "fitted"
                                                 : "given";
    return {{"method", how},
            {"scale", placement.scale},
            {"offset", {placement.offset.x, placement.offset.y, placement.offset.z}},
            {"up_axis", placement.zUpToYUp ? "z" : "y"},
            {"mirror_z", placement.mirrorZ},
            {"half_turn", placement.halfTurn},
            {"front",
             {{"chosen_by", frontName(front)},
              {"over_face", facing.overFace},
              {"long_at_back", facing.longAtBack},
              {"turned_round", turned && turnedFit ? nlohmann::json{{"over_face", turned->overFace},
                                                                    {"long_at_back", turned->longAtBack},
                                                                    {"roots_on_surface", turnedFit->onSurface}}
                                                   : nlohmann::json(nullptr)}}},
            {"roots",
             {{"count", fit.roots},
              {"median", fit.median},
              {"p90", fit.p90},
              {"max", fit.max},
              {"on_surface", fit.onSurface},
              {"on_surface_within", kRootOnSurface},
              {"unit", "fraction of the head's bounding-box diagonal"}}}};
}

GroomFacing measureFacing(const std::vector<std::vector<glm::vec3>>& strands, const HairPlacement& placement,
                          const Mesh& head, glm::vec3 headFront)
{
    GroomFacing out;
    glm::vec3 front(headFront.x, 0.0f, headFront.z);
    front = glm::length(front) > 0.0f ? glm::normalize(front) : glm::vec3(0.0f, 0.0f, 1.0f);
    glm::vec3 side = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), front);
    // The face: the head between the chin and the brow (a tenth to seven tenths of the way from
    // the neck to the top), its reach forward and its width from the middle of that band.
    HeadRegion region = headRegion(head);
    float height = region.top - region.neck;
    float low = region.neck + 0.1f * height, high = region.neck + 0.7f * height;
    float forwardLo = INFINITY, forwardHi = -INFINITY, sideLo = INFINITY, sideHi = -INFINITY;
    for (const glm::vec3& v : head.positions)
        if (v.y >= low && v.y <= high) {
            forwardLo = std::min(forwardLo, glm::dot(v, front));
            forwardHi = std::max(forwardHi, glm::dot(v, front));
            sideLo = std::min(sideLo, glm::dot(v, side));
            sideHi = std::max(sideHi, glm::dot(v, side));
        }
    if (!(forwardHi > forwardLo) || strands.empty())
        return out;
    float middle = 0.5f * (forwardLo + forwardHi), reach = 0.5f * (forwardHi - forwardLo);
    float across = 0.5f * (sideLo + sideHi), halfWidth = 0.5f * (sideHi - sideLo);

    // Points over the face: in the band, in front of six tenths of its reach, within half its width.
    size_t points = 0, over = 0;
    std::vector<float> lengths, depth; // per strand: its length, its root's place along the front
    for (const std::vector<glm::vec3>& strand : strands) {
        if (strand.empty())
            continue;
        float length = 0.0f;
        glm::vec3 previous = applyPlacement(placement, strand.front());
        for (const glm::vec3& raw : strand) {
            glm::vec3 q = applyPlacement(placement, raw);
            length += glm::length(q - previous);
            previous = q;
            ++points;
            over += q.y >= low && q.y <= high && glm::dot(q, front) - middle > 0.6f * reach &&
                            std::abs(glm::dot(q, side) - across) < 0.5f * halfWidth
                        ? 1
                        : 0;
        }
        lengths.push_back(length);
        depth.push_back(glm::dot(applyPlacement(placement, strand.front()), front));
    }
    out.overFace = points > 0 ? float(over) / float(points) : 0.0f;

    // The long strands: their length above or below the mean against where their roots sit along
    // the front, normalized to [-1, 1]; positive when the longer ones grow behind.
    double meanLength = 0.0, meanDepth = 0.0;
    for (size_t k = 0; k < lengths.size(); ++k) {
        meanLength += lengths[k];
        meanDepth += depth[k];
    }
    meanLength /= double(lengths.size());
    meanDepth /= double(lengths.size());
    double sum = 0.0, norm = 0.0;
    for (size_t k = 0; k < lengths.size(); ++k) {
        double dl = lengths[k] - meanLength, dz = depth[k] - meanDepth;
        sum += dl * dz;
        norm += std::abs(dl) * std::abs(dz);
    }
    out.longAtBack = norm > 0.0 ? float(-sum / norm) : 0.0f;
    return out;
}

GroomPlacement placeGroom(const GroomShape& shape, const Bounds& groomBounds, const HairPlacement& defaults,
                          const Mesh& head, const PlacementRequest& request)
{
    const std::vector<glm::vec3>& roots = shape.roots;
    MeshDistance distance(head);
    Bounds headBounds = head.bounds();
    float diagonal = headBounds.diagonal();
    std::vector<glm::vec3> sample = subsample(roots, 1500);
    auto evaluate = [&](const HairPlacement& p) { return measureRoots(placed(p, sample), distance, diagonal); };

    // The power-of-ten scale of units that clearly differ (autoPlacement's rule).
    HairAsset probe;
    probe.strands.push_back({.points = {groomBounds.min, groomBounds.max}});
    float unitScale = autoPlacement(probe, headBounds).scale;

    std::vector<bool> ups =
        request.zUp ? std::vector<bool>{*request.zUp} : std::vector<bool>{defaults.zUpToYUp, !defaults.zUpToYUp};
    std::vector<bool> mirrors =
        request.mirrorZ ? std::vector<bool>{*request.mirrorZ} : std::vector<bool>{defaults.mirrorZ, !defaults.mirrorZ};

    if (request.placesByHand()) {
        GroomPlacement given;
        given.method = GroomPlacement::Method::Given;
        given.placement.scale = request.scale.value_or(unitScale);
        given.placement.offset = request.offset.value_or(glm::vec3(0.0f));
        given.placement.zUpToYUp = ups.front();
        given.placement.mirrorZ = mirrors.front();
        given.placement.halfTurn = request.halfTurn.value_or(false);
        given.fit = measureRoots(placed(given.placement, roots), distance, diagonal);
        given.facing = measureFacing(shape.strands, given.placement, head, shape.headFront);
        return given;
    }

    std::vector<glm::vec3> top;
    HeadRegion region = headRegion(head);
    float cut = region.top - 0.5f * (region.top - region.neck); // the skull above the eyes
    for (const glm::vec3& v : head.positions)
        if (v.y >= cut)
            top.push_back(v);
    std::optional<Sphere> cranium = fitSphere(top);

    // The best placement with or without the half turn and the mirror: as in the file (in the
    // head's units), with either up axis; else fitted to the scalp.
    auto search = [&](bool turn, bool mirror) {
        GroomPlacement best;
        // As in the file (in the head's units): either up axis.
        bool first = true;
        for (bool up : ups) {
            HairPlacement p{
                .scale = unitScale, .offset = glm::vec3(0.0f), .zUpToYUp = up, .mirrorZ = mirror, .halfTurn = turn};
            RootFit fit = evaluate(p);
            if (first || better(fit, up != defaults.zUpToYUp, best.fit, best.placement.zUpToYUp != defaults.zUpToYUp)) {
                best.placement = p;
                best.fit = fit;
                best.method = unitScale == 1.0f ? GroomPlacement::Method::File : GroomPlacement::Method::Units;
                first = false;
            }
        }

        // Fitted to the scalp, each candidate moved onto the surface from where it starts; the first
        // that puts the roots on the head is taken (the format's axes first), else the best. Scales:
        // the units' (a groom made for a head of about the same size), then, where the roots span
        // enough of a sphere to measure it, that sphere's radius onto the cranium's (the cranium: a
        // sphere fitted to the top 30% of the head).
        for (int pass = 0; pass < 2 && !best.fit.onHead(); ++pass) {
            for (bool up : ups) {
                if (best.fit.onHead())
                    break;
                HairPlacement p{
                    .scale = unitScale, .offset = glm::vec3(0.0f), .zUpToYUp = up, .mirrorZ = mirror, .halfTurn = turn};
                std::vector<glm::vec3> oriented;
                oriented.reserve(sample.size());
                for (const glm::vec3& r : sample)
                    oriented.push_back(orient(p, r));
                std::optional<Sphere> groom = fitSphere(oriented);
                bool sphere = cranium && groom && groom->reliable && groom->radius > 0.0f;
                if (pass == 1) {
                    if (!sphere)
                        continue;
                    p.scale = cranium->radius / groom->radius;
                }
                // Where each try starts: the roots' sphere on the cranium's; else (a patch or a strip of
                // roots: the fringe, a hair band) the roots' centre on the cranium's surface above, behind,
                // in front and to either side, and the roots' top on the head's top.
                std::vector<glm::vec3> starts;
                if (sphere) {
                    starts.push_back(cranium->centre - p.scale * groom->centre);
                } else {
                    Bounds rb;
                    rb.min = rb.max = p.scale * oriented.front();
                    for (const glm::vec3& r : oriented) {
                        rb.min = glm::min(rb.min, p.scale * r);
                        rb.max = glm::max(rb.max, p.scale * r);
                    }
                    glm::vec3 headTop(headBounds.center().x, headBounds.max.y, headBounds.center().z);
                    starts.push_back(headTop - glm::vec3(rb.center().x, rb.max.y, rb.center().z));
                    if (cranium)
                        for (glm::vec3 d : {glm::vec3(0, 1, 0), glm::vec3(0, 0, -1), glm::vec3(0, 0, 1),
                                            glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0),
                                            glm::normalize(glm::vec3(0, 1, -1)), glm::normalize(glm::vec3(0, 1, 1))})
                            starts.push_back(cranium->centre + cranium->radius * d - rb.center());
                }
                for (glm::vec3 start : starts) {
                    p.offset = start;
                    settleOnSurface(p, sample, distance);
                    RootFit fit = evaluate(p);
                    if (better(fit, up != defaults.zUpToYUp, best.fit, best.placement.zUpToYUp != defaults.zUpToYUp)) {
                        best.placement = p;
                        best.fit = fit;
                        best.method = GroomPlacement::Method::Fitted;
                    }
                }
            }
        }
        return best;
    };

    // The candidates: each handedness, and (with strands to tell a front from a back) each way
    // round about the up axis, unless the request fixes them. Root distance cannot tell a front
    // from a back (a cranium is nearly symmetric; a mirrored z turns a groom round as well as
    // mirroring it), so the candidates that fit the roots alike (within kFacingRoots of the best)
    // are weighed by the hair over the face, then by the long strands; then the format's
    // handedness, then the file's way round.
    std::vector<bool> turns = request.halfTurn        ? std::vector<bool>{*request.halfTurn}
                              : shape.strands.empty() ? std::vector<bool>{false}
                                                      : std::vector<bool>{false, true};
    struct Candidate {
        GroomPlacement placed;
        GroomFacing facing;
        bool facesBack = false; // turned round, counting a flipped handedness as a turn
    };
    std::vector<Candidate> candidates;
    for (bool t : turns)
        for (bool m : mirrors) {
            Candidate c{.placed = search(t, m), .facing = {}, .facesBack = t != (m != defaults.mirrorZ)};
            c.facing = measureFacing(shape.strands, c.placed.placement, head, shape.headFront);
            candidates.push_back(std::move(c));
        }
    auto fitOrder = [&](const Candidate& a, const Candidate& b) {
        const HairPlacement &pa = a.placed.placement, &pb = b.placed.placement;
        return better(a.placed.fit, pa.zUpToYUp != defaults.zUpToYUp, b.placed.fit, pb.zUpToYUp != defaults.zUpToYUp);
    };
    const Candidate& fittest = *std::min_element(candidates.begin(), candidates.end(), fitOrder);
    using Front = GroomPlacement::Front;
    Front front = turns.size() > 1 ? Front::Ambiguous : Front::AsPlaced;
    std::vector<const Candidate*> alike;
    for (const Candidate& c : candidates) // the up axis is the roots' (the format's unless clearly worse)
        if (c.placed.placement.zUpToYUp == fittest.placed.placement.zUpToYUp &&
            c.placed.fit.onSurface >= fittest.placed.fit.onSurface - kFacingRoots)
            alike.push_back(&c);
    auto bothWays = [&] {
        return std::any_of(alike.begin(), alike.end(), [](const Candidate* c) { return c->facesBack; }) &&
               std::any_of(alike.begin(), alike.end(), [](const Candidate* c) { return !c->facesBack; });
    };
    auto keep = [&](auto&& ok) {
        std::vector<const Candidate*> kept;
        for (const Candidate* c : alike)
            if (ok(*c))
                kept.push_back(c);
        alike = kept;
    };
    if (turns.size() > 1 && !bothWays()) {
        front = Front::Roots;
    } else if (turns.size() > 1) {
        float least = INFINITY, most = 0.0f;
        for (const Candidate* c : alike) {
            least = std::min(least, c->facing.overFace);
            most = std::max(most, c->facing.overFace);
        }
        float bound = std::max(kFacingOverFace, 2.0f * least);
        if (most >= bound) {
            keep([&](const Candidate& c) { return c.facing.overFace < bound; });
            front = bothWays() ? Front::Ambiguous : Front::Face;
        }
        if (front == Front::Ambiguous) {
            float strongest = 0.0f;
            for (const Candidate* c : alike)
                strongest = std::max(strongest, std::abs(c->facing.longAtBack));
            if (strongest >= kFacingLongAtBack) {
                keep([&](const Candidate& c) { return c.facing.longAtBack > 0.0f; });
                front = bothWays() ? Front::Ambiguous : Front::LongStrands;
            }
        }
    }
    // Then the format's handedness, the file's way round, the roots.
    const Candidate* chosen = nullptr;
    for (const Candidate* c : alike) {
        auto rank = [&](const Candidate* x) {
            return std::make_tuple(x->placed.placement.mirrorZ != defaults.mirrorZ, x->placed.placement.halfTurn);
        };
        if (!chosen || rank(c) < rank(chosen) || (rank(c) == rank(chosen) && fitOrder(*c, *chosen)))
            chosen = c;
    }
    GroomPlacement out = chosen->placed;
    out.front = front;
    out.facing = chosen->facing;
    // The best of the other way round, for the figures and the ambiguity's sentence.
    const Candidate* other = nullptr;
    for (const Candidate& c : candidates)
        if (c.facesBack != chosen->facesBack && (!other || fitOrder(c, *other)))
            other = &c;
    if (other) {
        out.turned = other->facing;
        out.turnedFit = measureRoots(placed(other->placed.placement, roots), distance, diagonal);
    }
    out.fit = measureRoots(placed(out.placement, roots), distance, diagonal);
    return out;
}

// ---- Moving a groom onto the scalp --------------------------------------------------------------------

namespace {

// A scalp triangle a root may move onto faces away from the cranium's centre at least this much
// (the cosine of 72 degrees: the sides of the skull, not the back of an ear).
constexpr float kScalpFacing = 0.3f;

// The rotation by `angle` about the unit `axis` (Rodrigues).
glm::dmat3 rotation(glm::dvec3 axis, double angle)
{
    double c = std::cos(angle), s = std::sin(angle);
    glm::dmat3 k(0.0, axis.z, -axis.y, -axis.z, 0.0, axis.x, axis.y, -axis.x, 0.0); // columns: [axis]x
    return glm::dmat3(1.0) + s * k + (1.0 - c) * (k * k);
}

// A unit vector perpendicular to the unit `n`.
glm::dvec3 perpendicular(glm::dvec3 n)
{
    glm::dvec3 other = std::abs(n.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    return glm::normalize(glm::cross(n, other));
}

// The least rotation taking the unit `from` onto the unit `to` (about their common perpendicular):
// a tangent of `from` goes to the tangent of `to` parallel transport gives.
glm::dmat3 leastRotation(glm::dvec3 from, glm::dvec3 to)
{
    glm::dvec3 axis = glm::cross(from, to);
    double s = glm::length(axis), c = glm::dot(from, to);
    if (s < 1e-12)
        return c > 0.0 ? glm::dmat3(1.0) : rotation(perpendicular(from), 3.14159265358979323846);
    return rotation(axis / s, std::atan2(s, c));
}

// Each point moved by `m` about `pivot`, in doubles (so every segment keeps its length to a float's
// rounding), then shifted by `shift`.
std::vector<glm::vec3> moved(const std::vector<glm::vec3>& points, glm::dvec3 pivot, const glm::dmat3& m, glm::dvec3 to,
                             glm::dvec3 shift = glm::dvec3(0.0))
{
    std::vector<glm::vec3> out;
    out.reserve(points.size());
    for (const glm::vec3& p : points)
        out.push_back(glm::vec3(to + m * (glm::dvec3(p) - pivot) + shift));
    return out;
}

// Of the scalp's triangles, those a root may be moved onto: on the head's skin (the connected
// part of the mesh, its vertices joined by position, that holds most of the scalp's area: not a
// hair band, an eye or a collar the rule's plane also cuts), facing away from the cranium's centre
// (not the back of an ear), and seen from outside (the ray from each one's centre along its normal
// meets no other triangle: not under a band or a brim). None left: the scalp as the rule gives it.
std::vector<uint32_t> scalpSurface(const MeshDistance& surface, const Mesh& head, const std::vector<uint32_t>& scalp,
                                   float diagonal)
{
    auto corner = [&](uint32_t t, int k) { return head.positions[head.indices[3 * t + uint32_t(k)]]; };
    // Connected parts: union-find over the vertices, those at one position joined.
    std::vector<uint32_t> parent(head.positions.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t v) {
        while (parent[v] != v)
            v = parent[v] = parent[parent[v]];
        return v;
    };
    auto join = [&](uint32_t a, uint32_t b) { parent[find(a)] = find(b); };
    std::vector<uint32_t> byPosition(head.positions.size());
    std::iota(byPosition.begin(), byPosition.end(), 0u);
    auto key = [&](uint32_t v) {
        const glm::vec3& p = head.positions[v];
        return std::make_tuple(p.x, p.y, p.z);
    };
    std::sort(byPosition.begin(), byPosition.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
    for (size_t k = 1; k < byPosition.size(); ++k)
        if (key(byPosition[k]) == key(byPosition[k - 1]))
            join(byPosition[k], byPosition[k - 1]);
    for (size_t t = 0; t < head.triangleCount(); ++t) {
        join(head.indices[3 * t], head.indices[3 * t + 1]);
        join(head.indices[3 * t], head.indices[3 * t + 2]);
    }
    std::vector<double> area(head.positions.size(), 0.0);
    for (uint32_t t : scalp)
        area[find(head.indices[3 * t])] +=
            0.5 * double(glm::length(glm::cross(corner(t, 1) - corner(t, 0), corner(t, 2) - corner(t, 0))));
    uint32_t skin = uint32_t(std::max_element(area.begin(), area.end()) - area.begin());

    // The cranium's centre: the sphere through the skull above the eyes (as placeGroom fits it),
    // else the scalp's centre.
    HeadRegion region = headRegion(head);
    float cut = region.top - 0.5f * (region.top - region.neck);
    std::vector<glm::vec3> top;
    for (const glm::vec3& v : head.positions)
        if (v.y >= cut)
            top.push_back(v);
    std::optional<Sphere> cranium = fitSphere(top);
    glm::vec3 centre(0.0f);
    if (cranium) {
        centre = cranium->centre;
    } else {
        for (uint32_t t : scalp)
            centre += (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0f;
        centre /= float(std::max<size_t>(scalp.size(), 1));
    }

    std::vector<uint32_t> out;
    out.reserve(scalp.size());
    for (uint32_t t : scalp) {
        if (find(head.indices[3 * t]) != skin)
            continue;
        glm::vec3 a = corner(t, 0), b = corner(t, 1), c = corner(t, 2), middle = (a + b + c) / 3.0f;
        glm::vec3 n = glm::cross(b - a, c - a);
        float length = glm::length(n), away = glm::length(middle - centre);
        if (!(length > 0.0f) || !(away > 0.0f))
            continue;
        n /= length;
        if (glm::dot(n, (middle - centre) / away) < kScalpFacing)
            continue;
        if (!surface.hits(middle + 1e-4f * diagonal * n, n, 2.0f * diagonal))
            out.push_back(t);
    }
    return out.empty() ? scalp : out;
}

} // namespace

std::string GroomTransfer::describe() const
{
    std::string text =
        std::to_string(moved) + " of " + std::to_string(roots) + " roots moved onto the scalp (farther than " +
        percent(beyond) + " of the head's size from its surface after the fit), by median " + percent(median) +
        " and at most " + percent(max) + " of the head's size; " + std::to_string(turned) +
        " strands turned out of the head about their roots, " + std::to_string(lifted) + " lifted along the normal";
    if (lifted > 0)
        text += " (at most " + percent(liftMax) + ")";
    return text;
}

nlohmann::json GroomTransfer::toJson() const
{
    return {{"roots", roots},
            {"moved", moved},
            {"moved_beyond", beyond},
            {"displacement", {{"median", median}, {"max", max}}},
            {"turned", turned},
            {"lifted", lifted},
            {"lift_max", liftMax},
            {"inside_deeper_than", kStrandInside},
            {"unit", "fraction of the head's bounding-box diagonal"}};
}

GroomTransfer transferStrands(std::vector<std::vector<glm::vec3>>& strands, const Mesh& head,
                              const std::vector<uint32_t>& scalp, float beyond, bool keepAllOut,
                              const std::vector<bool>& movable)
{
    GroomTransfer out;
    float diagonal = head.bounds().diagonal();
    if (!(diagonal > 0.0f))
        return out;
    MeshDistance surface(head);
    MeshSignedDistance signedSurface(head);
    std::optional<MeshDistance> onto;
    out.beyond = beyond;
    float near = beyond * diagonal, deep = kStrandInside * diagonal;
    // How deep the deepest vertex past the root lies inside the head (<= deep: none inside), and which.
    auto deepest = [&](const std::vector<glm::vec3>& points, size_t* which = nullptr) {
        float depth = -INFINITY;
        for (size_t i = 1; i < points.size(); ++i) {
            float d = -signedSurface(points[i]);
            if (d > depth) {
                depth = d;
                if (which)
                    *which = i;
            }
        }
        return depth;
    };
    std::vector<float> displacement;
    for (size_t s = 0; s < strands.size(); ++s) {
        std::vector<glm::vec3>& points = strands[s];
        if (points.empty() || (!movable.empty() && !movable[s]))
            continue;
        ++out.roots;
        glm::vec3 root = points.front();
        MeshDistance::Closest from = surface.closest(root);
        bool move = from.distance > near;
        if (move && !onto)
            onto.emplace(head, scalpSurface(surface, head, scalp, diagonal));
        MeshDistance::Closest to = move ? onto->closest(root) : from;
        if (to.triangle == UINT32_MAX)
            continue; // no scalp (the caller refuses before asking), or no surface
        if (!move && !keepAllOut)
            continue;
        glm::dvec3 n1(move ? onto->normal(to) : surface.normal(from)), r1(move ? to.point : root);
        std::vector<glm::vec3> carried = points;
        if (move) {
            carried = moved(points, glm::dvec3(root), leastRotation(glm::dvec3(surface.normal(from)), n1), r1);
            carried.front() = to.point;
        }
        size_t k = 0;
        float depth = deepest(carried, &k);
        if (depth > deep) {
            // The least turn about the root toward the normal, in the plane of the normal and the
            // deepest vertex: sixteen steps up to standing along the normal, then halving the step.
            glm::dvec3 u = glm::dvec3(carried[k]) - r1;
            glm::dvec3 axis = glm::cross(u, n1);
            axis = glm::length(axis) > 1e-12 * glm::length(u) ? glm::normalize(axis) : perpendicular(n1);
            double most = std::acos(std::clamp(glm::dot(glm::normalize(u), n1), -1.0, 1.0));
            auto turned = [&](double angle) { return moved(carried, r1, rotation(axis, angle), r1); };
            std::optional<double> good;
            double bad = 0.0;
            for (int step = 1; step <= 16 && !good; ++step) {
                double angle = most * step / 16.0;
                if (deepest(turned(angle)) <= deep)
                    good = angle;
                else
                    bad = angle;
            }
            if (good) {
                for (int halving = 0; halving < 6; ++halving) {
                    double angle = 0.5 * (bad + *good);
                    (deepest(turned(angle)) <= deep ? *good : bad) = angle;
                }
                carried = turned(*good);
                carried.front() = glm::vec3(r1);
                ++out.turned;
            } else {
                // Lifted along the normal: the depth first, doubled until out, then halving the gap.
                auto lifted = [&](double h) { return moved(carried, r1, glm::dmat3(1.0), r1, h * n1); };
                double low = 0.0, high = double(depth);
                while (deepest(lifted(high)) > deep && high < double(diagonal)) {
                    low = high;
                    high *= 2.0;
                }
                for (int halving = 0; halving < 12; ++halving) {
                    double h = 0.5 * (low + high);
                    (deepest(lifted(h)) <= deep ? high : low) = h;
                }
                carried = lifted(high);
                ++out.lifted;
                out.liftMax = std::max(out.liftMax, float(high) / diagonal);
            }
        }
        if (move)
            displacement.push_back(glm::length(carried.front() - root) / diagonal);
        points = std::move(carried);
    }
    out.moved = displacement.size();
    if (!displacement.empty()) {
        std::sort(displacement.begin(), displacement.end());
        out.median = displacement[displacement.size() / 2];
        out.max = displacement.back();
    }
    return out;
}

} // namespace wisp
