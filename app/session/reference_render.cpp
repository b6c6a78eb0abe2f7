// app/session/reference_render.cpp: the reference of `wisp render`'s frame (see the header): the real-time
// frame drawn once in compute (hair_raster=compute), so its uniforms, its strands' parameters and its
// meshes' material are the frame's; then the strands it drew placed again on the CPU
// (placeStrands: the same shared functions, the same points), the meshes posed, and traced.
#include "app/session/reference_render.h"

#include "app/session/headless.h"
#include "assets/mesh.h"
#include "gpu/frame.h"
#include "physics/gpu_solver.h"
#include "physics/strand_set.h"
#include "renderer/mesh_pass.h"
#include "renderer/renderer.h"

#include <chrono>
#include <cstdio>
#include <stdexcept>

namespace wisp {

namespace {

reference::MeshObject meshObject(const Mesh& m, const std::vector<float>& scalp, uint32_t object)
{
    reference::MeshObject o{.object = object, .vertices = {}, .indices = m.indices};
    o.vertices.reserve(m.positions.size() * gpu::kMeshVertexFloats);
    for (size_t v = 0; v < m.positions.size(); ++v)
        for (float x : {m.positions[v].x, m.positions[v].y, m.positions[v].z, m.normals[v].x, m.normals[v].y,
                        m.normals[v].z, v < scalp.size() ? scalp[v] : 0.0f})
            o.vertices.push_back(x);
    return o;
}

} // namespace

ReferenceFrame prepareReference(const vk::Context& ctx, HairSession& session, RenderSettings settings, uint32_t frames,
                                float fps, const ReferenceOptions& options)
{
    settings.hairRaster = HairRaster::Compute; // the strands traced are the compute path's
    settings.strands.showGuides = false;       // (which draws its meshes in compute too)
    PosedFrame posed(ctx, session, settings, frames, fps);
    renderFrame(ctx, posed.renderer, posed.frame, posed.camera);
    Renderer& renderer = posed.renderer;
    const gpu::FrameParams& params = renderer.frameParams();
    if (!renderer.meshRaster())
        throw std::logic_error("the reference needs the compute meshes' material");
    gpu::MeshRasterPush meshes = renderer.meshRaster()->push();

    gpu::StrandRasterPush push{};
    push.divisions = 1;
    reference::DrawnStrands strands;
    std::vector<float> scalp;
    if (session.hasHair() && renderer.strandRaster()) {
        push = renderer.strandRaster()->cameraPush();
        std::vector<glm::vec3> guides;
        for (const glm::vec4& p : session.solver()->readState().positions)
            guides.push_back(glm::vec3(p));
        strands = reference::placeStrands(push, params, session.solver()->setup().params, guides,
                                          guideTriangles(session.scene().strands));
        scalp = scalpCoverage(session.scene().head.mesh, session.scene().strands);
    }
    Mesh sphere = makeSphereMesh();
    std::vector<reference::MeshObject> objects = {meshObject(session.scene().head.mesh, scalp, gpu::kMeshObjectHead),
                                                  meshObject(sphere, {}, gpu::kMeshObjectSphere),
                                                  meshObject(sphere, {}, gpu::kMeshObjectMarker)};
    ReferenceFrame out;
    out.scene = reference::buildReferenceScene(push, strands, params, meshes, objects);
    out.params = reference::referenceParams(out.scene, params, meshes, options.maxBounces, options.seed);
    return out;
}

ReferenceRender renderReference(const vk::Context& ctx, HairSession& session, RenderSettings settings, uint32_t frames,
                                float fps, const ReferenceOptions& options,
                                const std::function<void(uint32_t, uint32_t, double)>& progress)
{
    ReferenceFrame f = prepareReference(ctx, session, settings, frames, fps, options);
    ReferenceRender out;
    out.segments = f.scene.segments.size();
    out.triangles = f.scene.triangles.size();
    out.nodes = f.scene.bvh.nodes.size();
    ReferenceTracer tracer(ctx, f.scene, f.params);
    auto start = std::chrono::steady_clock::now();
    tracer.render(options.samples, options.perPass, [&](uint32_t done, uint32_t total) {
        if (progress)
            progress(done, total, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    });
    std::vector<glm::vec4> sums = tracer.sums();
    out.rays = tracer.raysCast();
    out.traceSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.picture = resolveReference(sums, f.params.frame, options.samples);
    return out;
}

std::string describeReference(const ReferenceRender& r, const ReferenceOptions& o)
{
    double paths = double(r.picture.width) * r.picture.height * o.samples;
    char line[512];
    std::snprintf(line, sizeof line,
                  "reference: %u samples per pixel at %ux%u in %.2f s (%.3g samples/s, %.3g rays/s); %llu strand "
                  "segments, %llu triangles, %llu hierarchy nodes; sample seed %u",
                  o.samples, r.picture.width, r.picture.height, r.traceSeconds,
                  r.traceSeconds > 0.0 ? paths / r.traceSeconds : 0.0,
                  r.traceSeconds > 0.0 ? double(r.rays) / r.traceSeconds : 0.0,
                  static_cast<unsigned long long>(r.segments), static_cast<unsigned long long>(r.triangles),
                  static_cast<unsigned long long>(r.nodes), o.seed);
    std::string text = line;
    if (r.picture.noiseLevels >= 0.0) {
        std::snprintf(line, sizeof line,
                      "\nnoise: %.2f of 255 levels RMS (half the difference of the even and odd samples' pictures; "
                      "4x the samples halve it)",
                      r.picture.noiseLevels);
        text += line;
    } else {
        text += "\nnoise: not estimated (it takes --spp 2 or more)";
    }
    return text;
}

} // namespace wisp
