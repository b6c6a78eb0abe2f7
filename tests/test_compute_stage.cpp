// tests/test_compute_stage.cpp: a compute stage is one list (gpu/compute_stage.h), on the real
// device. The frame's declarations come from it (each tracked resource once, the unbound and the
// untracked not at all); a stage cannot use what it does not list: a command on a resource it
// does not list throws, and so does the dispatch of a kernel whose shader uses a binding its stage
// leaves out (the compute strands' own scan, one entry dropped), which would otherwise read
// whatever an earlier stage pushed there, with no barrier. The kernels outside the compute path
// (the solver's two, the meshes' shadow mask, the OIT resolve) are held to their lists the same way.
#include "gpu/compute_stage.h"
#include "gpu/frame.h"
#include "physics/gpu_solver.h"
#include "renderer/compute/strand_raster.h"
#include "renderer/graphics/oit.h"
#include "renderer/mesh_pass.h"
#include "small_groomed_head.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

using namespace wisp;

TEST(ComputeStage, DeclaresEachListedResourceOnceAndNothingElse)
{
    TrackedBuffer read, unbound, arguments;
    TrackedImage maps;
    ComputeStage stage{.uses = {storageBuffer(0, read, Access::ComputeRead),
                                storageBuffer(1, unbound, Access::ComputeWrite).when(false),
                                sampledImage(2, maps, VK_NULL_HANDLE, VK_NULL_HANDLE),
                                sampledImage(3, maps, VK_NULL_HANDLE, VK_NULL_HANDLE), // one image, two bindings
                                uniformBlock(4, VkBuffer(VK_NULL_HANDLE)), constantBuffer(5, VK_NULL_HANDLE),
                                commandUse(arguments, Access::IndirectRead)}};
    PassIo io;
    stage.declare(io);
    ASSERT_EQ(io.buffers.size(), 2u);
    EXPECT_EQ(io.buffers[0].buffer, &read);
    EXPECT_EQ(io.buffers[0].access, Access::ComputeRead);
    EXPECT_EQ(io.buffers[1].buffer, &arguments);
    EXPECT_EQ(io.buffers[1].access, Access::IndirectRead);
    ASSERT_EQ(io.images.size(), 1u);
    EXPECT_EQ(io.images[0].image, &maps);
    EXPECT_EQ(io.images[0].access, Access::ComputeSampled);
}

TEST(ComputeStage, EntriesRefuseAccessesTheirKindCannotHave)
{
    TrackedBuffer buffer;
    EXPECT_THROW(storageBuffer(0, buffer, Access::TransferDst), std::logic_error);
    EXPECT_THROW(commandUse(buffer, Access::ComputeWrite), std::logic_error);
}

namespace {

// Runs one stage as a frame's only pass and, when it records, submits the frame: false when
// recording threw (its message in `error`).
bool runStage(const vk::Context& ctx, const ComputeStage& stage, const char* name, std::string& error)
{
    StageLayout layout(ctx, std::span(&stage, 1), 0, "test.layout");
    ComputeStagePass pass(name, layout, [&] { return stage; });
    Frame frame(ctx, 1);
    FrameContext& fc = frame.begin({});
    Pass* passes[] = {&pass};
    try {
        frame.run(fc, passes);
    } catch (const std::logic_error& e) {
        error = e.what();
        return false; // (never submitted: the frame's command buffer is dropped with it)
    }
    frame.submit(fc);
    frame.waitIdle();
    return true;
}

} // namespace

