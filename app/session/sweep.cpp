// app/session/sweep.cpp: the grid of settings, one profiled run per point (app/session/headless.cpp's
// profileFrames), results.csv, and the charts (scripts/plot_sweep.py through python3).
#include "app/session/sweep.h"

#include "app/commands/command.h"
#include "app/session/headless.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "renderer/settings.h"
#include "renderer/strand_draw.h"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#ifndef WISP_SOURCE_DIR
#error "WISP_SOURCE_DIR must name the source tree (for scripts/plot_sweep.py)"
#endif

namespace wisp {

SweepAxis parseSweepAxis(const std::string& spec, const Settings& base)
{
    size_t eq = spec.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
        throw UserError("--vary " + spec + ": expected NAME=V1,V2,... (names from 'wisp settings')");
    SweepAxis axis{spec.substr(0, eq), {}};
    const SettingSpec& setting = settingSpec(axis.name, "--vary " + spec);
    std::vector<std::string> seen; // each value as the table writes it: 1 and 1.0 are one value
    for (size_t at = eq + 1;;) {
        size_t comma = spec.find(',', at);
        std::string value = spec.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
        if (value.empty())
            throw UserError("--vary " + spec + ": an empty value" +
                            (comma == std::string::npos ? std::string(" (a trailing comma)") : std::string()));
        Settings probe = base;
        SettingValue parsed = parseSetting(setting, value, "--vary " + spec);
        setSetting(probe, setting, parsed, "--vary " + spec); // checked now
        std::string text = settingText(setting, parsed);
        if (std::find(seen.begin(), seen.end(), text) != seen.end())
            throw UserError("--vary " + spec + ": " + value + " is given twice");
        seen.push_back(text);
        axis.values.push_back(value);
        if (comma == std::string::npos)
            break;
        at = comma + 1;
    }
    return axis;
}

std::vector<SweepAxis> parseSweepGrid(const std::vector<std::string>& specs, const Settings& base)
{
    std::vector<SweepAxis> axes;
    size_t points = 1;
    std::string sizes;
    for (const std::string& spec : specs) {
        SweepAxis axis = parseSweepAxis(spec, base);
        for (size_t a = 0; a < axes.size(); ++a)
            if (axes[a].name == axis.name)
                throw UserError("--vary " + spec + ": " + axis.name + " is varied twice (also by --vary " + specs[a] +
                                "); give all its values in one --vary");
        points = points > kSweepMostPoints ? points : points * axis.values.size(); // stops growing past the cap
        sizes += (sizes.empty() ? "" : " x ") + std::to_string(axis.values.size());
        axes.push_back(std::move(axis));
    }
    if (points > kSweepMostPoints) {
        double total = 1.0;
        for (const SweepAxis& a : axes)
            total *= double(a.values.size());
        char count[32];
        std::snprintf(count, sizeof(count), "%.0f", total);
        throw UserError("--vary: the grid has " + std::string(count) + " points (" + sizes + " values); a sweep runs " +
                        "at most " + std::to_string(kSweepMostPoints) + ", each --warmup + --frames frames long");
    }
    return axes;
}

namespace {

// The output folder: created for the sweep, and removed again (with whatever it holds) when the
// sweep fails before it is done, so a failed sweep leaves nothing behind. A folder that was
// already there stays, less what the sweep put into it.
class OutputFolder {
public:
    explicit OutputFolder(const std::filesystem::path& dir) : dir_(dir)
    {
        std::error_code ec;
        existed_ = std::filesystem::is_directory(dir_, ec);
        std::filesystem::create_directories(dir_, ec);
        if (ec || !std::filesystem::is_directory(dir_))
            throw UserError("--out " + dir_.string() + ": cannot create the folder");
    }
    ~OutputFolder()
    {
        if (done_)
            return;
        std::error_code ec;
        if (!existed_)
            std::filesystem::remove_all(dir_, ec);
        else
            for (const char* name : {"results.csv", "fps.png", "frame.png", "passes.png"})
                std::filesystem::remove(dir_ / name, ec);
    }
    OutputFolder(const OutputFolder&) = delete;
    OutputFolder& operator=(const OutputFolder&) = delete;
    void keep() { done_ = true; }

private:
    std::filesystem::path dir_;
    bool existed_ = false;
    bool done_ = false;
};

// What one point of the grid measured.
struct SweepPoint {
    std::vector<std::string> values; // one per axis
    std::vector<PassTiming> timings; // the passes it ran, in their order, then the frame
    OitStats oit;
    RasterStats raster;
    HairRaster drawn = HairRaster::Graphics; // hair_raster as resolved for the device (auto: compute)
    uint32_t samples = 1;                    // the samples drawn (the device's, of those asked)
    uint64_t guides = 0;                     // the guides simulated (grown or loaded)
    uint64_t strands = 0;                    // the strands drawn from them
    uint64_t segments = 0;
    uint32_t width = 0;
    uint32_t height = 0;
};

// The pass columns: every pass some point ran, in the order first seen, then the frame.
std::vector<std::string> passColumns(const std::vector<SweepPoint>& points)
{
    std::vector<std::string> columns;
    for (const SweepPoint& p : points)
        for (const PassTiming& t : p.timings)
            if (t.name != "frame" && std::find(columns.begin(), columns.end(), t.name) == columns.end())
                columns.push_back(t.name);
    columns.push_back("frame");
    return columns;
}

std::string resultsCsv(const vk::Context& ctx, const std::vector<SweepAxis>& axes,
                       const std::vector<SweepPoint>& points)
{
    std::vector<std::string> passes = passColumns(points);
    std::ostringstream csv;
    for (const SweepAxis& a : axes)
        csv << a.name << ",";
    for (const std::string& p : passes)
        csv << p << "_ms_median," << p << "_ms_p95,";
    csv << "fps,guides,strands,segments,oit_fragments,oit_overflow,raster_segments,raster_fragments,raster_overflow,"
           "hair_raster_drawn,samples_drawn,width,height,device,driver\n";
    for (const SweepPoint& point : points) {
        for (const std::string& v : point.values)
            csv << v << ",";
        double frameMs = 0.0;
        for (const std::string& p : passes) {
            auto t = std::find_if(point.timings.begin(), point.timings.end(),
                                  [&](const PassTiming& x) { return x.name == p; });
            bool ran = t != point.timings.end(); // a pass this point did not run counts 0
            csv << (ran ? t->medianMs : 0.0) << "," << (ran ? t->p95Ms : 0.0) << ",";
            if (p == "frame" && ran)
                frameMs = t->medianMs;
        }
        csv << (frameMs > 0.0 ? 1000.0 / frameMs : 0.0) << "," << point.guides << "," << point.strands << ","
            << point.segments << "," << point.oit.fragments << "," << point.oit.overflow << "," << point.raster.segments
            << "," << point.raster.fragments << "," << point.raster.overflow << ","
            << (point.drawn == HairRaster::Compute ? "compute" : "graphics") << "," << point.samples << ","
            << point.width << "," << point.height << ",\"" << ctx.report().name << "\",\"" << ctx.report().driverInfo
            << "\"\n";
    }
    return csv.str();
}

} // namespace

void applyPointSettings(Settings& settings, const SessionOptions& base, const std::vector<SweepAxis>& axes,
                        const std::vector<std::string>& values)
{
    auto varied = [&](const std::string& name) {
        return std::any_of(axes.begin(), axes.end(), [&](const SweepAxis& a) { return a.name == name; });
    };
    // A style sets every growth parameter: it goes first, then the command line's own values come
    // back over it (--guides 60 --vary hair_style=bob,afro grows 60 guides at both points), then
    // the other axes.
    for (size_t i = 0; i < axes.size(); ++i)
        if (axes[i].name == "hair_style") {
            applySetting(settings, axes[i].name + "=" + values[i]);
            for (const std::string& name : base.commandLineSettings)
                if (name != "hair_style" && !varied(name)) {
                    const SettingSpec& spec = settingSpec(name);
                    spec.put(settings, spec.get(base.settings));
                }
        }
    for (size_t i = 0; i < axes.size(); ++i)
        if (axes[i].name != "hair_style")
            applySetting(settings, axes[i].name + "=" + values[i]);
}

int runSweep(const vk::Context& ctx, const SweepOptions& o, const SessionOptions& base)
{
    OutputFolder folder(o.outDir);
    size_t points = 1;
    for (const SweepAxis& a : o.axes)
        points *= a.values.size();

    // Every point first: the columns are the passes any of them ran.
    std::vector<SweepPoint> measured;
    for (size_t index = 0; index < points; ++index) {
        Settings settings = base.settings;
        const RenderSettings& render = settings.render;
        SweepPoint point;
        size_t rest = index;
        for (const SweepAxis& a : o.axes) {
            point.values.push_back(a.values[rest % a.values.size()]);
            rest /= a.values.size();
        }
        applyPointSettings(settings, base, o.axes, point.values);
        std::fprintf(stderr, "sweep: point %zu/%zu:", index + 1, points);
        for (size_t i = 0; i < o.axes.size(); ++i)
            std::fprintf(stderr, " %s=%s", o.axes[i].name.c_str(), point.values[i].c_str());
        std::fprintf(stderr, "\n");

        if (std::string note = useDeviceSamples(settings.render, ctx.report()); !note.empty())
            std::fprintf(stderr, "%s\n", note.c_str());
        point.samples = render.samples;
        HairSession session(ctx, base.source.buildGroomedHead(settings), settings.sim,
                            stillTimeline(base.source.sphere, settings.sim.wind, render.light), base.source);
        point.timings = profileFrames(ctx, session, render, 30.0f, o.warmup, o.frames, &point.oit, &point.raster);
        point.drawn = resolveHairRaster(render.hairRaster);
        point.guides = session.scene().strands.strandCount();
        StrandCounts counts = strandCounts(uint32_t(point.guides), render.strands);
        point.strands = counts.strands();
        point.segments = counts.segments();
        point.width = render.width;
        point.height = render.height;
        measured.push_back(std::move(point));
    }

    // results.csv appears whole or not at all.
    std::filesystem::path csvPath = o.outDir / "results.csv";
    writeFileAtomically(csvPath, resultsCsv(ctx, o.axes, measured));
    folder.keep(); // the results are whole: the charts failing below leaves them
    std::printf("%s\n", csvPath.string().c_str());

    // The chart script: beside the executable (a bundle), else in the source tree.
    std::filesystem::path plot = std::filesystem::path(WISP_SOURCE_DIR) / "scripts" / "plot_sweep.py";
    std::error_code ec;
    std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec && std::filesystem::exists(exe.parent_path() / "plot_sweep.py"))
        plot = exe.parent_path() / "plot_sweep.py";
    // Debian's python3 (where python3-matplotlib installs), not whichever python3 is first on PATH.
    std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    // matplotlib is installed with the tests' packages, not the demo's: without it, say how to get it.
    if (std::system((python + " -c 'import matplotlib' >/dev/null 2>&1").c_str()) != 0)
        throw UserError("sweep: the results are in " + csvPath.string() +
                        "; the charts need python3's matplotlib, which is not installed (Debian package "
                        "python3-matplotlib: apt-get install python3-matplotlib, or scripts/setup.sh --test)");
    std::string command = python + " '" + plot.string() + "' '" + csvPath.string() + "' '" + o.outDir.string() + "'";
    int status = std::system(command.c_str());
    if (WIFEXITED(status) && WEXITSTATUS(status) == 3)
        return kExitUserError; // a chart could not be written: the script has said which, in one line
    if (status != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw UserError("sweep: the results are in " + csvPath.string() +
                        " but the charts failed (python3 with python3-matplotlib runs scripts/plot_sweep.py)");
    return ctx.validationMessages() > 0 ? kExitInternalError : 0;
}

} // namespace wisp
