// tests/test_strand_raster.cpp: the compute strand renderer on the device. Every kernel against
// its CPU twin (renderer/compute/strand_raster_reference.h) on the same input: the generated strands, the
// pixels' fragments, the resolved pixels, the light's depth and opacity; then the whole path
// against the tessellation path on the same scenes (how much the hair changes each 8 x 8 block
// correlates, and adds up to about the same), determinism, and a fragment buffer that overflows,
// is counted and grows.
#include "app/session/headless.h"
#include "app/settings/hair_source.h"
#include "app/settings/workload.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "physics/gpu_solver.h"
#include "physics/groomed_head.h"
#include "renderer/compute/mesh_raster_reference.h"
#include "renderer/compute/strand_raster.h"
#include "renderer/compute/strand_raster_reference.h"
#include "renderer/render_target.h"
#include "renderer/renderer.h"
#include "small_groomed_head.h"
#include "test_support.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <optional>

using namespace wisp;

namespace {

using Buffer = StrandRaster::Buffer;
struct uvec2Fragment { // as strands.write stores a fragment
    uint32_t depth;    // float bits
    uint32_t color;
    bool operator==(const uvec2Fragment&) const = default;
};
constexpr Buffer kReadBuffers[] = {Buffer::Curves,      Buffer::Vertices,     Buffer::Colors,    Buffer::LightVertices,
                                   Buffer::LightColors, Buffer::Offsets,      Buffer::Fragments, Buffer::Counters,
                                   Buffer::LightDepth,  Buffer::LightOpacity, Buffer::Pieces,    Buffer::Reserved};

// Copies the compute path's buffers, its hair image, the compute meshes' samples (depth and
// triangle, one sample a pixel) and their colour to the host at the end of the frame that made them.
class RasterReadback : public Pass {
public:
    RasterReadback(const vk::Context& ctx, StrandRaster& raster, MeshRaster& meshes, RenderTarget& target)
        : raster_(raster), meshes_(meshes), extent_(target.extent())
    {
        for (Buffer b : kReadBuffers)
            copies_[b] = ctx.createBuffer({.size = raster.buffer(b).size(),
                                           .usage = vk::kTransferDst,
                                           .memory = vk::Memory::Readback,
                                           .name = "test.raster.readback"});
        VkExtent2D e = target.extent();
        color_ = ctx.createBuffer({.size = uint64_t(e.width) * e.height * 8,
                                   .usage = vk::kTransferDst,
                                   .memory = vk::Memory::Readback,
                                   .name = "test.raster.color"});
        depth_ = ctx.createBuffer({.size = uint64_t(e.width) * e.height * 4,
                                   .usage = vk::kTransferDst,
                                   .memory = vk::Memory::Readback,
                                   .name = "test.raster.depth"});
        ids_ = ctx.createBuffer({.size = uint64_t(e.width) * e.height * 4,
                                 .usage = vk::kTransferDst,
                                 .memory = vk::Memory::Readback,
                                 .name = "test.raster.ids"});
        meshColor_ = ctx.createBuffer({.size = uint64_t(e.width) * e.height * 8,
                                       .usage = vk::kTransferDst,
                                       .memory = vk::Memory::Readback,
                                       .name = "test.raster.mesh_color"});
    }
    const char* name() const override { return "test.readback"; }
    void declare(PassIo& io) override
    {
        for (Buffer b : kReadBuffers)
            io.use(raster_.track(b), Access::TransferSrc);
        io.use(raster_.color(), Access::TransferSrc);
        io.use(meshes_.depthSamples(), Access::TransferSrc);
        io.use(meshes_.idSamples(), Access::TransferSrc);
        io.use(meshes_.color(), Access::TransferSrc);
    }
    void record(VkCommandBuffer cmd, FrameContext&) override
    {
        for (Buffer b : kReadBuffers) {
            VkBufferCopy region{0, 0, raster_.buffer(b).size()};
            vkCmdCopyBuffer(cmd, raster_.buffer(b), copies_[b], 1, &region);
        }
        VkExtent2D e = extent_;
        VkBufferImageCopy color{.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                .imageExtent = {e.width, e.height, 1}};
        vkCmdCopyImageToBuffer(cmd, raster_.colorImage().get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, color_, 1,
                               &color);
        vkCmdCopyImageToBuffer(cmd, meshes_.colorImage().get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, meshColor_, 1,
                               &color);
        VkBufferCopy samples{0, 0, uint64_t(e.width) * e.height * 4};
        vkCmdCopyBuffer(cmd, meshes_.depthBuffer(), depth_, 1, &samples);
        vkCmdCopyBuffer(cmd, meshes_.idBuffer(), ids_, 1, &samples);
        vk::transferToHostBarrier(cmd);
    }
    template <typename T> std::vector<T> read(Buffer b, size_t count) const
    {
        std::vector<T> out(count);
        std::memcpy(out.data(), copies_.at(b).mapped(), count * sizeof(T));
        return out;
    }
    // (These two, once the frame is done, may outlive the renderer.)
    std::vector<glm::vec4> color() const { return halfImage(color_); }
    std::vector<glm::vec4> meshColor() const { return halfImage(meshColor_); }
    std::vector<uint32_t> ids() const
    {
        std::vector<uint32_t> out(size_t(extent_.width) * extent_.height);
        std::memcpy(out.data(), ids_.mapped(), out.size() * 4);
        return out;
    }
    std::vector<glm::vec4> halfImage(const vk::Buffer& buffer) const
    {
        VkExtent2D e = extent_;
        std::vector<glm::vec4> out(size_t(e.width) * e.height);
        const uint32_t* words = static_cast<const uint32_t*>(buffer.mapped());
        for (size_t i = 0; i < out.size(); ++i)
            out[i] = glm::vec4(glm::unpackHalf2x16(words[2 * i]), glm::unpackHalf2x16(words[2 * i + 1]));
        return out;
    }
    std::vector<float> depth() const
    {
        VkExtent2D e = extent_;
        std::vector<float> out(size_t(e.width) * e.height);
        std::memcpy(out.data(), depth_.mapped(), out.size() * 4);
        return out;
    }

private:
    StrandRaster& raster_;
    MeshRaster& meshes_;
    VkExtent2D extent_;
    std::map<Buffer, vk::Buffer> copies_;
    vk::Buffer color_, depth_, ids_, meshColor_;
};

// One compute-path frame of the small scene, its buffers read back, with the inputs the twins need.
struct RasterFrame {
    std::unique_ptr<RasterReadback> readback;
    gpu::FrameParams frame{};
    gpu::SimParams sim{};
    gpu::StrandRasterPush camera{}, light{};
    std::vector<glm::vec3> guides;
    std::vector<glm::uvec4> triangles;
    gpu::MeshRasterPush meshes{};
    reference::MeshObject head, sphere; // as the renderer uploaded them
    uint32_t recordedPieces = 1;

