// tests/test_device.cpp: device choice and the feature check (pure functions over reports), and
// the Vulkan core on the real device: buffers round-trip through the GPU, timestamps measure,
// Frame's declared accesses produce the barriers that synchronization validation demands, and a
// lost device (injected) is its own error that frames and the context survive.
#include "core/error.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/timestamps.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <memory>

using namespace wisp;

namespace {

vk::DeviceReport usable(uint32_t index, const char* name, VkPhysicalDeviceType type)
{
    vk::DeviceReport r;
    r.index = index;
    r.name = name;
    r.type = type;
    r.queueFamily = 0;
    r.vulkan13 = r.dynamicRendering = r.synchronization2 = r.maintenance4 = true;
    r.tessellationShader = r.geometryShader = r.fragmentStoresAndAtomics = true;
    r.timestamps = r.pushDescriptor = r.swapchain = true;
    r.floatAtomicAdd = r.int64Atomics = true;
    return r;
}

std::string selectError(const std::vector<vk::DeviceReport>& devices, const std::string& selector)
{
    try {
        vk::selectDevice(devices, selector, false);
    } catch (const UserError& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(DeviceChoice, PrefersDiscreteThenIntegratedThenCpu)
{
    std::vector<vk::DeviceReport> d = {usable(0, "llvmpipe", VK_PHYSICAL_DEVICE_TYPE_CPU),
                                       usable(1, "Intel UHD", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU),
                                       usable(2, "NVIDIA H100", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU)};
    EXPECT_EQ(vk::selectDevice(d, "", false).index, 2u);
    d.pop_back();
    EXPECT_EQ(vk::selectDevice(d, "", false).index, 1u);
}

TEST(DeviceChoice, SkipsDevicesMissingFeatures)
{
    std::vector<vk::DeviceReport> d = {usable(0, "old GPU", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU),
                                       usable(1, "llvmpipe", VK_PHYSICAL_DEVICE_TYPE_CPU)};
    d[0].geometryShader = false;
    EXPECT_EQ(vk::selectDevice(d, "", false).index, 1u);
}

TEST(DeviceChoice, ByIndexAndByNameCaseInsensitive)
{
    std::vector<vk::DeviceReport> d = {usable(0, "llvmpipe (LLVM 15)", VK_PHYSICAL_DEVICE_TYPE_CPU),
                                       usable(1, "NVIDIA H100 PCIe", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU)};
    EXPECT_EQ(vk::selectDevice(d, "0", false).index, 0u);
    EXPECT_EQ(vk::selectDevice(d, "h100", false).index, 1u);
    EXPECT_EQ(vk::selectDevice(d, "LLVMPIPE", false).index, 0u);
}

TEST(DeviceChoice, ErrorsNameWhatIsWrong)
{
    std::vector<vk::DeviceReport> d = {usable(0, "llvmpipe", VK_PHYSICAL_DEVICE_TYPE_CPU)};
    EXPECT_NE(selectError(d, "7").find("no such device index"), std::string::npos);
    EXPECT_NE(selectError(d, "radeon").find("no device name contains it"), std::string::npos);
    EXPECT_NE(selectError({}, "").find("no Vulkan device"), std::string::npos);
    d[0].tessellationShader = false;
    d[0].fragmentStoresAndAtomics = false;
    std::string e = selectError(d, "");
    EXPECT_NE(e.find("tessellationShader"), std::string::npos) << e;
    EXPECT_NE(e.find("fragmentStoresAndAtomics"), std::string::npos) << e;
    EXPECT_NE(e.find("'llvmpipe'"), std::string::npos) << e;
}

TEST(DeviceChoice, SwapchainOnlyRequiredForWindows)
{
    vk::DeviceReport r = usable(0, "headless", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU);
    r.swapchain = false;
    EXPECT_TRUE(r.missing(false).empty());
    ASSERT_EQ(r.missing(true).size(), 1u);
    EXPECT_EQ(r.missing(true)[0], "VK_KHR_swapchain");
}

TEST(VulkanCore, ContextOnThisMachineIsClean)
{
    vk::Context ctx(test::validatedOptions());
    EXPECT_TRUE(ctx.validationEnabled());
    EXPECT_TRUE(ctx.report().missing(false).empty());
    EXPECT_GE(ctx.report().maxTessellationGenerationLevel, 64u);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(VulkanCore, BufferRoundTripThroughTheGpu)
{
    vk::Context ctx(test::validatedOptions());
    std::vector<uint32_t> data(1000);
    for (uint32_t i = 0; i < data.size(); ++i)
        data[i] = i * 2654435761u;
    size_t bytes = data.size() * sizeof(uint32_t);
    vk::Buffer device = ctx.createBufferWithData(
        {.size = bytes, .usage = vk::kStorage | vk::kTransferSrc, .name = "test.device"}, data.data(), bytes);
    vk::Buffer host = ctx.createBuffer(
        {.size = bytes, .usage = vk::kTransferDst, .memory = vk::Memory::Readback, .name = "test.host"});
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{.size = bytes};
        vkCmdCopyBuffer(cmd, device, host, 1, &region);
    });
    EXPECT_EQ(std::memcmp(host.mapped(), data.data(), bytes), 0);
    vk::Buffer moved = std::move(host);
    EXPECT_FALSE(host);
    EXPECT_TRUE(moved);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

namespace {

// Fills a buffer with a value (a transfer write).
class FillPass : public Pass {
public:
    FillPass(TrackedBuffer& b, uint32_t value) : buffer_(b), value_(value) {}
    const char* name() const override { return "fill"; }
    void declare(PassIo& io) override { io.use(buffer_, Access::TransferDst); }
    void record(VkCommandBuffer cmd, FrameContext&) override
    {
        vkCmdFillBuffer(cmd, buffer_.buffer, 0, VK_WHOLE_SIZE, value_);
    }

private:
    TrackedBuffer& buffer_;
    uint32_t value_;
};

// Copies one buffer into another; declares its accesses only when asked to.
class CopyPass : public Pass {
public:
    CopyPass(TrackedBuffer& src, TrackedBuffer& dst, VkDeviceSize bytes, bool declareAccesses)
        : src_(src), dst_(dst), bytes_(bytes), declare_(declareAccesses)
    {
    }
    const char* name() const override { return "copy"; }
    void declare(PassIo& io) override
    {
        if (declare_) {
            io.use(src_, Access::TransferSrc);
            io.use(dst_, Access::TransferDst);
        }
    }
    void record(VkCommandBuffer cmd, FrameContext&) override
    {
        VkBufferCopy region{.size = bytes_};
        vkCmdCopyBuffer(cmd, src_.buffer, dst_.buffer, 1, &region);
    }

private:
    TrackedBuffer& src_;
    TrackedBuffer& dst_;
    VkDeviceSize bytes_;
    bool declare_;
};

// `forceSync` false: the synchronization checks only as test::validatedOptions() has them.
uint32_t runFillThenCopy(bool declareAccesses, uint32_t& firstWord, std::vector<vk::ScopeTime>& times,
                         bool forceSync = true)
{
    vk::ContextOptions options = test::validatedOptions();
    options.synchronizationValidation = options.synchronizationValidation || forceSync;
    vk::Context ctx(options);
    constexpr VkDeviceSize kBytes = 1 << 16;
    vk::Buffer a = ctx.createBuffer({.size = kBytes, .usage = vk::kTransferSrc | vk::kTransferDst, .name = "test.a"});
    vk::Buffer b =
        ctx.createBuffer({.size = kBytes, .usage = vk::kTransferDst, .memory = vk::Memory::Readback, .name = "test.b"});
    TrackedBuffer ta{.buffer = a}, tb{.buffer = b};
    FillPass fill(ta, 0xC0FFEEu);
    CopyPass copy(ta, tb, kBytes, declareAccesses);
    {
        Frame frame(ctx, 1);
        FrameContext& fc = frame.begin({});
        std::vector<Pass*> passes = {&fill, &copy};
        frame.run(fc, passes);
        frame.submit(fc);
        frame.waitIdle();
        times = frame.timings();
    }
    std::memcpy(&firstWord, b.mapped(), sizeof(firstWord));
    return ctx.validationMessages();
}

} // namespace

TEST(FrameBarriers, DeclaredAccessesAreSynchronized)
{
    uint32_t word = 0;
    std::vector<vk::ScopeTime> times;
    EXPECT_EQ(runFillThenCopy(true, word, times), 0u);
    EXPECT_EQ(word, 0xC0FFEEu);
    ASSERT_EQ(times.size(), 2u);
    EXPECT_EQ(times[0].name, "fill");
    EXPECT_EQ(times[1].name, "copy");
    for (const vk::ScopeTime& t : times)
        EXPECT_GE(t.milliseconds, 0.0);
}

TEST(Timestamps, ScopesOfOneNameAddUpInTheOrderTheyFirstCame)
{
    // The physics' kernels recorded beside several passes are scopes of one name: a frame's
    // profile and the window's panel show them as one line, their sum, where the first one came.
    std::vector<vk::ScopeTime> scopes = {
        {"physics", 0.25}, {"light.opacity", 0.5}, {"physics", 0.125}, {"strands.count", 1.0}, {"physics", 0.0625}};
    std::vector<vk::ScopeTime> byName = vk::timingsByName(scopes);
    ASSERT_EQ(byName.size(), 3u);
    EXPECT_EQ(byName[0].name, "physics");
    EXPECT_DOUBLE_EQ(byName[0].milliseconds, 0.4375);
    EXPECT_EQ(byName[1].name, "light.opacity");
    EXPECT_DOUBLE_EQ(byName[1].milliseconds, 0.5);
    EXPECT_EQ(byName[2].name, "strands.count");
    EXPECT_DOUBLE_EQ(byName[2].milliseconds, 1.0);
    EXPECT_TRUE(vk::timingsByName({}).empty());
}

TEST(FrameBarriers, UndeclaredReadIsCaughtBySyncValidation)
{
    // Without the declaration no barrier separates the fill from the copy: the validation layer's
    // synchronization checks must report the read-after-write hazard. (This is what proves the
    // barriers in the test above come from the declarations.)
    uint32_t word = 0;
    std::vector<vk::ScopeTime> times;
    testing::internal::CaptureStderr();
    uint32_t messages = runFillThenCopy(false, word, times);
    std::string err = testing::internal::GetCapturedStderr();
    EXPECT_GT(messages, 0u);
    EXPECT_NE(err.find("HAZARD"), std::string::npos) << err;
}

TEST(FrameBarriers, TheSyncValidationRoundReportsHazards)
{
    // scripts/test.sh --ci runs the GPU suites again with WISP_TEST_SYNC_VALIDATION=1: there the
    // tests' own context options must catch the hazard above (else that round checks nothing).
    if (!test::validatedOptions().synchronizationValidation)
        GTEST_SKIP() << "runs in the synchronization-validation round (WISP_TEST_SYNC_VALIDATION=1)";
    uint32_t word = 0;
    std::vector<vk::ScopeTime> times;
    testing::internal::CaptureStderr();
    uint32_t messages = runFillThenCopy(false, word, times, /*forceSync=*/false);
    std::string err = testing::internal::GetCapturedStderr();
    EXPECT_GT(messages, 0u);
    EXPECT_NE(err.find("HAZARD"), std::string::npos) << err;
}

namespace {

// Records a fill into a fresh buffer in each of `frames` frames and retires the buffer into the
// frame (freed when its fence signals). Freed any earlier, the validation layer reports it (and
// lavapipe crashes: which is why there is no in-process counter-test).
uint32_t fillThrowawayBuffers(int frames)
{
    vk::Context ctx(test::validatedOptions());
    {
        Frame frame(ctx, 2);
        for (int n = 0; n < frames; ++n) {
            FrameContext& fc = frame.begin({});
            vk::Buffer temp = ctx.createBuffer({.size = 4096, .usage = vk::kTransferDst, .name = "test.throwaway"});
            vkCmdFillBuffer(fc.cmd, temp, 0, VK_WHOLE_SIZE, uint32_t(n));
            fc.retire(std::move(temp));
            frame.submit(fc);
        }
        frame.waitIdle();
    }
    return ctx.validationMessages();
}

} // namespace

TEST(FrameDeletion, RetiredObjectsLiveUntilTheirFrameIsDone)
{
    EXPECT_EQ(fillThrowawayBuffers(5), 0u);
}

TEST(DeviceLoss, VkCheckThrowsDeviceLostForALostDeviceOnly)
{
    auto lost = [] { return VK_ERROR_DEVICE_LOST; };
    auto exhausted = [] { return VK_ERROR_OUT_OF_POOL_MEMORY; };
    try {
        VK_CHECK(lost());
        ADD_FAILURE() << "VK_CHECK let VK_ERROR_DEVICE_LOST through";
    } catch (const vk::DeviceLost& e) {
        std::string m = e.what();
        EXPECT_EQ(m.rfind("lost() at ", 0), 0u) << m;
        EXPECT_NE(m.find("test_device.cpp:"), std::string::npos) << m;
    }
    try {
        VK_CHECK(exhausted());
        ADD_FAILURE() << "VK_CHECK let VK_ERROR_OUT_OF_POOL_MEMORY through";
    } catch (const vk::DeviceLost&) {
        ADD_FAILURE() << "another error was reported as a lost device";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("VK_ERROR_OUT_OF_POOL_MEMORY"), std::string::npos) << e.what();
    }
}

TEST(DeviceLoss, InjectedLossReachesEverySubmissionAndTearsDownCleanly)
{
    // WISP_INJECT_DEVICE_LOST is read once, when the context is made: the second submission and
    // every later one report the device lost.
    setenv("WISP_INJECT_DEVICE_LOST", "2", 1);
    auto ctx = std::make_unique<vk::Context>(test::validatedOptions());
    unsetenv("WISP_INJECT_DEVICE_LOST");
    {
        vk::Buffer buffer = ctx->createBuffer({.size = 256, .usage = vk::kTransferDst, .name = "test.lost"});
        TrackedBuffer tracked{.buffer = buffer};
        FillPass fill(tracked, 7u);
        std::vector<Pass*> passes = {&fill};
        Frame frame(*ctx, 1);
        FrameContext& first = frame.begin({});
        frame.run(first, passes);
        frame.submit(first); // submission 1 reaches the driver
        frame.waitIdle();
        FrameContext& second = frame.begin({});
        frame.run(second, passes);
        EXPECT_THROW(frame.submit(second), vk::DeviceLost);
    } // the frame's and the buffer's teardown after the loss returns
    EXPECT_THROW(ctx->submitAndWait([](VkCommandBuffer) {}), vk::DeviceLost); // a lost device stays lost
    EXPECT_EQ(ctx->validationMessages(), 0u);
    ctx.reset(); // and so does the context's
}
