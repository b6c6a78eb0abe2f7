// tests/test_reference.cpp: the path-traced reference on the device (lavapipe), validation on: the
// fibre BSDF's kernel (fiber_probe.comp) against the CPU reference on random inputs; the path
// tracer's kernel against its CPU twin over the same shared header, pixel by pixel; the same
// picture for the same seed; the error against a many-sample picture falling as 1/sqrt(samples);
// and `wisp render --reference`'s bad input and a render stopped midway.
#include "app/image/image_io.h"
#include "app/session/reference_render.h"
#include "cli_support.h"
#include "fiber_bsdf_cases.h"
#include "gpu/compute_stage.h"
#include "gpu/frame.h"
#include "small_groomed_head.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sys/wait.h>

using namespace wisp;

namespace {

// fiber_probe.comp over `cases`, its results read back.
std::vector<gpu::FiberProbeResult> probeOnGpu(const vk::Context& ctx, const std::vector<gpu::FiberProbeCase>& cases)
{
    VkDeviceSize resultBytes = cases.size() * sizeof(gpu::FiberProbeResult);
    vk::Buffer input = ctx.createBufferWithData(
        {.size = cases.size() * sizeof(gpu::FiberProbeCase), .usage = vk::kStorage, .name = "test.fiber.cases"},
        cases.data(), cases.size() * sizeof(gpu::FiberProbeCase));
    vk::Buffer results =
        ctx.createBuffer({.size = resultBytes, .usage = vk::kStorage | vk::kTransferSrc, .name = "test.fiber.results"});
    vk::Buffer host = ctx.createBuffer(
        {.size = resultBytes, .usage = vk::kTransferDst, .memory = vk::Memory::Readback, .name = "test.fiber.host"});
    TrackedBuffer tracked{.buffer = results};
    gpu::FiberProbePush push{.count = uint32_t(cases.size())};
    vk::ComputeKernel kernel;
    ComputeStage probe{.uses = {constantBuffer(gpu::kFiberProbeBindingCases, input),
                                storageBuffer(gpu::kFiberProbeBindingResults, tracked, Access::ComputeWrite)},
                       .record = [&](StageCommands& c) {
                           c.dispatch(kernel, push, vk::groupCount(push.count, gpu::kFiberProbeGroupSize));
                       }};
    ComputeStage readBack{.uses = {commandUse(tracked, Access::TransferSrc)},
                          .record = [&](StageCommands& c) { c.copyToHost(tracked, host, resultBytes); }};
    ComputeStage both[] = {probe, readBack};
    StageLayout layout(ctx, both, sizeof(push), "test.fiber.layout");
    kernel = vk::createComputeKernel(ctx, layout.layout(), "fiber_probe.comp", "test.fiber.pipeline");
    ComputeStagePass run("test.fiber.probe", layout, [&] { return probe; });
    ComputeStagePass copy("test.fiber.readback", layout, [&] { return readBack; });
    Frame frame(ctx, 1);
    FrameContext& fc = frame.begin({});
    Pass* passes[] = {&run, &copy};
    frame.run(fc, passes);
    frame.submit(fc);
    frame.waitIdle();
    std::vector<gpu::FiberProbeResult> out(cases.size());
    std::memcpy(out.data(), host.mapped(), resultBytes);
    return out;
}

// The small scene's reference frame at `width` x `height` (8 strands a guide, 12 divisions).
ReferenceFrame smallReference(const vk::Context& ctx, uint32_t width, uint32_t height, uint32_t seed = 1)
{
    RenderSettings s = test::smallRenderSettings();
    s.width = width;
    s.height = height;
    GroomedHead scene = test::smallGroomedHead(40);
    HairSession session(ctx, scene, SimSettings{}, stillTimeline(glm::vec4(0.0f), glm::vec3(0.0f), s.light));
    ReferenceOptions o;
    o.seed = seed;
    return prepareReference(ctx, session, s, 0, 30.0f, o);
}

// Each pixel's mean radiance over the samples that met the scene (0 where none did), row-major.
std::vector<glm::vec3> meanRadiance(const std::vector<glm::vec4>& sums, size_t pixels, uint32_t samples)
{
    std::vector<glm::vec3> out(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        glm::vec4 s = sums[i] + sums[pixels + i];
        float hits = float(samples) - s.w;
        out[i] = hits > 0.0f ? glm::vec3(s) / hits : glm::vec3(0.0f);
    }
    return out;
}

} // namespace