    reference::StrandVertices strands(bool fromLight) const
    {
        const gpu::StrandRasterPush& p = fromLight ? light : camera;
        size_t n = size_t(p.guideCount) * p.drawnPerGuide * (p.divisions + 1);
        return {readback->read<glm::vec4>(fromLight ? Buffer::LightVertices : Buffer::Vertices, n),
                readback->read<uint32_t>(fromLight ? Buffer::LightColors : Buffer::Colors, n)};
    }
};

// One frame of the compute path with every buffer read back; `fragmentBudget` > 0 holds the
// fragment buffer to that many (the frame records one piece and one spare).
RasterFrame renderRasterFrame(const vk::Context& ctx, const GroomedHead& scene, RenderSettings s,
                              uint64_t fragmentBudget = 0)
{
    s.hairRaster = HairRaster::Compute;
    s.samples = 1; // the meshes' depth read back as one sample per pixel
    test::HairRenderer hair(ctx, scene, s);
    Renderer& renderer = hair.renderer;
    GpuSolver& solver = hair.solver;
    Frame& frame = hair.frame;
    OrbitCamera camera = hair.camera;
    if (fragmentBudget > 0)
        renderer.strandRaster()->setFragmentCapacity(fragmentBudget);
    FrameContext& fc = frame.begin(renderer.transientImages());
    renderer.prepare(fc, camera, 0.0f);
    RasterFrame out;
    out.recordedPieces = renderer.strandRaster()->recordedPieces();
    out.readback =
        std::make_unique<RasterReadback>(ctx, *renderer.strandRaster(), *renderer.meshRaster(), renderer.target());
    std::vector<Pass*> passes = renderer.passes();
    passes.push_back(out.readback.get());
    frame.run(fc, passes);
    frame.submit(fc);
    frame.waitIdle();
    out.frame = renderer.frameParams();
    out.sim = solver.setup().params;
    out.camera = renderer.strandRaster()->cameraPush();
    out.light = renderer.strandRaster()->lightPush();
    for (const glm::vec4& p : solver.readState().positions)
        out.guides.push_back(glm::vec3(p));
    out.triangles = guideTriangles(scene.strands);
    out.meshes = renderer.meshRaster()->push();
    auto object = [](const Mesh& m, const std::vector<float>& scalp, uint32_t id) {
        reference::MeshObject o{.object = id, .vertices = {}, .indices = m.indices};
        for (size_t v = 0; v < m.positions.size(); ++v)
            for (float x : {m.positions[v].x, m.positions[v].y, m.positions[v].z, m.normals[v].x, m.normals[v].y,
                            m.normals[v].z, v < scalp.size() ? scalp[v] : 0.0f})
                o.vertices.push_back(x);
        return o;
    };
    out.head = object(scene.head.mesh, scalpCoverage(scene.head.mesh, scene.strands), gpu::kMeshObjectHead);
    out.sphere = object(makeSphereMesh(), {}, gpu::kMeshObjectSphere);
    return out;
}

void expectSameStrands(const reference::StrandVertices& gpu, const reference::StrandVertices& cpu, bool colors)
{
    ASSERT_EQ(gpu.positions.size(), cpu.positions.size());
    size_t drawn = 0;
    int worstColor = 0;
    for (size_t i = 0; i < gpu.positions.size(); ++i) {
        glm::vec4 g = gpu.positions[i], c = cpu.positions[i];
        ASSERT_EQ(g.w < 0.0f, c.w < 0.0f) << "vertex " << i;
        if (c.w < 0.0f)
            continue;
        ++drawn;
        ASSERT_NEAR(g.x, c.x, 2e-3f) << "vertex " << i;
        ASSERT_NEAR(g.y, c.y, 2e-3f) << "vertex " << i;
        ASSERT_NEAR(g.z, c.z, 1e-5f) << "vertex " << i;
        ASSERT_NEAR(g.w, c.w, 1e-4f * std::max(1.0f, c.w)) << "vertex " << i;
        glm::uvec4 gc = glm::uvec4(glm::unpackUnorm4x8(gpu.colors[i]) * 255.0f + 0.5f);
        glm::uvec4 cc = glm::uvec4(glm::unpackUnorm4x8(cpu.colors[i]) * 255.0f + 0.5f);
        for (int ch = colors ? 0 : 3; ch < 4; ++ch)
            worstColor = std::max(worstColor, std::abs(int(gc[ch]) - int(cc[ch])));
    }
    EXPECT_GT(drawn, gpu.positions.size() / 2);
    EXPECT_LE(worstColor, 1) << "packed colours and opacities differ by at most their last bit";
}

} // namespace

TEST(StrandRaster, CameraKernelsMatchTheirCpuTwin)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(60);
    for (Interpolation interpolation : {Interpolation::Single, Interpolation::Multi}) {
        for (ShadingModel model : {ShadingModel::Karis, ShadingModel::Kajiya}) {
            SCOPED_TRACE(interpolation == Interpolation::Single ? "single" : "multi");
            SCOPED_TRACE(model == ShadingModel::Karis ? "karis" : "kajiya");
            RenderSettings s = test::smallRenderSettings();
            s.shadows.enabled = false; // the twin shades with the light unoccluded
            s.strands.interpolation = interpolation;
            s.hair.model = model;
            RasterFrame f = renderRasterFrame(ctx, scene, s);

            // strands.curves: each guide's points, as the twin evaluates them
            std::vector<gpu::CurvePoint> curves = reference::guideCurves(f.camera, f.guides);
            std::vector<glm::vec4> gpuCurves = f.readback->read<glm::vec4>(Buffer::Curves, 2 * curves.size());
            float worstCurve = 0.0f;
            for (size_t i = 0; i < curves.size(); ++i) {
                worstCurve = std::max(worstCurve, glm::length(glm::vec3(gpuCurves[2 * i]) - curves[i].position));
                worstCurve = std::max(worstCurve, glm::length(glm::vec3(gpuCurves[2 * i + 1]) - curves[i].tangent));
            }
            EXPECT_GT(curves.size(), 500u);
            EXPECT_LT(worstCurve, 1e-5f);

            // strands.generate
            reference::StrandVertices gpuStrands = f.strands(false);
            expectSameStrands(gpuStrands, reference::generateStrands(f.camera, f.frame, f.sim, f.guides, f.triangles),
                              true);

            // strands.depth, strands.count, the scan and strands.write, from the GPU's own vertices
            reference::SegmentCounts segments;
            std::vector<std::vector<reference::Fragment>> cpu =
                reference::pixelFragments(f.camera, gpuStrands, f.readback->depth(), &segments);
            size_t pixels = cpu.size();
            std::vector<uint32_t> offsets = f.readback->read<uint32_t>(Buffer::Offsets, pixels + 1);
            gpu::RasterCounters counters = f.readback->read<gpu::RasterCounters>(Buffer::Counters, 1)[0];
            EXPECT_EQ(counters.segments, segments.drawn);
            EXPECT_GT(segments.drawn, 1000u);
            // the segments behind the head's coarse depth, skipped: the same ones, and no hair lost
            EXPECT_EQ(counters.hidden, segments.hidden);
            EXPECT_GT(segments.hidden, segments.drawn / 20) << "the hair behind the head";
            EXPECT_EQ(segments.hiddenWithFragments, 0u);
            EXPECT_EQ(counters.fragments, offsets[pixels]);
            EXPECT_EQ(counters.overflow, 0u);
            std::vector<uvec2Fragment> raw = f.readback->read<uvec2Fragment>(Buffer::Fragments, offsets[pixels]);
            std::vector<std::vector<reference::Fragment>> gpuPixels(pixels);
            size_t total = 0, differentCounts = 0, worstColor = 0, most = 0;
            double worstDepth = 0.0;
            for (size_t p = 0; p < pixels; ++p) {
                ASSERT_LE(offsets[p], offsets[p + 1]) << "pixel " << p;
                for (uint32_t i = offsets[p]; i < offsets[p + 1]; ++i)
                    gpuPixels[p].push_back({std::bit_cast<float>(raw[i].depth), raw[i].color});
                total += cpu[p].size();
                most = std::max(most, gpuPixels[p].size());
                if (gpuPixels[p].size() != cpu[p].size()) {
                    ++differentCounts;
                    continue;
                }
                std::vector<reference::Fragment> a = gpuPixels[p], b = cpu[p];
                std::sort(a.begin(), a.end()); // written in any order by the atomics
                std::sort(b.begin(), b.end());
                for (size_t i = 0; i < a.size(); ++i) {
                    worstDepth = std::max(worstDepth, double(std::abs(a[i].depth - b[i].depth)));
                    glm::ivec4 ca = glm::ivec4(glm::unpackUnorm4x8(a[i].color) * 255.0f + 0.5f);
                    glm::ivec4 cb = glm::ivec4(glm::unpackUnorm4x8(b[i].color) * 255.0f + 0.5f);
                    for (int ch = 0; ch < 4; ++ch)
                        worstColor = std::max<size_t>(worstColor, size_t(std::abs(ca[ch] - cb[ch])));
                }
            }
            EXPECT_GT(total, 8000u); // a workload of some size (the default bob at this framing: about 9,900)
            EXPECT_NEAR(double(offsets[pixels]), double(total), 1e-4 * double(total));
            EXPECT_LE(differentCounts, pixels / 10000) << "a coverage on the edge of a threshold, at most";
            EXPECT_LT(worstDepth, 1e-6);
            EXPECT_LE(worstColor, 1u);
            EXPECT_EQ(counters.maxPixel, most);

            // strands.resolve, from the GPU's own fragments: the same pixels; from the twin's: close
            std::vector<glm::vec4> gpu = f.readback->color();
            std::vector<glm::vec4> same = reference::resolvePixels(f.camera, gpuPixels);
            std::vector<glm::vec4> twin = reference::resolvePixels(f.camera, cpu);
            double worstSame = 0.0, worstTwin = 0.0, sumTwin = 0.0;
            size_t hair = 0;
            for (size_t i = 0; i < pixels; ++i) {
                for (int ch = 0; ch < 4; ++ch) {
                    worstSame = std::max(worstSame, double(std::abs(gpu[i][ch] - same[i][ch])));
                    worstTwin = std::max(worstTwin, double(std::abs(gpu[i][ch] - twin[i][ch])));
                    sumTwin += std::abs(gpu[i][ch] - twin[i][ch]);
                }
                hair += twin[i].w > 0.0f ? 1 : 0;
            }
            EXPECT_GT(hair, pixels / 25) << "the hair covers part of the picture";
            EXPECT_LT(worstSame, 2e-3) << "RGBA16F rounding only";
            EXPECT_LT(worstTwin, 0.05) << "a fragment's 8-bit step, or one fragment more or less at an edge";
            EXPECT_LT(sumTwin / double(pixels * 4), 2e-4);
        }
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// The render-time coil (shaders/shared/strands.h coilAt) in strands.generate as in its twin, and it
// moves the drawn strands: about its radius on screen against the same frame without it.
TEST(StrandRaster, TheRenderTimeCoilIsGeneratedAsItsTwinGeneratesIt)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(60);
    RenderSettings s = test::smallRenderSettings();
    s.shadows.enabled = false; // the twin shades with the light unoccluded
    s.strands.divisions = 64;  // the bob's 20 to 30 cm: 8 to 12 turns at 40 a metre, 5 points a turn or more
    RasterFrame straight = renderRasterFrame(ctx, scene, s);
    s.strands.coilRadiusMetres = 0.003f;
    s.strands.coilTurnsPerMetre = 40.0f;
    RasterFrame coiled = renderRasterFrame(ctx, scene, s);
    EXPECT_GT(coiled.camera.coilRadius, 0.0f);
    reference::StrandVertices gpuStrands = coiled.strands(false);
    expectSameStrands(
        gpuStrands,
        reference::generateStrands(coiled.camera, coiled.frame, coiled.sim, coiled.guides, coiled.triangles), true);
    reference::StrandVertices before = straight.strands(false);
    ASSERT_EQ(before.positions.size(), gpuStrands.positions.size());
    // 3 mm at this framing (about 4 mm a pixel: the bust's 0.6 m in 150 rows) is 0.75 pixels across
    // the view, less where the helix turns along it.
    double moved = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < before.positions.size(); ++i)
        if (before.positions[i].w > 0.0f && gpuStrands.positions[i].w > 0.0f) {
            moved += glm::length(glm::vec2(gpuStrands.positions[i]) - glm::vec2(before.positions[i]));
            ++count;
        }
    ASSERT_GT(count, 1000u);
    EXPECT_GT(moved / double(count), 0.25) << "pixels, on average";
    EXPECT_LT(moved / double(count), 1.5);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// Drawn strands of their own lengths (strand_length_jitter, shaders/shared/strands.h