TEST(ComputeStage, ACommandOnAResourceTheStageDoesNotListThrows)
{
    vk::Context ctx(test::validatedOptions());
    vk::Buffer a = ctx.createBuffer({.size = 256, .usage = vk::kTransferSrc | vk::kTransferDst, .name = "test.a"});
    vk::Buffer b = ctx.createBuffer({.size = 256, .usage = vk::kTransferSrc | vk::kTransferDst, .name = "test.b"});
    vk::Buffer host =
        ctx.createBuffer({.size = 256, .usage = vk::kTransferDst, .memory = vk::Memory::Readback, .name = "test.host"});
    TrackedBuffer ta{.buffer = a}, tb{.buffer = b};

    // Listed: the fill and the copy run, ordered by the barrier the list's declarations imply.
    std::string error;
    ComputeStage listed{.uses = {commandUse(ta, Access::TransferDst)},
                        .record = [&](StageCommands& c) { c.fill(ta, 0xC0FFEEu); }};
    ComputeStage readBack{.uses = {commandUse(ta, Access::TransferSrc)},
                          .record = [&](StageCommands& c) { c.copyToHost(ta, host, 256); }};
    {
        StageLayout layout(ctx, std::span(&listed, 1), 0, "test.layout");
        ComputeStagePass fill("test.fill", layout, [&] { return listed; });
        ComputeStagePass copy("test.copy", layout, [&] { return readBack; });
        Frame frame(ctx, 1);
        FrameContext& fc = frame.begin({});
        Pass* passes[] = {&fill, &copy};
        frame.run(fc, passes);
        frame.submit(fc);
        frame.waitIdle();
    }
    uint32_t word = 0;
    std::memcpy(&word, host.mapped(), sizeof(word));
    EXPECT_EQ(word, 0xC0FFEEu);

    // Not listed (or listed with another access): the command is refused before it is recorded.
    ComputeStage unlisted{.uses = {commandUse(ta, Access::TransferDst)},
                          .record = [&](StageCommands& c) { c.fill(tb, 1); }};
    EXPECT_FALSE(runStage(ctx, unlisted, "test.unlisted", error));
    EXPECT_NE(error.find("compute stage 'test.unlisted' fills buffer"), std::string::npos) << error;
    EXPECT_NE(error.find("does not list as TransferDst"), std::string::npos) << error;
    ComputeStage readOnly{.uses = {commandUse(ta, Access::TransferSrc)},
                          .record = [&](StageCommands& c) { c.fill(ta, 1); }};
    EXPECT_FALSE(runStage(ctx, readOnly, "test.read_only", error));
    vk::ComputeKernel none;
    ComputeStage noArguments{.uses = {}, .record = [&](StageCommands& c) { c.dispatchIndirect(none, 0u, ta, 0); }};
    EXPECT_FALSE(runStage(ctx, noArguments, "test.indirect", error));
    EXPECT_NE(error.find("takes its dispatch from buffer"), std::string::npos) << error;
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(ComputeStage, TheLayoutRefusesOneBindingOfTwoTypes)
{
    vk::Context ctx(test::validatedOptions());
    TrackedBuffer buffer;
    std::vector<ComputeStage> stages(2);
    stages[0].uses = {storageBuffer(3, buffer, Access::ComputeRead)};
    stages[1].uses = {uniformBlock(3, VkBuffer(VK_NULL_HANDLE))};
    EXPECT_THROW(StageLayout(ctx, stages, 0, "test.layout"), std::logic_error);
    stages[1].uses = {uniformBlock(4, VkBuffer(VK_NULL_HANDLE))};
    StageLayout layout(ctx, stages, 0, "test.layout");
    EXPECT_EQ(layout.bindings(), (std::vector<uint32_t>{3, 4}));
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(ComputeStage, KernelsKnowTheBindingsTheirShadersUse)
{
    // strands_scan.comp declares five buffers; each of its three phases (a specialization
    // constant) uses some, but the shader uses all five statically, so every phase binds them.
    EXPECT_EQ(vk::shaderBindings("strands_scan.comp"),
              (std::vector<uint32_t>{gpu::kRasterBindingCounts, gpu::kRasterBindingOffsets, gpu::kRasterBindingCounters,
                                     gpu::kRasterBindingBlockSums, gpu::kRasterBindingReserved}));
    EXPECT_THROW(vk::spirvBindings(std::vector<uint32_t>{1, 2, 3, 4, 5}), std::runtime_error);
}

namespace {

// Records one compute-path frame of the small scene, its strands.scan.blocks made from the
// strands' own list for that stage less the entry of `dropBinding` (none: the whole list), and
// submits it unless recording threw: then false, with the message in `error`.
bool renderScanWithout(uint32_t dropBinding, std::string& error)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(12);
    RenderSettings s = test::smallRenderSettings();
    s.hairRaster = HairRaster::Compute;
    test::HairRenderer hair(ctx, scene, s);
    Renderer& renderer = hair.renderer;
    StrandRaster& raster = *renderer.strandRaster();
    Frame& frame = hair.frame;
    OrbitCamera camera = hair.camera;
    FrameContext& fc = frame.begin(renderer.transientImages());
    renderer.prepare(fc, camera, 0.0f);

    ComputeStage scan = raster.stage(StrandRaster::Stage::ScanBlocks);
    size_t listed = scan.uses.size();
    std::erase_if(scan.uses, [&](const StageUse& u) { return u.binding == dropBinding; });
    EXPECT_EQ(scan.uses.size(), dropBinding == StageUse::kNoBinding ? listed : listed - 1);
    ComputeStagePass pass("strands.scan.blocks", raster.layout(), [&] { return scan; });
    std::vector<Pass*> passes = renderer.passes();
    auto original = std::find(passes.begin(), passes.end(), raster.pass(StrandRaster::Stage::ScanBlocks));
    EXPECT_NE(original, passes.end());
    if (original != passes.end())
        *original = &pass;
    try {
        frame.run(fc, passes);
    } catch (const std::logic_error& e) {
        error = e.what();
        return false; // (never submitted)
    }
    frame.submit(fc);
    frame.waitIdle();
    EXPECT_EQ(ctx.validationMessages(), 0u);
    return true;
}

} // namespace

TEST(ComputeStage, AKernelCannotUseABindingItsStageLeavesOut)
{
    std::string error;
    EXPECT_TRUE(renderScanWithout(StageUse::kNoBinding, error)) << error;
    // Without the counts' entry the scan would read the counts strands.count pushed, with no
    // barrier after strands.count wrote them: the dispatch is refused instead.
    EXPECT_FALSE(renderScanWithout(gpu::kRasterBindingCounts, error));
    EXPECT_NE(error.find("compute stage 'strands.scan.blocks' dispatches strands.scan.blocks.pipeline, whose shader "
                         "uses binding " +
                         std::to_string(gpu::kRasterBindingCounts)),
              std::string::npos)
        << error;
}

namespace {

// Records `stage`, less its entry at `dropBinding` (none: the whole list), into a command buffer
// that is never submitted: false when recording threw (its message in `error`).
bool recordWithout(const vk::Context& ctx, const StageLayout& layout, ComputeStage stage, uint32_t dropBinding,
                   const std::string& name, std::string& error)
{
    size_t listed = stage.uses.size();
    std::erase_if(stage.uses, [&](const StageUse& u) { return u.binding == dropBinding; });
    EXPECT_EQ(stage.uses.size(), dropBinding == StageUse::kNoBinding ? listed : listed - 1) << name;
    Frame frame(ctx, 1);
    FrameContext& fc = frame.begin({});
    try {
        layout.record(stage, fc.cmd, fc.slot, name);
    } catch (const std::logic_error& e) {
        error = e.what();
        return false;
    }
    return true;
}

// The stage's whole list records, and without any one of its bindings the dispatch is refused,
// naming that binding: its kernel uses every binding it lists, and can use no other.
void expectEachBindingNeeded(const vk::Context& ctx, const StageLayout& layout, const ComputeStage& stage,
                             const std::string& name)
{
    std::string error;
    EXPECT_TRUE(recordWithout(ctx, layout, stage, StageUse::kNoBinding, name, error)) << error;
    size_t bindings = 0;
    for (const StageUse& u : stage.uses) {
        if (u.binding == StageUse::kNoBinding)
            continue;
        ++bindings;
        EXPECT_FALSE(recordWithout(ctx, layout, stage, u.binding, name, error)) << name << " without " << u.binding;
        EXPECT_NE(error.find("compute stage '" + name + "' dispatches"), std::string::npos) << error;
        EXPECT_NE(error.find("uses binding " + std::to_string(u.binding) + ","), std::string::npos) << error;
    }
    EXPECT_GT(bindings, 0u) << name;
}

} // namespace

// The compute kernels outside the compute path (the solver's, the meshes' shadow mask, the OIT
// resolve) are stages too: each lists what its kernel uses, and one entry less is refused.
TEST(ComputeStage, TheSolverTheShadowMaskAndTheOitResolveCannotUseWhatTheyDoNotList)
{
    vk::Context ctx(test::validatedOptions());
    GroomedHead scene = test::smallGroomedHead(12);
    RenderSettings s = test::smallRenderSettings();
    s.hairRaster = HairRaster::Graphics;
    s.transparency.mode = Transparency::Oit;
    s.transparency.oitAutoNodes = 1u << 16;
    test::HairRenderer hair(ctx, scene, s);
    gpu::SimStep step{};
    for (uint32_t turn : {0u, 1u}) {
        expectEachBindingNeeded(ctx, hair.solver.layout(), hair.solver.stage(GpuSolver::Stage::Integrate, step, turn),
                                "integrate");
        expectEachBindingNeeded(ctx, hair.solver.layout(), hair.solver.stage(GpuSolver::Stage::GridGather, step, turn),
                                "grid_gather");
    }
    MeshPass& meshes = hair.renderer.meshes();
    expectEachBindingNeeded(ctx, meshes.shadowMaskLayout(), meshes.shadowMaskStage(), "meshes.shadow");
    OitResolvePass* resolve = hair.renderer.oitResolve();
    ASSERT_NE(resolve, nullptr);
    expectEachBindingNeeded(ctx, resolve->layout(), resolve->stage(), "oit.resolve");
    EXPECT_EQ(ctx.validationMessages(), 0u);
}