// The GPU's eval, pdf and sampling are the CPU reference's on random inputs, to 1e-5 (an awkward
// count: not a multiple of the workgroup).
TEST(Reference, FiberBsdfOnTheGpuMatchesTheCpuReference)
{
    vk::Context ctx(test::validatedOptions());
    std::vector<test::FiberCase> cases = test::randomFiberCases(1037, 29);
    std::vector<gpu::FiberProbeCase> input;
    for (const test::FiberCase& c : cases)
        input.push_back(test::probeCase(c));
    std::vector<gpu::FiberProbeResult> got = probeOnGpu(ctx, input);
    ASSERT_EQ(got.size(), cases.size());
    for (size_t i = 0; i < cases.size(); ++i) {
        const test::FiberCase& c = cases[i];
        shading::HairBsdf ref(test::hairParams(c));
        glm::vec3 wi;
        float samplePdf = 0.0f;
        glm::vec3 sampleF = ref.sampleF(c.wo, {c.u.x, c.u.y, c.u.z, c.u.w}, &wi, &samplePdf);
        float cosWi = std::abs(wi.z);
        test::expectFiberNear(got[i], ref.f(c.wo, c.wi), ref.pdf(c.wo, c.wi), wi, samplePdf,
                              cosWi > 0.0f ? sampleF * cosWi : sampleF, 1e-5f, c);
        if (HasFailure())
            break; // one case's report is enough
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// The kernel's paths are its CPU twin's (reference_scene.cpp tracePixel, the same referenceSample):
// pixels on the hair, the head and the backdrop, two samples each.
TEST(Reference, KernelMatchesItsCpuTwinPixelByPixel)
{
    vk::Context ctx(test::validatedOptions());
    ReferenceFrame f = smallReference(ctx, 48, 36);
    ASSERT_GT(f.scene.segments.size(), 1000u);
    ASSERT_GT(f.scene.triangles.size(), 1000u);
    ReferenceTracer tracer(ctx, f.scene, f.params);
    tracer.render(2, 2);
    std::vector<glm::vec4> sums = tracer.sums();
    size_t pixels = size_t(f.params.width) * f.params.height;
    int compared = 0, matched = 0, backdrop = 0, lit = 0;
    uint64_t cpuRays = 0;
    for (uint32_t y = 2; y < f.params.height; y += 5)
        for (uint32_t x = 3; x < f.params.width; x += 7) {
            reference::PixelSums cpu = reference::tracePixel(f.scene, f.params, {x, y}, 0, 2);
            cpuRays += cpu.rays;
            size_t at = size_t(y) * f.params.width + x;
            for (int half = 0; half < 2; ++half) {
                glm::vec4 g = sums[size_t(half) * pixels + at], c = cpu.sums[size_t(half)];
                ++compared;
                backdrop += c.w > 0.0f;
                lit += glm::length(glm::vec3(c)) > 0.0f;
                // The same path, up to the transcendental functions' last bits: a path whose roulette
                // or grazing hit goes the other way on one of them differs whole, hence a share.
                bool same = g.w == c.w && glm::length(glm::vec3(g - c)) <= 1e-3f * (glm::length(glm::vec3(c)) + 1e-3f);
                matched += same;
            }
        }
    EXPECT_GT(backdrop, 0);
    EXPECT_GT(lit, compared / 4);
    EXPECT_GE(matched, compared * 9 / 10) << matched << " of " << compared << " paths the same";
    // Every pixel's rays, counted by the kernel: at least one a sample, and about as many as the twin
    // casts for its pixels (theirs, scaled by the share of pixels compared).
    EXPECT_GE(tracer.raysCast(), 2 * pixels);
    double perPixelGpu = double(tracer.raysCast()) / double(pixels), perPixelCpu = double(cpuRays) / (compared / 2);
    EXPECT_GT(perPixelCpu, 0.5 * perPixelGpu);
    EXPECT_LT(perPixelCpu, 2.0 * perPixelGpu);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// The same seed, the same sums bit for bit; another seed, another picture.
TEST(Reference, SameSeedSamePicture)
{
    vk::Context ctx(test::validatedOptions());
    ReferenceFrame f = smallReference(ctx, 40, 30, 7);
    auto render = [&](const ReferenceFrame& frame) {
        ReferenceTracer tracer(ctx, frame.scene, frame.params);
        tracer.render(4, 2);
        return tracer.sums();
    };
    std::vector<glm::vec4> a = render(f), b = render(f);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)), 0);
    ReferenceFrame g = f;
    g.params.seed = 8;
    std::vector<glm::vec4> c = render(g);
    EXPECT_NE(std::memcmp(a.data(), c.data(), a.size() * sizeof(glm::vec4)), 0);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// Monte Carlo's error falls as 1/sqrt(samples): against a 256-sample picture of another seed, the
// RMS error of 4 and of 16 samples per pixel (each the mean over 3 seeds, to steady it) differ by
// about 2 (16/4 = 4 times the samples); 1.5..2.7 allows for the reference's own noise and the spread.
TEST(Reference, ErrorFallsAsOneOverTheRootOfTheSamples)
{
    vk::Context ctx(test::validatedOptions());
    ReferenceFrame f = smallReference(ctx, 24, 18, 100);
    size_t pixels = size_t(f.params.width) * f.params.height;
    auto mean = [&](uint32_t seed, uint32_t samples) {
        ReferenceFrame g = f;
        g.params.seed = seed;
        ReferenceTracer tracer(ctx, g.scene, g.params);
        tracer.render(samples, 16);
        return meanRadiance(tracer.sums(), pixels, samples);
    };
    std::vector<glm::vec3> truth = mean(100, 256);
    auto rmsError = [&](uint32_t samples) {
        double total = 0.0;
        for (uint32_t seed = 1; seed <= 3; ++seed) {
            std::vector<glm::vec3> m = mean(seed, samples);
            double sum = 0.0;
            for (size_t i = 0; i < pixels; ++i) {
                glm::vec3 d = m[i] - truth[i];
                sum += double(glm::dot(d, d));
            }
            total += std::sqrt(sum / double(pixels));
        }
        return total / 3.0;
    };
    double e4 = rmsError(4), e16 = rmsError(16);
    ASSERT_GT(e16, 0.0);
    EXPECT_GT(e4 / e16, 1.5) << "error at 4 spp " << e4 << ", at 16 spp " << e16;
    EXPECT_LT(e4 / e16, 2.7) << "error at 4 spp " << e4 << ", at 16 spp " << e16;
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(Cli, RenderReferenceWritesAPngAndItsNoise)
{
    test::TempDir dir;
    auto r = test::runWisp("--validation render --reference --spp 2 --width 32 --height 24 --guides 30 "
                           "--set strands_per_guide=2 --out '" +
                           (dir / "ref.png").string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "ref.png"));
    EXPECT_NE(r.out.find("reference: 2 samples per pixel at 32x24"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("noise: "), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("reference ["), std::string::npos) << r.err; // the progress bar
}

// --out F.exr: the same render's linear radiance and coverage (decoded by ffmpeg), which the PNG of
// the same seed is: where every sample met the scene, the PNG is the EXR's radiance exposed,
// tone-mapped and sRGB-encoded; where none did, the EXR is 0 with alpha 0. A real-time frame has no
// linear output: refused, nothing written.
TEST(Cli, RenderReferenceWritesLinearRadianceAndCoverageAsExr)
{
    test::TempDir dir;
    std::string args = "--validation render --reference --spp 4 --width 32 --height 24 --guides 30 "
                       "--set strands_per_guide=2 --set exposure=1.5 --out '";
    auto png = test::runWisp(args + (dir / "ref.png").string() + "'");
    ASSERT_EQ(png.status, 0) << png.err;
    auto exr = test::runWisp(args + (dir / "ref.exr").string() + "'");
    ASSERT_EQ(exr.status, 0) << exr.err;
    std::string command = "ffmpeg -v error -y -i '" + (dir / "ref.exr").string() +
                          "' -f rawvideo -pix_fmt gbrapf32le '" + (dir / "ref.raw").string() + "' 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    std::string raw = test::readFile(dir / "ref.raw");
    constexpr size_t kPixels = 32 * 24;
    ASSERT_EQ(raw.size(), kPixels * 16);
    auto plane = [&](int p, size_t i) {
        float f = 0.0f;
        std::memcpy(&f, raw.data() + (size_t(p) * kPixels + i) * 4, 4);
        return f;
    };
    PngImage picture = readPng(dir / "ref.png", "test");
    int covered = 0, empty = 0;
    for (size_t i = 0; i < kPixels; ++i) {
        glm::vec3 rgb(plane(2, i), plane(0, i), plane(1, i));
        float alpha = plane(3, i);
        ASSERT_GE(alpha, 0.0f);
        ASSERT_LE(alpha, 1.0f);
        if (alpha == 0.0f) {
            EXPECT_EQ(rgb, glm::vec3(0.0f)) << i;
            ++empty;
        } else if (alpha == 1.0f) {
            glm::vec3 display = gpu::toneMapAces(rgb * 1.5f);
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(picture.rgba[i * 4 + size_t(k)] / 257.0, 255.0 * gpu::encodeSrgb(display[k]), 0.51)
                    << i << " channel " << k;
            ++covered;
        }
    }
    EXPECT_GT(covered, 20);
    EXPECT_GT(empty, 20);
    auto realTime = test::runWisp("render --width 32 --height 24 --out '" + (dir / "frame.exr").string() + "'");
    EXPECT_EQ(realTime.status, 2);
    EXPECT_NE(realTime.err.find("linear output (.exr) is written by --reference"), std::string::npos) << realTime.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "frame.exr"));
    auto missing = test::runWisp("render --reference --out '" + (dir / "no" / "ref.exr").string() + "'");
    EXPECT_EQ(missing.status, 2);
    EXPECT_NE(missing.err.find("does not exist"), std::string::npos) << missing.err;
}