// strandLengthFraction) in strands.generate as in its twin: each strand's root where it was, its
// points along the first 1 - cut of its guide (between the guide's samples: curveBetweenSamples),
// and fewer fragments for the shorter strands.
TEST(StrandRaster, StrandsOfTheirOwnLengthsAreGeneratedAsTheTwinGeneratesThem)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(60);
    RenderSettings s = test::smallRenderSettings();
    s.shadows.enabled = false; // the twin shades with the light unoccluded
    s.strands.lengthJitter = 0.0f;
    RasterFrame whole = renderRasterFrame(ctx, scene, s);
    s.strands.lengthJitter = 0.5f;
    RasterFrame trimmed = renderRasterFrame(ctx, scene, s);
    EXPECT_EQ(whole.frame.strandLengthJitter, 0.0f);
    EXPECT_EQ(trimmed.frame.strandLengthJitter, 0.5f);
    reference::StrandVertices gpuStrands = trimmed.strands(false);
    expectSameStrands(
        gpuStrands,
        reference::generateStrands(trimmed.camera, trimmed.frame, trimmed.sim, trimmed.guides, trimmed.triangles),
        true);
    reference::StrandVertices before = whole.strands(false);
    ASSERT_EQ(before.positions.size(), gpuStrands.positions.size());
    // In world space (the twin's placeStrands, which the path tracer draws): each strand's length is
    // its fraction of the whole strand's, its root the same point.
    reference::DrawnStrands a =
        reference::placeStrands(whole.camera, whole.frame, whole.sim, whole.guides, whole.triangles);
    reference::DrawnStrands b =
        reference::placeStrands(trimmed.camera, trimmed.frame, trimmed.sim, trimmed.guides, trimmed.triangles);
    uint32_t perStrand = trimmed.camera.divisions + 1;
    size_t strands = a.positions.size() / perStrand;
    ASSERT_GE(strands, 480u); // 60 guides x 8
    double ratios = 0.0;
    for (size_t k = 0; k < strands; ++k) {
        uint32_t guide = uint32_t(k / trimmed.camera.drawnPerGuide),
                 sIndex = uint32_t(k % trimmed.camera.drawnPerGuide);
        float fraction = gpu::strandLengthFraction(guide, sIndex, 0.5f);
        ASSERT_GE(fraction, 0.5f);
        ASSERT_EQ(a.positions[k * perStrand], b.positions[k * perStrand]) << "strand " << k << "'s root";
        float la = 0.0f, lb = 0.0f;
        for (uint32_t i = 0; i + 1 < perStrand; ++i) {
            la += glm::length(a.positions[k * perStrand + i + 1] - a.positions[k * perStrand + i]);
            lb += glm::length(b.positions[k * perStrand + i + 1] - b.positions[k * perStrand + i]);
        }
        // Within a few percent: the clump disc and the deviations follow the guide's t, not its length.
        EXPECT_NEAR(lb / la, fraction, 0.05f) << "strand " << k;
        ratios += double(lb / la);
    }
    EXPECT_NEAR(ratios / double(strands), 0.75, 0.02) << "the mean cut is half the jitter";
    gpu::RasterCounters c0 = whole.readback->read<gpu::RasterCounters>(Buffer::Counters, 1)[0];
    gpu::RasterCounters c1 = trimmed.readback->read<gpu::RasterCounters>(Buffer::Counters, 1)[0];
    EXPECT_LT(double(c1.fragments), 0.9 * double(c0.fragments)) << "shorter strands draw fewer fragments";
    EXPECT_GT(double(c1.fragments), 0.5 * double(c0.fragments));
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(StrandRaster, ThePiecesKernelMatchesItsCpuTwin)
{
    // strands.pieces from the GPU's own scan, with the buffer held to a quarter of the frame's
    // fragments (two pieces recorded of the five it needs) and unbounded (one piece and a spare).
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(60);
    RenderSettings s = test::smallRenderSettings();
    s.shadows.enabled = false;
    RasterFrame whole = renderRasterFrame(ctx, scene, s);
    gpu::RasterCounters wholeCounters = whole.readback->read<gpu::RasterCounters>(Buffer::Counters, 1)[0];
    ASSERT_GT(wholeCounters.fragments, 4000u);
    for (uint64_t budget : {uint64_t(0), uint64_t(wholeCounters.fragments / 4)}) {
        SCOPED_TRACE("budget " + std::to_string(budget));
        RasterFrame f = budget > 0 ? renderRasterFrame(ctx, scene, s, budget) : std::move(whole);
        size_t pixels = size_t(f.camera.targetWidth) * f.camera.targetHeight;
        std::vector<uint32_t> offsets = f.readback->read<uint32_t>(Buffer::Offsets, pixels + 1);
        gpu::RasterCounters c = f.readback->read<gpu::RasterCounters>(Buffer::Counters, 1)[0];
        EXPECT_EQ(c.fragments, offsets[pixels]);
        EXPECT_EQ(c.stride, gpu::rasterPieceStride(c.fragments, c.capacity, c.maxPixel));
        EXPECT_EQ(c.pieces, gpu::rasterPieces(c.fragments, c.stride));
        EXPECT_EQ(c.pieces >= 5u, budget > 0) << c.pieces;
        EXPECT_EQ(c.pieces == 1u, budget == 0) << c.pieces;
        ASSERT_EQ(f.recordedPieces, 2u);
        uint32_t notDrawn = 0;
        std::vector<gpu::RasterPiece> cpu = reference::framePieces(f.camera, offsets, c, f.recordedPieces, &notDrawn);
        std::vector<gpu::RasterPiece> gpu = f.readback->read<gpu::RasterPiece>(Buffer::Pieces, f.recordedPieces);
        auto text = [](const gpu::RasterPiece& r) {
            const uint32_t* w = reinterpret_cast<const uint32_t*>(&r);
            std::string t;
            for (size_t i = 0; i < sizeof(r) / 4; ++i)
                t += std::to_string(w[i]) + " ";
            return t;
        };
        for (uint32_t p = 0; p < f.recordedPieces; ++p)
            EXPECT_EQ(text(cpu[p]), text(gpu[p])) << "piece " << p;
        EXPECT_EQ(c.overflow, notDrawn);
        EXPECT_EQ(notDrawn > 0, budget > 0);
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(MeshRaster, KernelsMatchTheirCpuTwin)
{
    // mesh_raster.comp and mesh_shade.comp against their twin, in the compute path's frame (the
    // head drawn in compute, one sample a pixel; shadows off: the twin shades unoccluded).
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(60);
    RenderSettings s = test::smallRenderSettings();
    s.shadows.enabled = false;
    RasterFrame f = renderRasterFrame(ctx, scene, s);
    ASSERT_EQ(f.meshes.samples, 1u);
    reference::MeshSamples cpu = reference::rasterMeshes(f.meshes, f.frame, {f.head});
    std::vector<float> depth = f.readback->depth();
    std::vector<uint32_t> ids = f.readback->ids();
    size_t pixels = depth.size(), covered = 0, differentIds = 0;
    double worstDepth = 0.0;
    for (size_t p = 0; p < pixels; ++p) {
        covered += ids[p] != gpu::kNoMesh ? 1 : 0;
        differentIds += ids[p] != cpu.ids[p] ? 1 : 0;
        worstDepth = std::max(worstDepth, double(std::abs(depth[p] - std::bit_cast<float>(cpu.depth[p]))));
    }
    EXPECT_GT(covered, pixels / 10) << "the head covers part of the picture";
    EXPECT_LT(covered, pixels) << "and not all of it";
    EXPECT_LE(differentIds, pixels / 2000) << "a sample on a shared edge, at most";
    EXPECT_LT(worstDepth, 1e-6);

    // The shading, from the GPU's own samples: the same surfaces, RGBA16F rounding and the two
    // compilers' arithmetic apart; the backdrop's gradient exactly where no mesh is.
    reference::MeshSamples gpuSamples{cpu.depth, ids};
    std::vector<glm::vec3> twin = reference::shadeMeshes(f.meshes, f.frame, f.head, f.sphere, gpuSamples);
    std::vector<glm::vec4> color = f.readback->meshColor();
    double worst = 0.0, sum = 0.0, worstBackground = 0.0;
    for (size_t p = 0; p < pixels; ++p)
        for (int ch = 0; ch < 3; ++ch) {
            double d = std::abs(double(color[p][ch]) - double(twin[p][ch]));
            worst = std::max(worst, d);
            sum += d;
            if (ids[p] == gpu::kNoMesh) {
                float y = float(p / f.meshes.width) + 0.5f; // the backdrop's gradient at the pixel's row
                double backdrop = double(gpu::frameBackground(f.frame, y)[ch]);
                worstBackground = std::max(worstBackground, std::abs(double(color[p][ch]) - backdrop));
            }
        }
    EXPECT_LT(worst, 4e-3);
    EXPECT_LT(sum / double(pixels * 3), 2e-4);
    EXPECT_LT(worstBackground, 1e-3);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(MeshRaster, MatchesTheGraphicsMeshes)
{
    // The head alone, 4x MSAA, shadows on: drawn by the graphics pipeline and by compute, the same
    // picture but for samples on the silhouette's edges and the shadows' noise there.
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(60);
    RenderSettings s = test::smallRenderSettings();
    s.samples = 4;
    s.hairRaster = HairRaster::Graphics;
    Picture graphics = renderPicture(ctx, scene.head, s);
    s.hairRaster = HairRaster::Compute;
    Picture compute = renderPicture(ctx, scene.head, s);
    ASSERT_EQ(graphics.rgba.size(), compute.rgba.size());
    size_t differing = 0, head = 0;
    double sum = 0.0;
    for (size_t i = 0; i < graphics.rgba.size(); i += 4) {
        int d = 0;
        for (int k = 0; k < 3; ++k)
            d = std::max(d, std::abs(int(graphics.rgba[i + k]) - int(compute.rgba[i + k])));
        sum += d;
        differing += d > 24 ? 1 : 0;
        head += graphics.rgba[i] != graphics.rgba[0] ? 1 : 0;
    }
    double pixels = double(graphics.rgba.size() / 4);
    EXPECT_GT(double(head) / pixels, 0.1) << "the head is in the picture";
    EXPECT_LT(double(differing) / pixels, 0.003) << "pixels that differ clearly";
    EXPECT_LT(sum / pixels, 0.4) << "mean difference (levels of 255)";
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(MeshRaster, AStillCameraKeepsTheSamplesAnEarlierFrameDrew)
{
    // meshes.clear, meshes.raster and meshes.ids run only when what the samples depend on has
    // changed (MeshVisibilityKey): a second frame from the same camera keeps the first's samples
    // and draws the same picture; a sphere moved in, or the camera turned, draws them again, and
    // the picture is the one a fresh renderer draws there.
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(60);
    RenderSettings s = test::smallRenderSettings();
    s.hairRaster = HairRaster::Compute;
    s.samples = 4;
    test::HairRenderer hair(ctx, scene, s);
    Frame& frame = hair.frame;
    const OrbitCamera& camera = hair.camera;
    auto ran = [&](const std::string& pass) {
        const std::vector<vk::ScopeTime>& t = frame.timings();
        return std::any_of(t.begin(), t.end(), [&](const vk::ScopeTime& x) { return x.name == pass; });
    };
    auto rasterized = [&] { return ran("meshes.clear") && ran("meshes.raster") && ran("meshes.ids"); };
    Picture first = renderFrame(ctx, hair.renderer, frame, camera);
    EXPECT_TRUE(rasterized()) << "a first frame draws its samples";
    Picture still = renderFrame(ctx, hair.renderer, frame, camera);
    EXPECT_FALSE(ran("meshes.clear") || ran("meshes.raster") || ran("meshes.ids")) << "nothing moved";
    EXPECT_TRUE(ran("meshes.shade")) << "the shading (the hair's shadows) every frame";
    EXPECT_EQ(still.rgba, first.rgba);

    Bounds bounds = hair.renderer.sceneBounds();
    glm::vec4 sphere(bounds.center() + glm::vec3(0.3f, 0.0f, 0.3f) * bounds.diagonal(), 0.15f * bounds.diagonal());
    hair.renderer.setSphere(sphere);
    Picture withSphere = renderFrame(ctx, hair.renderer, frame, camera);
    EXPECT_TRUE(rasterized()) << "the sphere moved in";
    EXPECT_NE(withSphere.rgba, still.rgba) << "the sphere is in the picture";
    test::HairRenderer fresh(ctx, scene, s);
    fresh.renderer.setSphere(sphere);
    EXPECT_EQ(withSphere.rgba, renderFrame(ctx, fresh.renderer, fresh.frame, camera).rgba);

    OrbitCamera turned = camera;
    turned.orbit(4.0f, 1.0f);
    Picture moved = renderFrame(ctx, hair.renderer, frame, turned);
    EXPECT_TRUE(rasterized()) << "the camera turned";
    EXPECT_EQ(moved.rgba, renderFrame(ctx, fresh.renderer, fresh.frame, turned).rgba);
    renderFrame(ctx, hair.renderer, frame, turned);
    EXPECT_FALSE(ran("meshes.raster")) << "still again";
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(StrandRaster, LightKernelsMatchTheirCpuTwin)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(60);
    RenderSettings s = test::smallRenderSettings();
    s.shadows.mapSize = 256;
    RasterFrame f = renderRasterFrame(ctx, scene, s);

    reference::StrandVertices gpuStrands = f.strands(true);
    expectSameStrands(gpuStrands, reference::generateStrands(f.light, f.frame, f.sim, f.guides, f.triangles), false);

    reference::LightMaps cpu = reference::rasterLight(f.light, f.frame, gpuStrands);
    size_t texels = size_t(f.light.targetWidth) * f.light.targetHeight;
    std::vector<uint32_t> depth = f.readback->read<uint32_t>(Buffer::LightDepth, texels);
    std::vector<glm::uvec4> opacity = f.readback->read<glm::uvec4>(Buffer::LightOpacity, texels);
    size_t hair = 0, worst = 0;
    double gpuSum = 0.0, cpuSum = 0.0;
    for (size_t t = 0; t < texels; ++t) {
        float g = std::bit_cast<float>(depth[t]), c = std::bit_cast<float>(cpu.depth[t]);
        ASSERT_EQ(g < 1.0f, c < 1.0f) << "texel " << t << ": hair in one map only";
        ASSERT_NEAR(g, c, 1e-6f) << "texel " << t;
        hair += c < 1.0f ? 1 : 0;
        for (int l = 0; l < 4; ++l) {
            worst = std::max<size_t>(worst, size_t(std::abs(int64_t(opacity[t][l]) - int64_t(cpu.opacity[t][l]))));
            gpuSum += opacity[t][l];
            cpuSum += cpu.opacity[t][l];
        }
    }
    EXPECT_GT(hair, texels / 50) << "the hair covers part of the light's map";
    EXPECT_GT(cpuSum, 0.0);
    EXPECT_NEAR(gpuSum, cpuSum, 1e-4 * cpuSum);
    EXPECT_LE(worst, 8u) << "a few fixed-point units of 1/1024 (one rounding per covered texel)";
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// ---- The whole path against the tessellation path ----------------------------------------------

namespace {

// How much the hair changes each 8 x 8 block of the picture (against the picture without hair):
// the sum of absolute RGB differences, per block.
std::vector<double> hairBlocks(const Picture& hair, const Picture& bare)
{
    uint32_t bx = hair.width / 8, by = hair.height / 8;
    std::vector<double> blocks(size_t(bx) * by, 0.0);
    for (uint32_t y = 0; y < by * 8; ++y)
        for (uint32_t x = 0; x < bx * 8; ++x)
            for (int c = 0; c < 3; ++c) {
                size_t i = (size_t(y) * hair.width + x) * 4 + size_t(c);
                blocks[size_t(y / 8) * bx + x / 8] += std::abs(int(hair.rgba[i]) - int(bare.rgba[i]));
            }
    return blocks;
}

struct Agreement {
    double correlation = 0.0;
    double totalRatio = 0.0; // compute's total change over graphics'
};

Agreement agreement(const Picture& graphics, const Picture& compute, const Picture& bare)
{
    std::vector<double> a = hairBlocks(graphics, bare), b = hairBlocks(compute, bare);
    double ma = 0.0, mb = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        ma += a[i];
        mb += b[i];
    }
    double sa = ma, sb = mb;
    ma /= double(a.size());
    mb /= double(b.size());
    double cov = 0.0, va = 0.0, vb = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        cov += (a[i] - ma) * (b[i] - mb);
        va += (a[i] - ma) * (a[i] - ma);
        vb += (b[i] - mb) * (b[i] - mb);
    }
    return {cov / std::sqrt(va * vb), sb / sa};
}

struct EquivalenceCase {
    const char* name;
    void (*adjust)(RenderSettings&);
    bool loadedGroom = false;
};

// Sintel Lite's groom on its bust, loaded as a user loads it (none where ../shared/data lacks it).
std::optional<GroomedHead> sintelLiteScene()
{
    std::filesystem::path head = test::sharedData("sintel-lite/sintel_lite.obj");
    std::filesystem::path hair = test::sharedData("sintel-lite/sintel_hair_228x32.tfx");
    if (head.empty() || hair.empty())
        return std::nullopt;
    HairSource source;
    source.headFile = head;
    source.hairFiles = {hair.string()};
    return source.buildGroomedHead(Settings{});
}
constexpr const char* kNoSintelLite = "../shared/data/sintel-lite is absent: this test needs the shared "
                                      "third-party assets beside the checkout";

Picture renderWith(const vk::Context& ctx, const GroomedHead& scene, RenderSettings s, HairRaster raster)
{
    s.hairRaster = raster;
    return test::renderHair(ctx, scene, s);
}

} // namespace

class RasterEquivalence : public ::testing::TestWithParam<EquivalenceCase> {};

TEST_P(RasterEquivalence, TheComputePathDrawsWhatTheTessellationPathDraws)
{
    const EquivalenceCase& c = GetParam();
    vk::Context ctx(test::validatedOptions());
    std::optional<GroomedHead> loaded = c.loadedGroom ? sintelLiteScene() : std::nullopt;
    if (c.loadedGroom && !loaded)
        GTEST_SKIP() << kNoSintelLite;
    GroomedHead scene = loaded ? std::move(*loaded) : test::smallGroomedHead(300);
    RenderSettings s = test::smallRenderSettings();
    s.width = 320;
    s.height = 240;
    c.adjust(s);
    Picture graphics = renderWith(ctx, scene, s, HairRaster::Graphics);
    Picture compute = renderWith(ctx, scene, s, HairRaster::Compute);
    Picture bare = renderPicture(ctx, scene.head, s); // the same frame without hair
    Agreement a = agreement(graphics, compute, bare);
    std::printf("[ %s ] block correlation %.4f, total ratio %.4f\n", c.name, a.correlation, a.totalRatio);
    EXPECT_GE(a.correlation, 0.95);
    EXPECT_NEAR(a.totalRatio, 1.0, 0.2);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, RasterEquivalence,
    ::testing::Values(
        EquivalenceCase{"grown", [](RenderSettings&) {}},
        EquivalenceCase{"single", [](RenderSettings& s) { s.strands.interpolation = Interpolation::Single; }},
        EquivalenceCase{"multi", [](RenderSettings& s) { s.strands.interpolation = Interpolation::Multi; }},
        EquivalenceCase{"coiled",
                        [](RenderSettings& s) {
                            s.strands.divisions = 64;
                            s.strands.coilRadiusMetres = 0.003f;
                            s.strands.coilTurnsPerMetre = 40.0f;
                        }},
        EquivalenceCase{"trimmed", [](RenderSettings& s) { s.strands.lengthJitter = 0.5f; }},
        EquivalenceCase{"whole", [](RenderSettings& s) { s.strands.lengthJitter = 0.0f; }},
        EquivalenceCase{"kajiya", [](RenderSettings& s) { s.hair.model = ShadingModel::Kajiya; }},
        EquivalenceCase{"lut", [](RenderSettings& s) { s.hair.model = ShadingModel::Lut; }},
        EquivalenceCase{"backlit",
                        [](RenderSettings& s) {
                            s.light.azimuthDeg = 160.0f;
                            s.light.elevationDeg = 20.0f;
                            applyHairPreset(s.hair, "blonde");
                        }},
        EquivalenceCase{"loaded", [](RenderSettings&) {}, true}),
    [](const ::testing::TestParamInfo<EquivalenceCase>& param) { return std::string(param.param.name); });

TEST(StrandRaster, TwoRendersAreIdentical)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(200);
    RenderSettings s = test::smallRenderSettings();
    Picture a = renderWith(ctx, scene, s, HairRaster::Compute);
    Picture b = renderWith(ctx, scene, s, HairRaster::Compute);
    EXPECT_EQ(a.rgba, b.rgba);
    EXPECT_GT(a.raster.fragments, 1000u);
    EXPECT_GT(a.raster.maxPixel, 1u);
    EXPECT_EQ(a.raster.overflow, 0u);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(StrandRaster, ASmallBudgetDrawsTheSamePictureInPieces)
{
    // The fragment buffer held to a fifth of what the frame needs: the frame is drawn in pieces,
    // byte for byte the picture of an unbounded buffer. The first frame after the budget shrinks
    // records the pieces its slot needed before (one, and one spare): it counts what it could
    // not draw, and the next frame records enough.
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(150);
    RenderSettings s = test::smallRenderSettings();
    s.hairRaster = HairRaster::Compute;
    Picture reference = test::renderHair(ctx, scene, s);
    ASSERT_EQ(reference.raster.pieces, 1u);
    ASSERT_EQ(reference.raster.overflow, 0u);

    test::HairRenderer hair(ctx, scene, s);
    Renderer& renderer = hair.renderer;
    Frame& frame = hair.frame;
    OrbitCamera camera = hair.camera;
    Picture whole = renderFrame(ctx, renderer, frame, camera);
    EXPECT_EQ(whole.rgba, reference.rgba);
    uint64_t budget = whole.raster.fragments / 5;
    ASSERT_GT(budget, 2 * whole.raster.maxPixel) << "every pixel fits half the budget";
    renderer.strandRaster()->setFragmentCapacity(budget);
    Picture first = renderFrame(ctx, renderer, frame, camera);
    EXPECT_EQ(renderer.strandRaster()->recordedPieces(), 2u);
    EXPECT_EQ(first.raster.capacity, budget);
    EXPECT_EQ(first.raster.fragments, whole.raster.fragments);
    EXPECT_GE(first.raster.pieces, 5u);
    EXPECT_GT(first.raster.overflow, 0u) << "the pieces past the two recorded are counted";
    EXPECT_LT(first.raster.overflow, first.raster.fragments);
    // (Its pixels past the recorded pieces are not resolved: the hair image keeps what it held.)
    Picture pieces = renderFrame(ctx, renderer, frame, camera);
    EXPECT_GE(renderer.strandRaster()->recordedPieces(), first.raster.pieces);
    EXPECT_EQ(pieces.raster.capacity, budget) << "the buffer stays within the budget";
    EXPECT_EQ(pieces.raster.pieces, first.raster.pieces);
    EXPECT_EQ(pieces.raster.overflow, 0u);
    EXPECT_EQ(pieces.raster.maxPixel, whole.raster.maxPixel);
    EXPECT_EQ(pieces.rgba, reference.rgba) << "pieces draw the picture of an unbounded buffer";
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// The fragments of every pixel, from a frame's read-back buffers: pixel p's list at `first[p]`,
// offsets[p + 1] - offsets[p] of them, sorted (the atomics write them in any order).
std::vector<std::vector<uvec2Fragment>> sortedPixelLists(const RasterReadback& r, const std::vector<uint32_t>& offsets,
                                                         const std::vector<uint32_t>& first, uint32_t capacity)
{
    std::vector<uvec2Fragment> raw = r.read<uvec2Fragment>(Buffer::Fragments, capacity);
    std::vector<std::vector<uvec2Fragment>> out(offsets.size() - 1);
    for (size_t p = 0; p + 1 < offsets.size(); ++p) {
        for (uint32_t i = 0; i < offsets[p + 1] - offsets[p]; ++i)
            out[p].push_back(raw.at(first[p] + i));
        std::sort(out[p].begin(), out[p].end(), [](const uvec2Fragment& a, const uvec2Fragment& b) {
            return std::tie(a.depth, a.color) < std::tie(b.depth, b.color);
        });
    }
    return out;
}

TEST(StrandRaster, TheNextFrameIsWrittenInOneWalkIntoTheRoomTheLastOneReserved)
{
    // shared/strand_raster.h "One walk". The first frame has no room reserved: strands.count only
    // counts and strands.write lays the fragments out exactly, as before. strands.reserve then
    // leaves each pixel its count, an eighth more and a few (its twin below); the next frame of the
    // same scene fits that room: strands.count writes every fragment, no second walk is dispatched,
    // and each pixel holds the same fragments, at its reserved slot.
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(150);
    RenderSettings s = test::smallRenderSettings();
    s.hairRaster = HairRaster::Compute;
    s.samples = 1;
    test::HairRenderer hair(ctx, scene, s);
    Renderer& renderer = hair.renderer;
    Frame& frame = hair.frame;
    OrbitCamera camera = hair.camera;
    auto run = [&] {
        FrameContext& fc = frame.begin(renderer.transientImages());
        renderer.prepare(fc, camera, 0.0f);
        auto readback =
            std::make_unique<RasterReadback>(ctx, *renderer.strandRaster(), *renderer.meshRaster(), renderer.target());
        std::vector<Pass*> passes = renderer.passes();
        passes.push_back(readback.get());
        frame.run(fc, passes);
        frame.submit(fc);
        frame.waitIdle();
        return readback;
    };
    size_t pixels = size_t(s.width) * s.height;
    std::unique_ptr<RasterReadback> first = run();
    std::vector<uint32_t> offsets = first->read<uint32_t>(Buffer::Offsets, pixels + 1);
    gpu::RasterCounters c1 = first->read<gpu::RasterCounters>(Buffer::Counters, 1)[0];
    ASSERT_GT(c1.fragments, 4000u);
    EXPECT_EQ(renderer.strandRaster()->cameraPush().reserving, 0u) << "a first frame: nothing to reserve from";
    EXPECT_EQ(c1.reservedEnd, gpu::kRasterNotReserved);
    EXPECT_EQ(c1.spilled, 0u);
    EXPECT_GT(first->read<gpu::RasterPiece>(Buffer::Pieces, 1)[0].walkGroups[0], 0u);
    std::vector<uint32_t> reserved = first->read<uint32_t>(Buffer::Reserved, pixels + 1);
    EXPECT_EQ(reserved, reference::reservedLayout(offsets)) << "strands.reserve and its twin";
    for (size_t p = 0; p < pixels; ++p) {
        uint32_t count = offsets[p + 1] - offsets[p];
        ASSERT_GE(reserved[p + 1] - reserved[p], count + count / 8 + gpu::kRasterReservedPerPixel) << "pixel " << p;
    }

    std::unique_ptr<RasterReadback> second = run();
    gpu::RasterCounters c2 = second->read<gpu::RasterCounters>(Buffer::Counters, 1)[0];
    EXPECT_EQ(renderer.strandRaster()->cameraPush().reserving, 1u);
    EXPECT_EQ(c2.fragments, c1.fragments);
    EXPECT_EQ(c2.reservedEnd, reserved[pixels]);
    EXPECT_EQ(c2.spilled, 0u);
    EXPECT_EQ(c2.spillListed, 0u);
    EXPECT_EQ(c2.pieces, 1u);
    EXPECT_EQ(second->read<gpu::RasterPiece>(Buffer::Pieces, 1)[0].walkGroups[0], 0u) << "no second walk";
    EXPECT_EQ(second->read<uint32_t>(Buffer::Offsets, pixels + 1), offsets);
    std::vector<uint32_t> exact(offsets.begin(), offsets.end() - 1);
    std::vector<uint32_t> room(reserved.begin(), reserved.end() - 1);
    EXPECT_TRUE(sortedPixelLists(*second, offsets, room, c2.capacity) ==
                sortedPixelLists(*first, offsets, exact, c1.capacity))
        << "each pixel's fragments, at its reserved slot";
    EXPECT_EQ(second->color(), first->color());
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// The next frame's steps recorded beside this frame's passes (Renderer::setStepsAhead) leave each
// frame's picture and the solver's state as recording every frame's steps first does, byte for
// byte, with the hair moving (a turning head, wind, the sphere): the compute path, whose kernels go
// in front of its passes after the curves (four steps a frame: every kernel hosted, no pass more;
// seven: the ones left over at the end), and the graphics path, which runs them at the end.
TEST(StrandRaster, StepsAheadBesideTheFrameDrawWhatStepsFirstDraw)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(120);
    struct Case {
        HairRaster raster;
        uint32_t stepsPerFrame;
        size_t passesMore; // in a frame with steps ahead, over the same frame with its steps first
    };
    for (Case c :
         {Case{HairRaster::Compute, 4, 0}, Case{HairRaster::Compute, 7, 6}, Case{HairRaster::Graphics, 3, 6}}) {
        RenderSettings s = test::smallRenderSettings();
        s.hairRaster = c.raster;
        struct Run {
            std::vector<std::vector<uint8_t>> pictures;
            std::vector<size_t> passCounts;
            SimState state;
        };
        auto run = [&](bool ahead) {
            test::HairRenderer hair(ctx, scene, s);
            Renderer& renderer = hair.renderer;
            const SimSetup& setup = hair.solver.setup();
            uint32_t taken = 0;
            auto steps = [&] {
                std::vector<gpu::SimStep> list;
                for (uint32_t k = 0; k < c.stepsPerFrame; ++k, ++taken) {
                    float t = float(taken) / 120.0f;
                    glm::mat4 head = glm::rotate(glm::mat4(1.0f), 0.8f * std::sin(6.0f * t), glm::vec3(0, 1, 0));
                    list.push_back(makeStep(setup, head, glm::vec4(0.08f - 0.5f * t, 0.1f, 0.08f, 0.05f), t,
                                            glm::vec3(4.0f, 0.0f, 1.0f)));
                }
                return list;
            };
            Run out;
            constexpr uint32_t kFrames = 3;
            for (uint32_t f = 0; f < kFrames; ++f) {
                if (ahead) {
                    renderer.setSteps(f == 0 ? steps() : std::vector<gpu::SimStep>{});
                    renderer.setStepsAhead(f + 1 < kFrames ? steps() : std::vector<gpu::SimStep>{});
                } else {
                    renderer.setSteps(steps());
                }
                FrameContext& fc = hair.frame.begin(renderer.transientImages());
                renderer.prepare(fc, hair.camera, 0.0f);
                ReadbackPass readback(ctx, renderer.target());
                std::vector<Pass*> passes = renderer.passes();
                out.passCounts.push_back(passes.size());
                passes.push_back(&readback);
                hair.frame.run(fc, passes);
                hair.frame.submit(fc);
                hair.frame.waitIdle();
                out.pictures.push_back(readback.pixels());
            }
            out.state = hair.solver.readState();
            return out;
        };
        Run first = run(false), ahead = run(true);
        std::string what = std::string(c.raster == HairRaster::Compute ? "compute" : "graphics") + ", " +
                           std::to_string(c.stepsPerFrame) + " steps a frame";
        ASSERT_EQ(ahead.pictures.size(), first.pictures.size());
        for (size_t f = 0; f < first.pictures.size(); ++f) {
            EXPECT_TRUE(ahead.pictures[f] == first.pictures[f]) << what << ": frame " << f;
            size_t more = f + 1 < first.pictures.size() ? c.passesMore : 0;
            EXPECT_EQ(ahead.passCounts[f], first.passCounts[f] + more) << what << ": frame " << f;
        }
        EXPECT_FALSE(first.pictures.front() == first.pictures.back()) << what << ": the hair moves";
        EXPECT_EQ(std::memcmp(ahead.state.positions.data(), first.state.positions.data(),
                              first.state.positions.size() * sizeof(glm::vec4)),
                  0)
            << what;
        EXPECT_EQ(std::memcmp(ahead.state.velocities.data(), first.state.velocities.data(),
                              first.state.velocities.size() * sizeof(glm::vec4)),
                  0)
            << what;
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(StrandRaster, AFrameThatOutgrowsItsRoomWalksAgainOnlyForThePixelsThatDid)
{
    // After two frames from one camera, the camera turns: the pixels that now hold more than
    // their reserved room spill, and only theirs are laid out again, after the reserved region,
    // from the list of spilled fragments (no second walk); the picture is the one a first frame
    // draws there. The same with a spill list too short for them: the walk again. With a buffer
    // too small for the reserved layout and the exact one after it, the frame is laid out
    // exactly, as before.
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(150);
    RenderSettings s = test::smallRenderSettings();
    s.hairRaster = HairRaster::Compute;
    test::HairRenderer hair(ctx, scene, s);
    Frame& frame = hair.frame;
    const OrbitCamera& camera = hair.camera;
    renderFrame(ctx, hair.renderer, frame, camera);
    Picture still = renderFrame(ctx, hair.renderer, frame, camera);
    EXPECT_TRUE(still.raster.oneWalk());
    OrbitCamera turned = camera;
    turned.orbit(4.0f, 1.0f);
    Picture moved = renderFrame(ctx, hair.renderer, frame, turned);
    EXPECT_TRUE(moved.raster.reserved);
    EXPECT_GT(moved.raster.spilled, 0u);
    EXPECT_LT(moved.raster.spilled, moved.raster.fragments / 2) << "most pixels had room";
    EXPECT_EQ(moved.raster.overflow, 0u);

    test::HairRenderer fresh(ctx, scene, s);
    Picture exact = renderFrame(ctx, fresh.renderer, fresh.frame, turned);
    EXPECT_FALSE(exact.raster.reserved) << "a first frame: laid out exactly";
    EXPECT_EQ(moved.raster.fragments, exact.raster.fragments);
    EXPECT_EQ(moved.rgba, exact.rgba);

    hair.renderer.strandRaster()->setSpillCapacity(uint32_t(moved.raster.spilled / 2));
    renderFrame(ctx, hair.renderer, frame, camera);
    renderFrame(ctx, hair.renderer, frame, camera);
    Picture walkedAgain = renderFrame(ctx, hair.renderer, frame, turned);
    EXPECT_EQ(walkedAgain.raster.spilled, moved.raster.spilled);
    EXPECT_EQ(walkedAgain.rgba, exact.rgba) << "the spill list too short: the walk again";

    hair.renderer.strandRaster()->setFragmentCapacity(moved.raster.fragments + moved.raster.fragments / 8);
    Picture tight = renderFrame(ctx, hair.renderer, frame, turned);
    EXPECT_FALSE(tight.raster.reserved) << "no room for both layouts";
    EXPECT_EQ(tight.raster.pieces, 1u);
    EXPECT_EQ(tight.raster.overflow, 0u);
    EXPECT_EQ(tight.rgba, exact.rgba);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(StrandRaster, PiecesDrawEveryCaseByteForByte)
{
    // The cases the paths are compared in (a loaded groom with its own head, MSAA meshes, the
    // nearest fragment alone, blonde backlit hair), each drawn whole and with a buffer of a
    // third of its fragments.
    vk::Context ctx(test::validatedOptions());
    struct Case {
        const char* name;
        std::function<void(RenderSettings&)> set;
        bool loaded;
    };
    for (const Case& c : {Case{"default", [](RenderSettings&) {}, false},
                          Case{"one sorted", [](RenderSettings& s) { s.transparency.oitK = 1; }, false},
                          Case{"single sample", [](RenderSettings& s) { s.samples = 1; }, false},
                          Case{"loaded", [](RenderSettings&) {}, true}}) {
        SCOPED_TRACE(c.name);
        std::optional<GroomedHead> loaded = c.loaded ? sintelLiteScene() : std::nullopt;
        if (c.loaded && !loaded) // (last: without the data, the cases before it have run)
            GTEST_SKIP() << kNoSintelLite;
        GroomedHead scene = loaded ? std::move(*loaded) : test::smallGroomedHead(120);
        RenderSettings s = test::smallRenderSettings();
        s.hairRaster = HairRaster::Compute;
        c.set(s);
        test::HairRenderer hair(ctx, scene, s);
        Picture whole = renderFrame(ctx, hair.renderer, hair.frame, hair.camera);
        ASSERT_EQ(whole.raster.pieces, 1u);
        hair.renderer.strandRaster()->setFragmentCapacity(
            std::max(whole.raster.fragments / 3, 2 * whole.raster.maxPixel));
        renderFrame(ctx, hair.renderer, hair.frame, hair.camera); // records the pieces the next one needs
        Picture pieces = renderFrame(ctx, hair.renderer, hair.frame, hair.camera);
        EXPECT_GE(pieces.raster.pieces, 2u);
        EXPECT_EQ(pieces.raster.overflow, 0u);
        EXPECT_EQ(pieces.rgba, whole.rgba);
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(StrandRaster, DeviceBytesIsWhatItAllocates)
{
    // The up-front estimate (StrandRaster::deviceBytes, which the workload's memory check sums)
    // against the buffers and image a first frame really makes: with the light's strands, without
    // them (shadows off), on a size whose pixels do not fill the scan's blocks.
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(150);
    for (bool shadows : {true, false}) {
        RenderSettings s = test::smallRenderSettings();
        s.width = 203;
        s.height = 97;
        s.hairRaster = HairRaster::Compute;
        s.shadows.enabled = shadows;
        test::HairRenderer hair(ctx, scene, s);
        Renderer& renderer = hair.renderer;
        Picture picture = renderFrame(ctx, renderer, hair.frame, hair.camera);
        ASSERT_GT(picture.raster.fragments, 0u);
        StrandRaster& raster = *renderer.strandRaster();
        const gpu::StrandRasterPush& cam = raster.cameraPush();
        const gpu::StrandRasterPush& light = raster.lightPush();
        EXPECT_EQ(cam.drawnPerGuide, 8u) << "the default framing draws every strand";
        EXPECT_EQ(light.drawnPerGuide, shadows ? 2u : 0u) << "shadow_strands 0.25 of 8";
        uint64_t estimate = StrandRaster::deviceBytes({.extent = {s.width, s.height},
                                                       .guides = cam.guideCount,
                                                       .strandsPerGuide = cam.drawnPerGuide,
                                                       .lightStrandsPerGuide = light.drawnPerGuide,
                                                       .divisions = cam.divisions,
                                                       .lightMapSize = s.shadows.mapSize,
                                                       .samples = uint32_t(renderer.target().samples()),
                                                       .fragmentBudget = raster.fragmentBudget()});
        EXPECT_EQ(raster.allocatedBytes(), estimate) << "shadows " << shadows;
        ASSERT_NE(renderer.meshRaster(), nullptr) << "the meshes drawn in compute too";
        uint64_t meshes = renderer.meshRaster()->allocatedBytes();
        EXPECT_EQ(meshes, MeshRaster::deviceBytes({s.width, s.height}, uint32_t(renderer.target().samples())));
        EXPECT_EQ(raster.fragmentCapacity(), picture.raster.capacity);
        // The workload's check counts the same from the settings alone.
        Workload w{.guides = scene.strands.strandCount(),
                   .verticesPerStrand = scene.strands.verticesPerStrand,
                   .sim = SimSettings{},
                   .render = &s};
        EXPECT_EQ(estimateGpuMemory(w, ctx.report()).raster, raster.allocatedBytes() + meshes) << "shadows " << shadows;
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(StrandRaster, StatsAreDescribedInOneLine)
{
    // The line `wisp render` prints and the window's panel shows.
    RasterStats s{.segments = 1200, .hidden = 300, .fragments = 5000, .capacity = 8000, .overflow = 0, .maxPixel = 17};
    EXPECT_EQ(describeRasterStats(s), "compute raster: 1200 segments on screen (300 skipped whole: behind the meshes "
                                      "in every 8 x 8 tile they cross), 5000 hair "
                                      "fragments (at most 17 in a pixel), buffer of 8000");
    s.capacity = 2000;
    s.pieces = 3;
    EXPECT_EQ(describeRasterStats(s), "compute raster: 1200 segments on screen (300 skipped whole: behind the meshes "
                                      "in every 8 x 8 tile they cross), 5000 hair "
                                      "fragments (at most 17 in a pixel), buffer of 2000, drawn in 3 pieces");
    s.overflow = 1000;
    EXPECT_EQ(describeRasterStats(s), "compute raster: 1200 segments on screen (300 skipped whole: behind the meshes "
                                      "in every 8 x 8 tile they cross), 5000 hair "
                                      "fragments (at most 17 in a pixel), buffer of 2000, drawn in 3 pieces, 1000 not "
                                      "drawn (more pieces are recorded for the next frame)");
    RasterStats reserved{.segments = 1200, .hidden = 300, .fragments = 5000, .capacity = 16000, .maxPixel = 17};
    reserved.reserved = true;
    EXPECT_EQ(describeRasterStats(reserved), "compute raster: 1200 segments on screen (300 skipped whole: behind the "
                                             "meshes in every 8 x 8 tile they cross), 5000 "
                                             "hair fragments (at most 17 in a pixel), buffer of 16000, one walk");
    reserved.spilled = 40;
    EXPECT_EQ(describeRasterStats(reserved),
              "compute raster: 1200 segments on screen (300 skipped whole: behind the meshes in every 8 x 8 tile they "
              "cross), 5000 hair fragments (at most 17 in a "
              "pixel), buffer of 16000, 40 spilled from their reserved room");
}

TEST(StrandRaster, TheFragmentBudgetSettingDrawsTheSamePicture)
{
    // `wisp render` with the smallest budget (1 MiB: 131,072 fragments) draws the frame in pieces,
    // says so, and writes the PNG of the automatic budget byte for byte.
    test::TempDir dir;
    std::string common = "--validation render --guides 300 --width 240 --height 180 --set strands_per_guide=32 ";
    test::RunResult whole = test::runWisp(common + "--out '" + (dir / "whole.png").string() + "'");
    ASSERT_EQ(whole.status, 0) << whole.err;
    test::RunResult pieces =
        test::runWisp(common + "--set fragment_budget=1 --out '" + (dir / "pieces.png").string() + "'");
    ASSERT_EQ(pieces.status, 0) << pieces.err;
    EXPECT_EQ(whole.out.find("pieces"), std::string::npos) << whole.out;
    EXPECT_NE(pieces.out.find("buffer of 131072, drawn in "), std::string::npos) << pieces.out;
    EXPECT_EQ(pieces.err.find("warning"), std::string::npos) << pieces.err;
    EXPECT_EQ(test::readFile(dir / "pieces.png"), test::readFile(dir / "whole.png"));
}
