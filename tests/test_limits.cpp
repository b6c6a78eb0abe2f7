// tests/test_limits.cpp: absurd values are range errors, not undefined behaviour: every setting
// `--set` takes against NaN, infinities and huge numbers, and each range's ends; the sphere,
// wind, offset and per-part values; loaded hair too large for floats once placed; the workload's 32-bit counts, and its
// GPU memory estimated and checked against a device before anything is allocated. (The same through the real binary:
// test_cli.cpp, BadInput.*.)
#include "app/settings/hair_source.h"
#include "app/settings/settings_table.h"
#include "app/settings/workload.h"
#include "core/error.h"
#include "gpu/context.h"
#include "physics/groomed_head.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <sstream>

using namespace wisp;

namespace {

// The UserError `f` throws ("" when it throws none).
template <typename F> std::string errorOf(F&& f)
{
    try {
        f();
    } catch (const UserError& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(Limits, EverySettingRefusesNonFiniteAndAbsurdValues)
{
    for (const SettingSpec& spec : settingSpecs()) {
        for (const char* value : {"nan", "-nan", "inf", "-inf", "1e309", "1e30", "-1e30", "", "1,2", "0x10"}) {
            Settings settings;
            std::string what = errorOf([&] { applySetting(settings, spec.name + "=" + value); });
            EXPECT_EQ(what.rfind("--set " + spec.name + ": ", 0), 0u) << spec.name << "=" << value << ": " << what;
        }
    }
}

TEST(Limits, NumericSettingsStayInsideTheirRange)
{
    // Each range's ends are accepted and just past them refused, for every numeric setting (and
    // every component of the vectors and colours).
    int checked = 0;
    for (const SettingSpec& spec : settingSpecs()) {
        if (spec.type == SettingType::OnOff || spec.type == SettingType::Choice)
            continue;
        bool vector = spec.type == SettingType::Vector || spec.type == SettingType::Color;
        auto set = [&](double v) {
            std::ostringstream s;
            s.precision(17);
            s << v;
            std::string text = vector ? s.str() + "," + s.str() + "," + s.str() : s.str();
            Settings settings;
            return errorOf([&] { applySetting(settings, spec.name + "=" + text); });
        };
        double lo = spec.range.min, hi = spec.range.max;
        EXPECT_EQ(set(lo), "") << spec.name;
        EXPECT_EQ(set(hi), "") << spec.name;
        std::string below = set(lo - std::max(1.0, std::abs(lo))), above = set(hi + std::max(1.0, std::abs(hi)));
        std::string range = spec.allowed().substr(vector ? 9 : 0); // "lo .. hi unit", without "x,y,z in "
        range = range.substr(0, range.find(" | "));                // and without " | part"
        EXPECT_NE(below.find("is out of range: allowed " + range), std::string::npos) << spec.name << ": " << below;
        EXPECT_NE(above.find("is out of range"), std::string::npos) << spec.name << ": " << above;
        ++checked;
    }
    EXPECT_GT(checked, 40);
}

TEST(Limits, SphereAndOffsetMustBeFiniteAndInRange)
{
    auto error = [](const std::string& text, size_t n) {
        return errorOf([&] { parseNumbers(text, n, "x,y,z,r", kPositionRange, "head units", "--sphere"); });
    };
    EXPECT_NE(error("nan,0,0,1", 4).find("--sphere: the first value (nan) is not a finite number"), std::string::npos);
    EXPECT_NE(error("0,0,0,inf", 4).find("--sphere: the fourth value (inf)"), std::string::npos);
    EXPECT_NE(error("0,0,1e9,1", 4)
                  .find("--sphere: the third value (1000000000) is out of range: allowed -10000 .. 10000 head units"),
              std::string::npos);
    EXPECT_NE(error("0,0,1", 4).find("is not 4 numbers x,y,z,r"), std::string::npos);
    EXPECT_EQ(error("0,1,0,0.5", 4), "");
    Settings settings;
    EXPECT_NE(errorOf([&] {
                  applySetting(settings, "wind=nan,0,0");
              }).find("--set wind: the first value (nan) is not a finite number"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { applySetting(settings, "wind=0,0,1e9"); }).find("out of range"), std::string::npos);
    EXPECT_EQ(errorOf([&] { applySetting(settings, "wind=-100,0,100"); }), "");
    EXPECT_EQ(settings.sim.wind, glm::vec3(-100.0f, 0.0f, 100.0f));
}

TEST(Limits, PartValuesRefuseNonFiniteAndOutOfRange)
{
    for (const char* spec : {"0:global=nan", "0:local=inf", "0:damping=-0.1", "0:drag=1e40", "0:drag=-inf",
                             "0:global=1e-50x", "0:global=part"}) {
        std::vector<PartSettings> parts(1);
        std::string what = errorOf([&] { HairSource::applyPartOverride(parts, spec); });
        EXPECT_NE(what.find(std::string("--part ") + spec), std::string::npos) << spec << ": " << what;
    }
}

TEST(Limits, LoadedHairTooLargeForFloatsIsRefusedNamingItsLine)
{
    // A TressFX 2 strand with coordinates near the float maximum (placed 10x larger, they were not
    // finite; 6e38 apart, a segment's length overflowed): refused as it is read, past the range
    // the float math handles (assets/text.h kMaxCoordinate), naming the file and the line.
    test::TempDir dir;
    std::string text = "numStrands 1\nstrand 0 numVerts 3 texcoord 0 0\n0 0 0\n0 3e38 0\n0 3.2e38 0\n";
    test::writeFile(dir / "huge.tfx", text);
    HairPartSource part{.file = dir / "huge.tfx", .placement = HairPlacement{.scale = 10.0f}, .settings = {}};
    std::string what = errorOf([&] { buildLoadedHead(defaultHeadPath(), {part}, 8); });
    EXPECT_NE(what.find("huge.tfx:4: coordinate 3e+38 is out of the range Wisp's float math handles"),
              std::string::npos)
        << what;
    test::writeFile(dir / "far.tfx", "numStrands 1\nstrand 0 numVerts 2 texcoord 0 0\n-3e38 0 0\n3e38 0 0\n");
    part = {.file = dir / "far.tfx", .placement = HairPlacement{}, .settings = {}};
    what = errorOf([&] { buildLoadedHead(defaultHeadPath(), {part}, 4); });
    EXPECT_NE(what.find("far.tfx:3: coordinate -3e+38 is out of the range"), std::string::npos) << what;
}

// ---- The workload: counts and GPU memory -------------------------------------------------------

TEST(Workload, SolverMemoryByHand)
{
    // 33 strands pad to 64 (blocks of 32) x 4 vertices = 256 slots of positions, velocities,
    // tangents and rest vertices (16 bytes each); 33 strand infos; 512 grid nodes of 4 64-bit
    // fixed-point sums (or one 16-byte float node), twice (this step's and the next's); parameters
    // and counters.
    uint64_t common = 33 * 16 + sizeof(gpu::SimParams) + sizeof(gpu::SimCounters);
    EXPECT_EQ(solverDeviceBytes(33, 4, 512, true), 256u * 64u + 512u * 2u * 32u + common);
    EXPECT_EQ(solverDeviceBytes(33, 4, 512, false), 256u * 64u + 512u * 2u * 16u + common);
    // The largest grown workload: 2e6 x 64 vertices, a 256^3 grid: about 8.5 GB, in 64 bits.
    uint64_t big = solverDeviceBytes(kMaxGuides, kMaxVerticesPerStrand, 256ull * 256 * 256, true);
    EXPECT_GT(big, uint64_t(8) << 30);
}

namespace {

// The small workload the memory estimates are checked against by hand: 100 x 50 pixels, 4 samples,
// 64² light maps, 10 OIT nodes a pixel, an 8³ grid.
RenderSettings byHandSettings()
{
    RenderSettings r;
    r.width = 100;
    r.height = 50;
    r.samples = 4;
    r.shadows.mapSize = 64;
    r.transparency.mode = Transparency::Oit;
    r.transparency.oitNodesPerPixel = 10;
    return r;
}

SimSettings byHandSim()
{
    SimSettings sim;
    sim.gridResolution = 8;
    return sim;
}

} // namespace

TEST(Workload, RenderMemoryByHand)
{
    RenderSettings r = byHandSettings();
    SimSettings sim = byHandSim();
    r.hairRaster = HairRaster::Graphics; // (the compute path's buffers: ComputeRasterMemoryByHand)
    GpuMemory m = estimateGpuMemory({.guides = 10, .verticesPerStrand = 4, .sim = sim, .render = &r});
    EXPECT_EQ(m.simulation, solverDeviceBytes(10, 4, 512, true));
    EXPECT_EQ(m.raster, 0u) << "drawn by the graphics pipeline";
    // MSAA colour (4 bytes) and depth (4 bytes) x 4 samples, and the resolved colour, per pixel.
    EXPECT_EQ(m.target, 5000u * (16u + 16u + 4u));
    // Two depth maps (4 bytes), the hair depth as values (R32F) and the opacity layers (RGBA16F) per texel.
    EXPECT_EQ(m.lightMaps, 64u * 64u * 20u);
    // A list head (4 bytes), the resolved colour (8) and 10 nodes of 12 bytes per pixel.
    EXPECT_EQ(m.oit, 5000u * (4u + 8u + 120u));
    // A triangle of guides (16 bytes) each, the 64^2 x 5 RGBA32F tables, two indices per guide line.
    EXPECT_EQ(m.hair, 10u * 16u + 64u * 64u * 5u * 16u + 10u * 3u * 2u * 4u);
    EXPECT_EQ(m.total(), m.simulation + m.hair + m.target + m.lightMaps + m.oit + m.raster);
    r.transparency.mode = Transparency::Msaa;
    EXPECT_EQ(estimateGpuMemory({.guides = 10, .verticesPerStrand = 4, .sim = sim, .render = &r}).oit, 0u);
    EXPECT_EQ(estimateGpuMemory({.guides = 10, .verticesPerStrand = 4, .sim = sim, .render = nullptr}).total(),
              m.simulation);
    // No guides (the head alone): nothing simulated, no guide triangles.
    GpuMemory head = estimateGpuMemory({.guides = 0, .verticesPerStrand = 4, .sim = sim, .render = &r});
    EXPECT_EQ(head.simulation, 0u);
    EXPECT_EQ(head.hair, 64u * 64u * 5u * 16u);
}

TEST(Workload, ComputeRasterMemoryByHand)
{
    RenderSettings r = byHandSettings();
    r.strands.strandsPerGuide = 4;
    r.strands.divisions = 3;
    r.shadows.strandFraction = 0.25f; // one strand a guide into the light's maps
    r.hairRaster = HairRaster::Compute;
    SimSettings sim = byHandSim();
    Workload w{.guides = 10, .verticesPerStrand = 4, .sim = sim, .render = &r};
    GpuMemory m = estimateGpuMemory(w);
    uint64_t byHand = 10u * 16u                    // a triangle of guides (uvec4) each
                      + 10u * 4u * 32u             // each guide's curve at its strands' 4 points: position, tangent
                      + 44u                        // the counters
                      + 10u * 4u * 4u * (16u + 4u) // 40 camera strands x 4 vertices: a vec4 and a packed colour
                      + 10u * 1u * 4u * (16u + 4u) // 10 light strands x 4 vertices
                      + 3u * 5001u * 4u        // counts, offsets and reserved slots per pixel, and one past the last
                      + 5000u * 8u             // each pixel's depth range
                      + 13u * 7u * 4u          // each 8 x 8 tile's farthest mesh depth (100 x 50 pixels)
                      + 5u * 4u                // the scan's block sums: ceil(5001 / 1024)
                      + 64u * 64u * (4u + 16u) // the light's depth and opacity layers per texel
                      + (1u << 18) * 8u        // at least 2^18 fragments of 8 bytes (120 segments x 8 is fewer)
                      + 64u * 48u              // the pieces the frame may record: their pixels and dispatches
                      + (1u << 20) * 16u       // the spill list: 2^20 fragments with their pixel and number
                      + 5000u * 8u             // the hair image, RGBA16F
                      + 5000u * 4u * 4u        // the meshes' depth samples the strands test against
                      // the meshes in compute: each sample's depth and triangle, their colour
                      // (RGBA16F) and the frame (RGBA8)
                      + 5000u * (4u * 8u + 8u + 4u);
    EXPECT_EQ(m.raster, byHand);
    EXPECT_EQ(m.total(), m.simulation + m.hair + m.target + m.lightMaps + m.oit + m.raster);
    // The OIT lists are the graphics path's: not made when the compute path draws the hair.
    EXPECT_EQ(m.oit, 0u);
    r.hairRaster = HairRaster::Auto; // compute everywhere measured
    EXPECT_EQ(estimateGpuMemory(w).raster, byHand);
    r.hairRaster = HairRaster::Graphics;
    EXPECT_EQ(estimateGpuMemory(w).raster, 0u);
    r.hairRaster = HairRaster::Compute;
    // Shadows off: no light strands (each buffer is at least 16 bytes).
    r.shadows.enabled = false;
    EXPECT_EQ(estimateGpuMemory(w).raster, byHand - 10u * 4u * 20u + 2u * 16u);
    r.shadows.enabled = true;
    // Many segments: 8 fragments each; within the device's storage-buffer range.
    r.strands.strandsPerGuide = 1000;
    r.strands.divisions = 100; // 1e6 segments: 8e6 fragments, 64 MB
    vk::DeviceReport small;
    small.maxStorageBufferRange = 1u << 20; // holds 2^17 fragments
    EXPECT_EQ(estimateGpuMemory(w).raster - estimateGpuMemory(w, small).raster, 8000000u * 8u - (1u << 20));
    // Within the budget: an eighth of the device's memory (8 MiB of 64), or fragment_budget.
    vk::DeviceReport device;
    device.maxStorageBufferRange = std::numeric_limits<uint32_t>::max();
    device.deviceLocalBytes = uint64_t(64) << 20;
    uint64_t unbounded = estimateGpuMemory(w).raster;
    EXPECT_EQ(unbounded - estimateGpuMemory(w, device).raster, 8000000u * 8u - (8u << 20));
    r.fragmentBudgetMiB = 4;
    EXPECT_EQ(unbounded - estimateGpuMemory(w).raster, 8000000u * 8u - (4u << 20));
    r.fragmentBudgetMiB = 0;
    // No hair, or the simulation alone: nothing drawn.
    EXPECT_EQ(estimateGpuMemory({.guides = 0, .verticesPerStrand = 4, .sim = sim, .render = &r}).raster, 0u);
    EXPECT_EQ(estimateGpuMemory({.guides = 10, .verticesPerStrand = 4, .sim = sim, .render = nullptr}).raster, 0u);
}

TEST(Workload, ABufferPastOneStorageBuffersRangeIsRefusedUpFront)
{
    // 50 guides x 4096 strands x 65 vertices of 16 bytes: 212,992,000 bytes of strand vertices for
    // the compute path, past lavapipe's 128 MiB a storage buffer may hold (validation would
    // refuse the binding; a driver that does not check would read past it).
    vk::DeviceReport device;
    device.name = "Range GPU";
    device.deviceLocalBytes = uint64_t(8) << 30;
    device.maxStorageBufferRange = 134217728;
    RenderSettings r;
    r.width = 64;
    r.height = 48;
    r.strands.strandsPerGuide = 4096;
    r.strands.divisions = 64;
    r.hairRaster = HairRaster::Compute;
    Workload w{.guides = 50, .verticesPerStrand = 16, .sim = {}, .render = &r};
    std::string what = errorOf([&] { checkWorkload(w, device); });
    EXPECT_NE(what.find("strands.vertices needs 212992000 bytes"), std::string::npos) << what;
    EXPECT_NE(what.find("more than the 134217728 bytes one storage buffer may hold on 'Range GPU'"), std::string::npos)
        << what;
    r.strands.strandsPerGuide = 2048; // 106,496,000 bytes: fits
    EXPECT_EQ(errorOf([&] { checkWorkload(w, device); }), "");
}

TEST(Workload, DrawnStrandsAndSegmentsMustFit32Bits)
{
    RenderSettings r;
    r.strands.strandsPerGuide = 4096;
    r.strands.divisions = 1;
    Workload w{.guides = kMaxGuides, .verticesPerStrand = 16, .sim = {}, .render = &r};
    std::string what = errorOf([&] { checkCounts(w); });
    EXPECT_NE(what.find("8192000000 drawn strands"), std::string::npos) << what;
    r.strands.strandsPerGuide = 2000; // 4e9 strands fit, their segments do not
    r.strands.divisions = 2;
    what = errorOf([&] { checkCounts(w); });
    EXPECT_NE(what.find("8000000000 segments"), std::string::npos) << what;
    r.strands.divisions = 1;
    EXPECT_EQ(errorOf([&] { checkCounts(w); }), "");
    w.render = nullptr; // the simulation alone draws nothing
    r.strands.strandsPerGuide = 4096;
    EXPECT_EQ(errorOf([&] { checkCounts(w); }), "");
}

TEST(Workload, TooLargeForTheDeviceIsRefusedWithBothSizes)
{
    vk::DeviceReport tiny;
    tiny.name = "Tiny GPU";
    tiny.deviceLocalBytes = uint64_t(256) << 20;
    tiny.maxStorageBufferRange = std::numeric_limits<uint32_t>::max();
    RenderSettings r;
    Workload w{.guides = kMaxGuides, .verticesPerStrand = 64, .sim = {}, .render = &r};
    std::string what = errorOf([&] { checkWorkload(w, tiny); });
    uint64_t need = (estimateGpuMemory(w, tiny).total() + (1u << 20) - 1) >> 20;
    EXPECT_NE(what.find("needs " + std::to_string(need) + " MiB"), std::string::npos) << what;
    EXPECT_NE(what.find("'Tiny GPU' has 256 MiB"), std::string::npos) << what;
    EXPECT_NE(what.find("--guides"), std::string::npos) << what;
    // The default workload fits in 512 MiB (about 290: the compute raster's light buffers, per-pixel
    // buffers and first fragment buffer are 168 of them); drawn by the graphics pipeline, in 256.
    w.guides = GrowthSettings{}.guides;
    w.verticesPerStrand = GrowthSettings{}.verticesPerStrand;
    vk::DeviceReport small = tiny;
    small.deviceLocalBytes = uint64_t(512) << 20;
    EXPECT_EQ(errorOf([&] { checkWorkload(w, small); }), "") << estimateGpuMemory(w, small).total();
    r.hairRaster = HairRaster::Graphics;
    EXPECT_EQ(errorOf([&] { checkWorkload(w, tiny); }), "") << estimateGpuMemory(w, tiny).total();
}

TEST(Workload, AComputeRasterTooLargeForTheDeviceIsNamed)
{
    // 1000 guides x 4096 strands x 1024 divisions: about 100 GB of strand vertices for the compute
    // path; the simulation and the images are small.
    vk::DeviceReport device;
    device.name = "Small GPU";
    device.deviceLocalBytes = uint64_t(8) << 30;
    device.maxStorageBufferRange = std::numeric_limits<uint32_t>::max();
    RenderSettings r;
    r.width = 64;
    r.height = 64;
    r.shadows.mapSize = 64;
    r.strands.strandsPerGuide = 4096;
    r.strands.divisions = 1024;
    r.hairRaster = HairRaster::Compute;
    Workload w{.guides = 1000, .verticesPerStrand = 16, .sim = {}, .render = &r};
    GpuMemory m = estimateGpuMemory(w, device);
    EXPECT_GT(m.raster, device.deviceLocalBytes);
    EXPECT_LT(m.total() - m.raster, device.deviceLocalBytes) << "the compute raster alone is too large";
    std::string what = errorOf([&] { checkWorkload(w, device); });
    EXPECT_NE(what.find("compute raster " + std::to_string((m.raster + (1u << 20) - 1) >> 20) +
                        " MiB (4096000 strands x 1024 divisions)"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("'Small GPU' has 8192 MiB"), std::string::npos) << what;
    EXPECT_NE(what.find("strands_per_guide, divisions, the size"), std::string::npos) << what;
    r.hairRaster = HairRaster::Graphics; // the tessellation keeps no per-vertex buffers: it fits
    EXPECT_EQ(errorOf([&] { checkWorkload(w, device); }), "");
}

TEST(Workload, ALoadedGroomIsDrawnAtAboutAHundredThousandStrands)
{
    // A file of every strand of a groom draws each once or twice; one of sparse guides draws more,
    // at most the default's 46 a guide.
    uint32_t most = StrandSettings{}.strandsPerGuide;
    EXPECT_EQ(loadedStrandsPerGuide(150000, most), 1u);
    EXPECT_EQ(loadedStrandsPerGuide(100000, most), 1u);
    EXPECT_EQ(loadedStrandsPerGuide(50000, most), 2u);
    EXPECT_EQ(loadedStrandsPerGuide(11400, most), 9u); // Sintel's groom: 102,600 strands
    EXPECT_EQ(loadedStrandsPerGuide(10000, most), 10u);
    EXPECT_EQ(loadedStrandsPerGuide(228, most), 46u); // Sintel lite's: capped
    EXPECT_EQ(loadedStrandsPerGuide(228, 4), 4u);
    EXPECT_EQ(loadedStrandsPerGuide(0, most), most);
}