// Bad --spp (and its options without --reference): one line naming it, exit 2, no file.
TEST(Cli, RenderReferenceRefusesBadSamples)
{
    test::TempDir dir;
    std::string out = " --out '" + (dir / "ref.png").string() + "'";
    for (const char* spp : {"0", "-3", "many", "2000000"}) {
        auto r = test::runWisp("render --reference --spp " + std::string(spp) + out);
        EXPECT_EQ(r.status, 2) << spp << "\n" << r.err;
        EXPECT_NE(r.err.find("--spp"), std::string::npos) << spp << "\n" << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    auto r = test::runWisp("render --spp 16" + out);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("--spp, --sample-seed and --bounces are options of --reference"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "ref.png"));
}

// A render stopped midway (SIGINT, as Ctrl-C) leaves nothing in the output's folder: the PNG is
// written whole at the end or not at all.
TEST(Cli, RenderReferenceCancelledLeavesNoFile)
{
    test::TempDir dir;
    std::string command = "timeout -s INT 3 '" WISP_BINARY "' render --reference --spp 1000000 --width 32 --height 24 "
                          "--guides 30 --set strands_per_guide=2 --out '" +
                          (dir / "ref.png").string() + "' >/dev/null 2>&1";
    int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 124); // timeout's status: it was still rendering when stopped
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}
