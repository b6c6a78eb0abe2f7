// physics/cpu_solver.cpp: the reference solver. integrateStrand mirrors sim_integrate.comp line
// for line; the grid functions mirror grid_clear/splat/normalize/gather.comp.
#include "physics/cpu_solver.h"

namespace wisp {

using namespace gpu;

std::vector<RestVertex> restVertices(const StrandSet& strands)
{
    std::vector<RestVertex> out(strands.vertexCount());
    uint32_t V = strands.verticesPerStrand;
    for (size_t g = 0; g < out.size(); ++g) {
        out[g].position = strands.rest[g];
        out[g].segmentLength = g % V == 0 ? 0.0f : glm::length(strands.rest[g] - strands.rest[g - 1]);
    }
    return out;
}

CpuSolver::CpuSolver(const StrandSet& strands, const SimSetup& setup, const glm::mat4& headTransform)
    : strands_(strands), setup_(setup), rest_(restVertices(strands)), state_(initialState(strands, headTransform)),
      grid_(setup.params.gridNodeCount), gridVelocity_(setup.params.gridNodeCount)
{
}

void CpuSolver::step(const SimStep& first)
{
    SimStep sub = first;
    for (uint32_t k = 0; k < setup_.substeps; ++k) {
        sub.time = first.time + float(k) * setup_.params.dt;
        for (uint32_t s = 0; s < setup_.params.strandCount; ++s)
            integrateStrand(s, sub);
    }
    gridClear();
    gridSplat(first);
    gridNormalize();
    gridGather(first);
}

void CpuSolver::integrateStrand(uint32_t s, const SimStep& step)
{
    const SimParams& params = setup_.params;
    std::vector<vec4>& positions = state_.positions;
    std::vector<vec4>& velocities = state_.velocities;
    std::vector<vec4>& tangents = state_.tangents;

    auto penalty = [&](vec3 x) {
        vec3 a(0.0f);
        vec3 local = toHeadSpace(step.headTransform, x);
        for (uint32_t c = 0; c < params.colliderCount; ++c) {
            Contact k = ellipsoidContact(params.colliders[c], local, params.collisionMargin);
            if (k.depth > 0.0f)
                a += params.penaltyStiffness * k.depth * (glm::mat3(step.headTransform) * k.normal);
        }
        if (step.sphereRadius > 0.0f) {
            Contact k = sphereContact(step.sphereCenter, step.sphereRadius, x, params.collisionMargin);
            if (k.depth > 0.0f)
                a += params.penaltyStiffness * k.depth * k.normal;
        }
        return a;
    };
    auto pushOut = [&](vec3 p) {
        vec3 local = toHeadSpace(step.headTransform, p);
        for (uint32_t c = 0; c < params.colliderCount; ++c) {
            Contact k = ellipsoidContact(params.colliders[c], local, 0.0f);
            if (k.depth > 0.0f) {
                p += k.depth * (glm::mat3(step.headTransform) * k.normal);
                local = toHeadSpace(step.headTransform, p);
            }
        }
        if (step.sphereRadius > 0.0f) {
            Contact k = sphereContact(step.sphereCenter, step.sphereRadius, p, 0.0f);
            if (k.depth > 0.0f)
                p += k.depth * k.normal;
        }
        return p;
    };

    uint32_t V = params.verticesPerStrand;
    uint32_t base = s * V;
    StrandInfo info = strands_.strands[s];
    SimPart part = params.parts[info.part];
    float dt = params.dt;
    mat3 R = mat3(step.headTransform);
    vec3 wind = strandWind(params.wind, params.windFrequency, step.time, info.seed);
    bool finite = true;
    vec3 lastTangent(0.0f);

    vec3 prevX = vec3(positions[base]);
    vec3 prevP = vec3(step.headTransform * vec4(rest_[base].position, 1.0f));
    bool prevPinned = true;
    vec3 prevShift(0.0f);  // see sim_integrate.comp: local shape stays out of the velocity
    mat3 frame = R;
    bool bothEnds = info.pinnedTip != 0u && info.pinnedRoot < V - 1u;

    for (uint32_t i = 1; i < V; ++i) {
        uint32_t g = base + i;
        vec3 x = vec3(positions[g]);
        vec3 v = vec3(velocities[g]);
        RestVertex r = rest_[g];
        vec3 restWorld = vec3(step.headTransform * vec4(r.position, 1.0f));
        vec3 restDir = (r.position - rest_[g - 1].position) / r.segmentLength;
        vec3 targetDir = frame * restDir;
        bool pinned = i < info.pinnedRoot || (info.pinnedTip != 0u && i == V - 1u);

        vec3 p;
        vec3 d(0.0f);
        vec3 shift(0.0f);
        if (pinned) {
            p = restWorld;
        } else {
            vec3 segment = x - prevX;
            float segLen = length(segment);
            vec3 t = segLen > 1e-12f ? segment / segLen : targetDir;
            vec3 a = params.gravity - part.drag * v + windAcceleration(t, wind) + penalty(x);
            p = x + dt * v + dt * dt * a;
            p = mix(p, restWorld, globalShapeWeight(part.globalStiffness, i, V));
            vec3 beforeShape = p;
            p = mix(p, prevP + r.segmentLength * targetDir, part.localStiffness);
            shift = p - beforeShape;
            p = pushOut(p);
            vec3 before = p;
            p = ftlProject(prevP, p, r.segmentLength);
            d = p - before;
        }
        finite = finite && isFinite3(p);

        vec3 prevV = (prevP - prevX - prevShift) / dt;
        if (!prevPinned)
            prevV -= part.ftlDamping * d / dt;
        positions[g - 1] = vec4(prevP, positions[g - 1].w);
        velocities[g - 1] = vec4(prevV, 0.0f);
        vec3 actualDir = normalize(p - prevP);
        tangents[g - 1] = vec4(actualDir, 0.0f);
        lastTangent = actualDir;

        frame = transportFrame(frame, targetDir, actualDir);
        prevX = x;
        prevP = p;
        prevPinned = pinned;
        prevShift = shift;
    }
    positions[base + V - 1] = vec4(prevP, positions[base + V - 1].w);
    velocities[base + V - 1] = vec4((prevP - prevX - prevShift) / dt, 0.0f);
    tangents[base + V - 1] = vec4(lastTangent, 0.0f);

    // Both ends pinned: the strand bends at two vertices so that its end lands on the pinned tip,
    // its three parts moving rigidly (sim.h); a moved vertex keeps no velocity against its move.
    if (bothEnds) {
        auto move = [&](uint32_t i, vec3 p) {
            uint32_t g = base + i;
            velocities[g] = vec4(constrainedVelocity(vec3(velocities[g]), p - vec3(positions[g]), dt), 0.0f);
            positions[g] = vec4(p, positions[g].w);
            finite = finite && isFinite3(p);
        };
        auto at = [&](uint32_t i) { return vec3(positions[base + i]); };
        uint32_t anchor = info.pinnedRoot - 1u;  // the last pinned root vertex
        uint32_t span = V - 1u - anchor;
        vec3 a = at(anchor), tip = at(V - 1u);
        float d = length(tip - a);
        if (span == 2u) {  // one free vertex: where the spheres around a and the tip meet
            move(V - 2u, twoLinkJoint(a, tip, rest_[base + V - 2u].segmentLength, rest_[base + V - 1u].segmentLength, at(V - 2u)));
        } else {
            vec3 end = ftlProject(at(V - 2u), tip, rest_[base + V - 1u].segmentLength);  // where FTL puts the tip
            // The bends: a third and two thirds along, unless their parts cannot reach the tip or
            // one part's chord is tiny (a curled loop's middle: its direction would be rounding);
            // then the pair whose parts reach it with the longest shortest chord (the kernel
            // searches in the same order).
            uint32_t m1 = std::max(anchor + span / 3u, anchor + 1u);
            uint32_t m2 = std::max(anchor + (2u * span) / 3u, m1 + 1u);
            auto shortest = [&](uint32_t i1, uint32_t i2) {
                vec3 q1 = at(i1), q2 = at(i2);
                if (bendTarget(length(tip - q1), length(q1 - a), length(q2 - q1), length(end - q2), d) < 0.0f)
                    return -1.0f;
                return std::min(std::min(length(q1 - a), length(q2 - q1)), length(end - q2));
            };
            float best = shortest(m1, m2);
            if (best < kBendMinChord * length(end - a) / 3.0f)
                for (uint32_t i1 = anchor + 1u; i1 < V - 2u; ++i1)
                    for (uint32_t i2 = i1 + 1u; i2 < V - 1u; ++i2)
                        if (float c = shortest(i1, i2); c > best) {
                            best = c;
                            m1 = i1;
                            m2 = i2;
                        }
            vec3 p1 = at(m1), p2 = at(m2);
            float l1 = length(p1 - a), l2 = length(p2 - p1), l3 = length(end - p2);
            float target12 = bendTarget(length(tip - p1), l1, l2, l3, d);

            if (target12 >= 0.0f && l1 > 1e-12f && l2 > 1e-12f && l3 > 1e-12f) {
                vec3 b1 = twoLinkJoint(a, tip, l1, target12, p1);
                vec3 b2 = twoLinkJoint(b1, tip, l2, l3, p2);
                mat3 r1 = rotationBetween((p1 - a) / l1, normalize(b1 - a));
                mat3 r2 = rotationBetween((p2 - p1) / l2, normalize(b2 - b1));
                mat3 r3 = rotationBetween((end - p2) / l3, normalize(tip - b2));
                for (uint32_t i = m2 + 1u; i < V - 1u; ++i)
                    move(i, b2 + r3 * (at(i) - p2));
                for (uint32_t i = m1 + 1u; i <= m2; ++i)
                    move(i, b1 + r2 * (at(i) - p1));
                for (uint32_t i = info.pinnedRoot; i <= m1; ++i)
                    move(i, a + r1 * (at(i) - a));
            }
        }
        for (uint32_t i = 0; i < V; ++i) {
            uint32_t j = std::min(i + 1u, V - 1u);
            tangents[base + i] = vec4(normalize(at(j) - at(j - 1u)), 0.0f);
        }
    }

    if (!finite) {
        for (uint32_t i = 0; i < V; ++i) {
            positions[base + i] = vec4(vec3(step.headTransform * vec4(rest_[base + i].position, 1.0f)), positions[base + i].w);
            velocities[base + i] = vec4(0.0f);
            uint32_t j = std::min(i + 1u, V - 1u);
            tangents[base + i] = vec4(R * normalize(rest_[base + j].position - rest_[base + j - 1].position), 0.0f);
        }
        state_.nonfiniteResets += 1;
    }
}

void CpuSolver::gridClear()
{
    for (GridNode& n : grid_)
        n = GridNode{vec3(0.0f), 0.0f};
}

void CpuSolver::gridSplat(const SimStep& step)
{
    const SimParams& params = setup_.params;
    for (size_t g = 0; g < state_.positions.size(); ++g) {
        GridCell cell = gridCell(vec3(state_.positions[g]), step.gridOrigin, params.gridCellSize);
        if (!cellInside(cell.base, params.gridResolution))
            continue;
        vec3 v = clampSpeed(vec3(state_.velocities[g]), params.gridMaxSplatSpeed);
        for (uint32_t k = 0; k < 8; ++k) {
            float w = cornerWeight(cell.frac, k);
            uint32_t n = gridIndex(cell.base + cornerOffset(k), params.gridResolution);
            grid_[n].density += w;
            grid_[n].momentum += w * v;
        }
    }
}

void CpuSolver::gridNormalize()
{
    for (size_t n = 0; n < grid_.size(); ++n) {
        const GridNode& node = grid_[n];
        vec3 velocity = node.density > kGridMinDensity ? node.momentum / node.density : vec3(0.0f);
        gridVelocity_[n] = vec4(velocity, node.density);
    }
}

void CpuSolver::gridGather(const SimStep& step)
{
    const SimParams& params = setup_.params;
    for (size_t g = 0; g < state_.positions.size(); ++g) {
        if (state_.positions[g].w == 0.0f)
            continue;
        GridCell cell = gridCell(vec3(state_.positions[g]), step.gridOrigin, params.gridCellSize);
        if (!cellInside(cell.base, params.gridResolution))
            continue;
        GridSample gs = gridSampleZero();
        for (uint32_t k = 0; k < 8; ++k) {
            vec4 node = gridVelocity_[gridIndex(cell.base + cornerOffset(k), params.gridResolution)];
            gs = gridAccumulate(gs, cell.frac, k, vec3(node), node.w);
        }
        vec3 v = gridBlend(vec3(state_.velocities[g]), gs, params.gridFriction, params.gridRepulsion, params.gridCellSize);
        state_.velocities[g] = vec4(v, 0.0f);
    }
}

}  // namespace wisp
