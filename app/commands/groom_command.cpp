// app/commands/groom_command.cpp: `wisp groom --out FILE.hair|FILE.tfx [--frames N]`: the guide groom Wisp
// grows (or loads) written for other tools (assets/hair_writer.h), in head space and head units:
// the rest pose, or where the guides hang after N simulated frames (the session `simulate` runs,
// its positions read back and taken into head space). Takes the shared head, hair, scene and
// settings options. Everything is checked before anything is grown or simulated; the file appears
// whole or not at all.
#include "app/commands/commands.h"

#include "app/session/hair_session.h"
#include "app/session/simulate.h"
#include "assets/hair_writer.h"
#include "core/error.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>
#include <unistd.h>

namespace wisp {

namespace {

constexpr float kHairDiameterMetres = 70e-6f; // a human hair: cyHair's d_thickness

struct GroomCommand {
    CLI::App* command = nullptr;
    std::unique_ptr<SessionCommandLine> shared;
    std::string out;
    uint32_t frames = 0;
    float fps = 30.0f;
};

// The output's format and folder, before any work (messages as render's --out).
HairFormat checkGroomOutput(const std::filesystem::path& path)
{
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw UserError("--out " + path.string() + ": is a folder; name the groom file in it (FILE.hair or FILE.tfx)");
    HairFormat format;
    try {
        format = hairFormatForOutput(path);
    } catch (const UserError& e) {
        throw UserError(std::string("--out ") + e.what());
    }
    std::filesystem::path dir = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
    if (!std::filesystem::is_directory(dir, ec))
        throw UserError("--out " + path.string() + ": folder '" + dir.string() + "' does not exist");
    if (access(dir.c_str(), W_OK) != 0)
        throw UserError("--out " + path.string() + ": folder '" + dir.string() + "' is not writable");
    return format;
}

GroomToWrite groomOf(const StrandSet& strands, const std::vector<glm::vec3>& positions, float unitsPerMetre,
                     HairFormat format, uint32_t frames)
{
    GroomToWrite groom;
    uint32_t V = strands.verticesPerStrand;
    groom.strands.resize(strands.strandCount());
    for (size_t s = 0; s < strands.strandCount(); ++s) {
        HairStrand& out = groom.strands[s];
        out.points.assign(positions.begin() + std::ptrdiff_t(s * V), positions.begin() + std::ptrdiff_t((s + 1) * V));
        out.pinnedRoot = strands.strands[s].pinnedRoot;
        out.pinnedTip = strands.strands[s].pinnedTip != 0u;
    }
    groom.thickness = kHairDiameterMetres * unitsPerMetre;
    groom.info = "Wisp groom: head units (" + std::to_string(unitsPerMetre) + " a metre), " +
                 (frames == 0 ? std::string("rest pose") : "after " + std::to_string(frames) + " frames") +
                 (format == HairFormat::CyHair ? ", y-up head space written z-up" : "");
    return groom;
}

// cyHair has no pinning: read back, every strand pins its root vertex alone. One line on stderr
// says what of the groom's pinning the file lost (nothing when every strand pins only its root).
void noteCyHairLosses(const std::filesystem::path& out, HairFormat format, const StrandSet& strands)
{
    if (format != HairFormat::CyHair)
        return;
    size_t rootSegment = 0, rigid = 0, tips = 0;
    for (const gpu::StrandInfo& s : strands.strands) {
        rigid += s.pinnedRoot >= strands.verticesPerStrand ? 1 : 0;
        rootSegment += s.pinnedRoot > 1 && s.pinnedRoot < strands.verticesPerStrand ? 1 : 0;
        tips += s.pinnedTip != 0u ? 1 : 0;
    }
    if (rootSegment + rigid + tips == 0)
        return;
    std::string lost;
    auto add = [&](size_t n, const std::string& what) {
        if (n > 0)
            lost += (lost.empty() ? "" : ", ") + std::to_string(n) + " " + what;
    };
    add(rootSegment, "strands pinned at their first segment");
    add(rigid, "rigid strands");
    add(tips, "pinned tips");
    std::fprintf(stderr,
                 "wisp: note: %s: cyHair carries no pinning (read back, every strand pins its root vertex alone): "
                 "lost %s; .tfx keeps them\n",
                 out.c_str(), lost.c_str());
}

int run(const GlobalOptions& g, const GroomCommand& c)
{
    std::filesystem::path out = c.out;
    HairFormat format = checkGroomOutput(out);
    SessionOptions session = c.shared->resolve();
    if (c.frames == 0) { // the rest pose needs no device
        GroomedHead scene = session.source.buildGroomedHead(session.settings);
        for (const std::string& w : scene.warnings)
            std::fprintf(stderr, "wisp: warning: %s\n", w.c_str());
        if (scene.strands.strandCount() == 0)
            throw UserError("groom: the groom has no strands to write (every strand of its files has no length)");
        writeHairFile(out, groomOf(scene.strands, scene.strands.rest, scene.unitsPerMetre, format, 0));
        noteCyHairLosses(out, format, scene.strands);
        std::printf("%s: %zu guides x %u vertices at rest, %s\n", out.c_str(), scene.strands.strandCount(),
                    scene.strands.verticesPerStrand,
                    format == HairFormat::CyHair ? "cyHair (z-up)" : "TressFX 4 (y-up)");
        return 0;
    }
    GroomedHead scene = buildCheckedHead(g, session, nullptr);
    if (scene.strands.strandCount() == 0)
        throw UserError("groom: the groom has no strands to write (every strand of its files has no length)");
    vk::Context ctx(contextOptions(g));
    HairSession hair(ctx, std::move(scene), session.settings.sim, session.timeline, session.source);
    const StrandSet& strands = hair.scene().strands;
    uint32_t steps = c.frames * hair.clock().stepsPerFrame(c.fps);
    SimulationReport r = simulateHeadless(ctx, hair, steps, steps);
    if (int status = validationStatus(ctx); status != 0)
        return status; // a groom simulated with validation errors is not trusted: nothing written
    glm::mat4 toHead = glm::inverse(r.headTransform);
    std::vector<glm::vec3> positions;
    positions.reserve(r.state.positions.size());
    for (const glm::vec4& p : r.state.positions)
        positions.push_back(glm::vec3(toHead * glm::vec4(glm::vec3(p), 1.0f)));
    writeHairFile(out, groomOf(strands, positions, hair.scene().unitsPerMetre, format, c.frames));
    noteCyHairLosses(out, format, strands);
    std::printf("%s: %zu guides x %u vertices after %u frames (%u steps), %s\n", out.c_str(), strands.strandCount(),
                strands.verticesPerStrand, c.frames, steps,
                format == HairFormat::CyHair ? "cyHair (z-up)" : "TressFX 4 (y-up)");
    return 0;
}

} // namespace

CommandRun addGroomCommand(CLI::App& app, const GlobalOptions& global)
{
    auto c = std::make_shared<GroomCommand>();
    CLI::App* cmd = app.add_subcommand(
        "groom",
        "write the guide groom (grown or loaded; at rest or after --frames) as cyHair .hair or TressFX 4 .tfx");
    c->command = cmd;
    cmd->add_option("--out", c->out,
                    "output groom: .hair (cyHair, written z-up) or .tfx (TressFX 4, y-up); its folder must exist")
        ->required();
    cmd->add_option("--frames", c->frames,
                    "simulated frames before writing (each 1/fps seconds of fixed steps; 0: the rest pose, no GPU)")
        ->check(wholeWithin(0, 100000))
        ->capture_default_str();
    cmd->add_option("--fps", c->fps, "simulated frames per second")->check(within(1.0, 1000.0))->capture_default_str();
    c->shared = std::make_unique<SessionCommandLine>(
        cmd, SessionCommandLine::Uses{.scene = true, .noHair = false, .draws = false});
    return [c, &global] { return c->command->parsed() ? run(global, *c) : -1; };
}

} // namespace wisp
