// app/settings/settings_table.cpp: the table (buildSpecs: one entry per setting, each range stated here
// once, bounds that are the code's own limits named by their constants), and the one way values
// are read, checked, written and shown.
#include "app/settings/settings_table.h"

#include "app/settings/value_text.h"
#include "core/error.h"
#include "physics/hair_style.h"
#include "shaders/shared/shadows.h"
#include "shading/hair_bsdf.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace wisp {

namespace {

using Json = nlohmann::ordered_json;

std::string joined(const std::vector<std::string>& words, const char* separator)
{
    std::string out;
    for (const std::string& w : words)
        out += (out.empty() ? "" : separator) + w;
    return out;
}

[[noreturn]] void fail(const std::string& where, const std::string& why)
{
    throw UserError(where + ": " + why);
}

// How a refused value is named: itself ('wide', 0), or, one of several ("x,y,z"), "the second
// value (nan)" ("value 2" would read as the number 2). `ordinal`: 0 alone, else 1, 2, ...
std::string valueName(const std::string& value, size_t ordinal, bool quoted)
{
    static const char* const kOrdinals[] = {"first", "second", "third", "fourth"};
    if (ordinal == 0)
        return quoted ? "'" + value + "'" : value;
    std::string nth = ordinal <= 4 ? kOrdinals[ordinal - 1] : std::to_string(ordinal) + "th";
    return "the " + nth + " value (" + value + ")";
}

// Reads one number of `text` (the `ordinal`-th of several, 0: alone); "nan", "inf" and 1e400 are refused.
double readNumber(std::string_view text, const std::string& where, size_t ordinal = 0)
{
    double v = 0.0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    std::string quoted = valueName(std::string(text), ordinal, true);
    if (text.empty() || end != text.data() + text.size() || (ec != std::errc() && ec != std::errc::result_out_of_range))
        fail(where, quoted + " is not a number");
    if (ec == std::errc::result_out_of_range || !std::isfinite(v))
        fail(where, quoted + " is not a finite number");
    return v;
}

// "a,b,c" into its comma-separated parts.
std::vector<std::string_view> split(std::string_view text)
{
    std::vector<std::string_view> parts;
    for (size_t start = 0;;) {
        size_t comma = text.find(',', start);
        parts.push_back(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
        if (comma == std::string_view::npos)
            return parts;
        start = comma + 1;
    }
}

void checkNumber(const SettingSpec& spec, double v, const std::string& where, size_t ordinal = 0)
{
    std::string shown = valueName(numberText(v), ordinal, false);
    if (!std::isfinite(v))
        fail(where, shown + " is not a finite number");
    if (!spec.range.contains(v))
        fail(where, shown + " is out of range: allowed " + rangeText(spec.range, spec.unit));
    if (spec.type == SettingType::Integer && v != std::floor(v))
        fail(where, shown + " is not a whole number");
}

// ---- Binding a table entry to the field it lives in ----------------------------------------

template <typename T> SettingValue valueOf(const T& field)
{
    static_assert(!std::is_enum_v<T>, "an enum is a choice: bind it by name with choiceField()");
    SettingValue v;
    if constexpr (std::is_same_v<T, float>)
        v.number = shortest(field);
    else if constexpr (std::is_same_v<T, bool>)
        v.number = field ? 1.0 : 0.0;
    else if constexpr (std::is_same_v<T, glm::vec3>)
        v.vector = glm::dvec3(shortest(field.x), shortest(field.y), shortest(field.z));
    else if constexpr (std::is_same_v<T, std::optional<float>>)
        v = field ? valueOf(*field) : SettingValue{.unset = true};
    else
        v.number = double(field);
    return v;
}

template <typename T> void store(T& field, const SettingValue& v)
{
    if constexpr (std::is_same_v<T, bool>)
        field = v.number != 0.0;
    else if constexpr (std::is_same_v<T, glm::vec3>)
        field = glm::vec3(v.vector);
    else if constexpr (std::is_same_v<T, std::optional<float>>)
        field = v.unset ? std::nullopt : std::optional<float>(float(v.number));
    else
        field = static_cast<T>(v.number);
}

// A spec reading and writing the field `ref` returns (ref: Settings& -> T&).
template <typename Ref> SettingSpec field(SettingSpec spec, Ref ref)
{
    spec.get = [ref](const Settings& s) { return valueOf(ref(const_cast<Settings&>(s))); };
    spec.put = [ref](Settings& s, const SettingValue& v) { store(ref(s), v); };
    return spec;
}

// One choice of an enum setting: the word a person writes and the enum value it stands for.
template <typename E> struct NamedChoice {
    const char* name;
    E value;
};

// A choice spec reading and writing the enum field `ref` returns (ref: Settings& -> E&). The spec's
// choices are the table's names in its order (the order `wisp settings` and the panel list them);
// each name is bound to its value here, so the enum's own order does not matter.
template <typename E, typename Ref>
SettingSpec choiceField(SettingSpec spec, std::vector<NamedChoice<E>> table, Ref ref)
{
    static_assert(std::is_enum_v<E>);
    spec.choices.clear();
    for (const NamedChoice<E>& c : table)
        spec.choices.push_back(c.name);
    spec.get = [table, ref](const Settings& s) {
        E value = ref(const_cast<Settings&>(s));
        for (size_t i = 0; i < table.size(); ++i)
            if (table[i].value == value)
                return SettingValue{.number = double(i)};
        throw std::logic_error("a value of the choice setting's enum has no name in its table");
    };
    spec.put = [table, ref](Settings& s, const SettingValue& v) { ref(s) = table[size_t(v.number)].value; };
    return spec;
}

constexpr SettingChange kLive = SettingChange::Live;
constexpr SettingChange kRenderer = SettingChange::Renderer;
constexpr SettingChange kSolver = SettingChange::Solver;
constexpr SettingChange kRestart = SettingChange::Restart;

std::vector<SettingSpec> buildSpecs()
{
    using T = SettingType;
    std::vector<SettingSpec> s;
    SettingGroup group = SettingGroup::Growth;
    auto add = [&](SettingSpec spec) {
        spec.group = group;
        s.push_back(std::move(spec));
    };
    auto number = [](std::string name, std::string unit, Range range, SettingChange change, std::string option,
                     std::string help) {
        return SettingSpec{.name = std::move(name),
                           .type = T::Number,
                           .unit = std::move(unit),
                           .range = range,
                           .help = std::move(help),
                           .change = change,
                           .option = std::move(option)};
    };
    auto integer = [&](std::string name, Range range, SettingChange change, std::string option, std::string help,
                       std::string unit = "") {
        SettingSpec spec = number(std::move(name), std::move(unit), range, change, std::move(option), std::move(help));
        spec.type = T::Integer;
        return spec;
    };
    auto onOff = [](std::string name, SettingChange change, std::string option, std::string help) {
        return SettingSpec{.name = std::move(name),
                           .type = T::OnOff,
                           .help = std::move(help),
                           .change = change,
                           .option = std::move(option)};
    };
    auto choice = [](std::string name, std::vector<std::string> choices, SettingChange change, std::string option,
                     std::string help) {
        return SettingSpec{.name = std::move(name),
                           .type = T::Choice,
                           .choices = std::move(choices),
                           .help = std::move(help),
                           .change = change,
                           .option = std::move(option)};
    };
    auto partValue = [&](std::string name, std::string unit, Range range, std::string option, std::string help) {
        SettingSpec spec = number(std::move(name), std::move(unit), range, kSolver, std::move(option),
                                  std::move(help) + ", every part (part: each part's own)");
        spec.unsetText = "part";
        return spec;
    };
    const Range fraction{0.0, 1.0};

    // ---- Growth: the groom generator (physics/growth.h), in the order of its steps ----
    auto grown = [&](SettingSpec spec, auto ref) { add(field(std::move(spec), ref)); };
    SettingSpec style = choice("hair_style", {}, kRestart, "--style",
                               "a named style: sets every growth parameter below but the seed, and the drawn "
                               "strands' coil, divisions, count and length jitter (custom: none of the styles' own)");
    for (const HairStyle& h : hairStyles())
        style.choices.push_back(h.name);
    style.choices.push_back("custom");
    // Saved, and first: a scene of a style names it (its shape stiffness is no setting of its own),
    // then its parameters, which the style sets again, so the scene reads back the same.
    style.get = [](const Settings& x) {
        for (size_t i = 0; i < hairStyles().size(); ++i)
            if (isHairStyle(x.growth, hairStyles()[i]))
                return SettingValue{.number = double(i)};
        return SettingValue{.number = double(hairStyles().size())};
    };
    style.put = [](Settings& x, const SettingValue& v) {
        size_t i = size_t(v.number);
        if (i < hairStyles().size()) { // "custom" keeps the parameters as they are
            const HairStyle& h = hairStyles()[i];
            applyHairStyle(x.growth, h);
            x.render.strands.coilRadiusMetres = h.drawn.coilRadiusMetres;
            x.render.strands.coilTurnsPerMetre = h.drawn.coilTurnsPerMetre;
            x.render.strands.divisions = h.drawn.divisions;
            x.render.strands.strandsPerGuide = h.drawn.strandsPerGuide;
            x.render.strands.lengthJitter = h.drawn.lengthJitter;
        }
    };
    add(style);
    grown(
        integer("guides", {1, kMaxGuides}, kRestart, "--guides", "guide strands grown on the scalp"),
        [](Settings & x) -> auto& { return x.growth.guides; });
    grown(
        integer("vertices_per_strand", {kMinVerticesPerStrand, kMaxVerticesPerStrand}, kRestart, "--vertices",
                "vertices per simulated guide (loaded hair is resampled to it)"),
        [](Settings & x) -> auto& { return x.growth.verticesPerStrand; });
    grown(
        integer("seed", {0.0, 4294967295.0}, kRestart, "--seed", "seed for root sampling and strand variation"),
        [](Settings & x) -> auto& { return x.growth.seed; });
    grown(
        onOff("poisson", kRestart, "--poisson", "blue-noise (Poisson-disk) roots instead of area-weighted random"),
        [](Settings & x) -> auto& { return x.growth.poissonDisk; });
    grown(
        number("hairline_band", "m", {0.001, 0.05}, kRestart, "",
               "the root density rises from 0 to full over this inside the hairline"),
        [](Settings & x) -> auto& { return x.growth.hairlineBandMetres; });
    add(choiceField(
        choice("parting", {}, kRestart, "", "where the hair on top is parted"),
        std::vector<NamedChoice<Parting>>{
            {"none", Parting::None}, {"centre", Parting::Centre}, {"side", Parting::Side}},
        [](Settings & x) -> auto& { return x.growth.parting; }));
    grown(
        number("parting_offset", "m", {-0.08, 0.08}, kRestart, "",
               "a side parting's distance from the middle (+: the head's left)"),
        [](Settings & x) -> auto& { return x.growth.partingOffsetMetres; });
    grown(
        number("parting_sweep", "", {0.0, 2.0}, kRestart, "", "how strongly hair is combed away from the parting"),
        [](Settings & x) -> auto& { return x.growth.partingSweep; });
    grown(
        number("fall_back", "", {0.0, 2.0}, kRestart, "", "how far the hair on top is combed toward the back"),
        [](Settings & x) -> auto& { return x.growth.fallBack; });
    grown(
        number("crown_whorl", "", fraction, kRestart, "", "the swirl of the hair around the crown"),
        [](Settings & x) -> auto& { return x.growth.crownWhorl; });
    grown(
        number("bangs", "", fraction, kRestart, "", "how much of the front is combed forward over the forehead"),
        [](Settings & x) -> auto& { return x.growth.bangs; });
    grown(
        number("bangs_length", "m", {0.02, 0.3}, kRestart, "", "the length of the hair combed forward"),
        [](Settings & x) -> auto& { return x.growth.bangsLengthMetres; });
    grown(
        number("root_lift", "deg", {0.0, 90.0}, kRestart, "", "angle above the scalp strands leave at"),
        [](Settings & x) -> auto& { return x.growth.rootLiftDeg; });
    grown(
        number("style_gravity", "", {0.0, 4.0}, kRestart, "",
               "how fast grown strands turn down once they leave the scalp"),
        [](Settings & x) -> auto& { return x.growth.styleGravity; });
    grown(
        number("volume", "m", {0.0, 0.05}, kRestart, "",
               "how far the hair lies off the head once it has run a head's length over it"),
        [](Settings & x) -> auto& { return x.growth.volumeMetres; });
    grown(
        number("hair_length", "m", {0.01, 2.0}, kRestart, "--hair-length",
               "mean grown strand length before the trim (scaled to the head's units)"),
        [](Settings & x) -> auto& { return x.growth.lengthMetres; });
    grown(
        number("length_variation", "", {0.0, 0.9}, kRestart, "--length-variation",
               "relative spread of grown strand lengths"),
        [](Settings & x) -> auto& { return x.growth.lengthVariation; });
    grown(
        number("trim_level", "m", {0.0, 1.0}, kRestart, "",
               "strands are cut where they fall this far below the head's top (0: no trim)"),
        [](Settings & x) -> auto& { return x.growth.trimLevelMetres; });
    grown(
        number("trim_slope", "", {-2.0, 2.0}, kRestart, "",
               "how much lower the trim line runs per unit toward the face (an A-line)"),
        [](Settings & x) -> auto& { return x.growth.trimSlope; });
    grown(
        number("trim_jitter", "m", {0.0, 0.1}, kRestart, "",
               "the trim line's spread along the hem and from strand to strand (0: a ruled line)"),
        [](Settings & x) -> auto& { return x.growth.trimJitterMetres; });
    grown(
        number("hairline_length", "", {0.1, 1.0}, kRestart, "",
               "the length of a hair at the very hairline, as a share of the length"),
        [](Settings & x) -> auto& { return x.growth.hairlineLength; });
    grown(
        number("hairline_width", "", {0.1, 1.0}, kRestart, "",
               "the drawn width of a hair at the very hairline, as a share of `width` (finer hairs there)"),
        [](Settings & x) -> auto& { return x.growth.hairlineWidth; });
    grown(
        number("clump_size", "m", {0.0, 0.05}, kRestart, "", "spacing of the grown clumps' centres (0: no clumps)"),
        [](Settings & x) -> auto& { return x.growth.clumpSizeMetres; });
    grown(
        number("clump_strength", "", fraction, kRestart, "", "how far a strand's tip gathers to its clump's centre"),
        [](Settings & x) -> auto& { return x.growth.clumpStrength; });
    grown(
        number("clump_shape", "", {0.2, 6.0}, kRestart, "",
               "exponent of the clumping along the strand (higher: gathers nearer the tip)"),
        [](Settings & x) -> auto& { return x.growth.clumpShape; });
    grown(
        number("curl", "m", {0.0, 0.1}, kRestart, "--curl", "curl (helix) radius of grown strands (0: straight)"),
        [](Settings & x) -> auto& { return x.growth.curlRadiusMetres; });
    grown(
        number("curl_turns", "", {0.0, 15.0}, kRestart, "",
               "helix turns along a strand of the mean length (4 vertices a turn, more with curl_randomness: 15 "
               "fill the most, 64, without it)"),
        [](Settings & x) -> auto& { return x.growth.curlTurns; });
    grown(
        number("curl_randomness", "", fraction, kRestart, "", "per-strand spread of the curl's radius and frequency"),
        [](Settings & x) -> auto& { return x.growth.curlRandomness; });
    grown(
        number("wave", "m", {0.0, 0.05}, kRestart, "", "wave amplitude across the strand (0: no wave)"),
        [](Settings & x) -> auto& { return x.growth.waveMetres; });
    grown(
        number("wave_length", "m", {0.01, 0.5}, kRestart, "", "wavelength of the wave along the strand"),
        [](Settings & x) -> auto& { return x.growth.waveLengthMetres; });
    grown(
        number("frizz", "m", {0.0, 0.02}, kRestart, "", "noise amplitude at the tips, growing from the root"),
        [](Settings & x) -> auto& { return x.growth.frizzMetres; });
    grown(
        number("flyaways", "", {0.0, 0.2}, kRestart, "", "share of strands that stray off the hair's surface"),
        [](Settings & x) -> auto& { return x.growth.flyaways; });

    // ---- Simulation ----
    group = SettingGroup::Simulation;
    add(field(
        number("step_hz", "1/s", {30.0, 1000.0}, kSolver, "--step-hz", "fixed simulation steps per simulated second"),
        [](Settings & x) -> auto& { return x.sim.stepHz; }));
    add(field(
        integer("substeps", {1, 16}, kSolver, "--substeps", "integrate/FTL passes per step"),
        [](Settings & x) -> auto& { return x.sim.substeps; }));
    add(field(
        number("gravity", "m/s^2", {0.0, 100.0}, kSolver, "", "downward acceleration (scaled to the head's units)"),
        [](Settings & x) -> auto& { return x.sim.gravity; }));
    add(field(
        SettingSpec{.name = "wind",
                    .type = T::Vector,
                    .unit = "m/s^2",
                    .range = {-100.0, 100.0},
                    .help = "wind x,y,z (scaled to the head's units), gusting around this",
                    .change = kLive,
                    .option = "--wind"},
        [](Settings & x) -> auto& { return x.sim.wind; }));
    add(field(
        number("wind_frequency", "Hz", {0.0, 10.0}, kLive, "", "frequency of the wind's gusts"),
        [](Settings & x) -> auto& { return x.sim.windFrequency; }));
    add(field(
        integer("grid", {8, 256}, kSolver, "--grid", "hair-hair grid nodes per axis"),
        [](Settings & x) -> auto& { return x.sim.gridResolution; }));
    using GridAtomics = SimSettings::GridAtomics;
    add(choiceField(
        choice("grid_atomics", {}, kSolver, "--grid-atomics",
               "hair grid sums: 64-bit fixed point (deterministic) or float atomics"),
        std::vector<NamedChoice<GridAtomics>>{{"fixed", GridAtomics::Fixed}, {"float", GridAtomics::Float}},
        [](Settings & x) -> auto& { return x.sim.gridAtomics; }));
    add(field(
        number("friction", "", fraction, kSolver, "--friction", "hair-hair friction: blend toward the grid velocity"),
        [](Settings & x) -> auto& { return x.sim.gridFriction; }));
    add(field(
        number("repulsion", "", fraction, kSolver, "--repulsion",
               "hair-hair repulsion along the density gradient (keeps volume; 0: off)"),
        [](Settings & x) -> auto& { return x.sim.gridRepulsion; }));
    add(field(
        number("penalty_stiffness", "1/s^2", {0.0, 100000.0}, kSolver, "",
               "k of the colliders' penalty force k * depth * n"),
        [](Settings & x) -> auto& { return x.sim.penaltyStiffness; }));
    add(field(
        number("collision_margin", "m", {0.0, 0.05}, kSolver, "", "how far outside their surface the colliders act"),
        [](Settings & x) -> auto& { return x.sim.collisionMarginMetres; }));
    add(field(
        integer("sdf_resolution", {0, kSdfResolutionMax}, kSolver, "",
                "cells of the head mesh's distance field along its longest side, the hair kept out of the mesh "
                "itself beside the colliders (0, the default: the colliders alone; 96 is typical)"),
        [](Settings & x) -> auto& { return x.sim.sdfResolution; }));
    add(field(
        partValue("global_stiffness", "", fraction, "--global-stiffness",
                  "pull toward the rest pose per step at the root"),
        [](Settings & x) -> auto& { return x.sim.globalStiffness; }));
    add(field(
        partValue("local_stiffness", "", fraction, "--local-stiffness",
                  "pull of each segment toward its rest direction per step"),
        [](Settings & x) -> auto& { return x.sim.localStiffness; }));
    // s_damp stands for the pull of each vertex's children back on it, which follow-the-leader
    // leaves out: below about a half the chain passes the head's motion toward the tips and little
    // back, and the tips whip (the default bob's worst kinetic energy 64 at 0.9, 159 at 0.5, 571 at
    // 0.25, 1,450 at 0, there growing 2.4 times every 5 steps and still moving a second after the
    // head stopped: tests/test_sim_stability.cpp). The default is 0.9.
    add(field(
        partValue("damping", "", {0.5, 1.0}, "--damping",
                  "FTL velocity correction s_damp (Muller 2012): the children's pull back on their parents"),
        [](Settings & x) -> auto& { return x.sim.ftlDamping; }));
    add(field(
        partValue("drag", "1/s", {0.0, 100.0}, "--drag", "air drag"),
        [](Settings & x) -> auto& { return x.sim.drag; }));

    // ---- Strands drawn from the guides ----
    group = SettingGroup::Strands;
    add(field(
        integer("strands_per_guide", {1, 4096}, kLive, "", "strands drawn per guide"),
        [](Settings & x) -> auto& { return x.render.strands.strandsPerGuide; }));
    add(field(
        integer("divisions", {1, 1024}, kLive, "", "segments per drawn strand"),
        [](Settings & x) -> auto& { return x.render.strands.divisions; }));
    add(choiceField(
        choice("interpolation", {}, kLive, "", "strands around one guide (clumps), between three, or both"),
        std::vector<NamedChoice<Interpolation>>{
            {"single", Interpolation::Single}, {"multi", Interpolation::Multi}, {"mixed", Interpolation::Mixed}},
        [](Settings & x) -> auto& { return x.render.strands.interpolation; }));
    add(field(
        number("deviation", "m", {0.0, 0.1}, kLive, "", "strength of random strand deviations"),
        [](Settings & x) -> auto& { return x.render.strands.deviationMetres; }));
    add(field(
        number("clump_radius", "m", {0.0, 0.1}, kLive, "", "radius of the disc single-strand interpolation fills"),
        [](Settings & x) -> auto& { return x.render.strands.clumpRadiusMetres; }));
    add(field(
        number("coil_radius", "m", {0.0, 0.01}, kLive, "",
               "render-time coil: the radius of a helix about each drawn strand, finer than the guides' vertices "
               "(0: none)"),
        [](Settings & x) -> auto& { return x.render.strands.coilRadiusMetres; }));
    add(field(
        number("coil_frequency", "1/m", {0.0, 2000.0}, kLive, "",
               "render-time coil: its turns per metre along the strand (a turn needs 6 of the divisions; with fewer "
               "it fades out)"),
        [](Settings & x) -> auto& { return x.render.strands.coilTurnsPerMetre; }));
    add(field(
        number("strand_length_jitter", "", {0.0, 0.9}, kLive, "",
               "each drawn strand cut from the tip by a share of its guide's length, uniform up to this, its own "
               "(0: every strand as long as its guide; a loaded groom is drawn at 0 unless given)"),
        [](Settings & x) -> auto& { return x.render.strands.lengthJitter; }));
    add(field(
        number("width", "m", {0.00001, 0.01}, kLive, "", "strand width at the root"),
        [](Settings & x) -> auto& { return x.render.strands.widthMetres; }));
    add(field(
        number("min_pixel_width", "px", {0.25, 4.0}, kLive, "",
               "narrower ribbons are widened to this, their alpha scaled by the true coverage"),
        [](Settings & x) -> auto& { return x.render.strands.minPixelWidth; }));
    add(field(
        onOff("lod", kLive, "", "fewer, wider strands with camera distance"),
        [](Settings & x) -> auto& { return x.render.strands.lod; }));
    add(field(
        number("lod_min", "", {0.01, 1.0}, kLive, "",
               "the smallest share of strands LOD keeps, however far the camera"),
        [](Settings & x) -> auto& { return x.render.strands.lodMinFraction; }));
    add(field(
        onOff("show_guides", kLive, "", "also draw the simulated guides as lines"),
        [](Settings & x) -> auto& { return x.render.strands.showGuides; }));
    add(choiceField(
        choice("hair_raster", {}, kLive, "",
               "how the hair is drawn: tessellation and geometry shaders, or compute (analytic coverage, fragments "
               "binned per pixel, the nearest oit_k sorted; the meshes too); auto: the faster on the device "
               "(compute on every device measured)"),
        std::vector<NamedChoice<HairRaster>>{
            {"graphics", HairRaster::Graphics}, {"compute", HairRaster::Compute}, {"auto", HairRaster::Auto}},
        [](Settings & x) -> auto& { return x.render.hairRaster; }));

    // ---- The target, the light and the shadows ----
    group = SettingGroup::Light;
    SettingSpec samples = choice("samples", {"1", "2", "4", "8"}, kRenderer, "--samples",
                                 "MSAA samples (clamped to what the device has)");
    samples.get = [](const Settings& x) {
        return SettingValue{.number = std::log2(double(std::max<uint32_t>(x.render.samples, 1)))};
    };
    samples.put = [](Settings& x, const SettingValue& v) { x.render.samples = 1u << uint32_t(v.number); };
    add(samples);
    add(field(
        number("light_azimuth", "deg", {-360.0, 360.0}, kLive, "--light-azimuth",
               "key light angle around the up axis (0: in front of the face)"),
        [](Settings & x) -> auto& { return x.render.light.azimuthDeg; }));
    add(field(
        number("light_elevation", "deg", {-89.0, 89.0}, kLive, "--light-elevation",
               "key light angle above the horizon"),
        [](Settings & x) -> auto& { return x.render.light.elevationDeg; }));
    add(field(
        number("light_intensity", "", {0.0, 20.0}, kLive, "--light-intensity", "key light strength"),
        [](Settings & x) -> auto& { return x.render.light.intensity; }));
    add(field(
        SettingSpec{.name = "light_color",
                    .type = T::Color,
                    .range = {0.0, 1.0},
                    .help = "key light colour (linear RGB)",
                    .change = kLive},
        [](Settings & x) -> auto& { return x.render.light.color; }));
    // The fill and the rim: unshadowed directional lights (renderer/settings.h kDefaultFill, kDefaultRim).
    struct StudioLight {
        const char* name;
        const char* role;
        LightSettings RenderSettings::*light;
    };
    for (StudioLight l :
         {StudioLight{"fill", "fill light (unshadowed; softens the key's shadowed side)", &RenderSettings::fill},
          StudioLight{"rim", "rim light (unshadowed; from behind, lights the hair's edge)", &RenderSettings::rim}}) {
        std::string name = l.name, role = l.role;
        auto light = l.light;
        add(field(
            number(name + "_azimuth", "deg", {-360.0, 360.0}, kLive, "",
                   role + ": angle around the up axis (0: in front of the face)"),
            [light](Settings & x) -> auto& { return (x.render.*light).azimuthDeg; }));
        add(field(
            number(name + "_elevation", "deg", {-89.0, 89.0}, kLive, "", role + ": angle above the horizon"),
            [light](Settings & x) -> auto& { return (x.render.*light).elevationDeg; }));
        add(field(
            number(name + "_intensity", "", {0.0, 20.0}, kLive, "", role + ": strength (0: off)"),
            [light](Settings & x) -> auto& { return (x.render.*light).intensity; }));
        add(field(
            SettingSpec{.name = name + "_color",
                        .type = T::Color,
                        .range = {0.0, 1.0},
                        .help = role + ": colour (linear RGB)",
                        .change = kLive},
            [light](Settings & x) -> auto& { return (x.render.*light).color; }));
    }
    add(field(
        SettingSpec{.name = "background_top",
                    .type = T::Color,
                    .range = {0.0, 1.0},
                    .help = "the backdrop's colour at the top of the picture (linear RGB), a soft gradient down to "
                            "background_bottom",
                    .change = kLive},
        [](Settings & x) -> auto& { return x.render.backgroundTop; }));
    add(field(
        SettingSpec{.name = "background_bottom",
                    .type = T::Color,
                    .range = {0.0, 1.0},
                    .help = "the backdrop's colour at the bottom of the picture (linear RGB)",
                    .change = kLive},
        [](Settings & x) -> auto& { return x.render.backgroundBottom; }));
    add(field(
        number("ambient", "", {0.0, 4.0}, kLive, "", "strength of the hemisphere ambient light"),
        [](Settings & x) -> auto& { return x.render.ambient; }));
    add(field(
        number("exposure", "", {0.01, 16.0}, kLive, "", "exposure before tone mapping"),
        [](Settings & x) -> auto& { return x.render.exposure; }));
    add(field(
        onOff("shadows", kLive, "", "the key light's shadows (head and hair cast on each other)"),
        [](Settings & x) -> auto& { return x.render.shadows.enabled; }));
    add(field(
        integer("shadow_size", {64, 8192}, kRenderer, "", "shadow and deep opacity map size per side", "texels"),
        [](Settings & x) -> auto& { return x.render.shadows.mapSize; }));
    add(field(
        integer("pcf_samples", {1, gpu::kMaxPcfSamples}, kLive, "",
                "percentage-closer filtering taps per shadow lookup"),
        [](Settings & x) -> auto& { return x.render.shadows.pcfSamples; }));
    add(field(
        number("pcf_radius", "texels", {0.0, 16.0}, kLive, "", "radius of the PCF disk"),
        [](Settings & x) -> auto& { return x.render.shadows.pcfRadiusTexels; }));
    add(field(
        integer("dom_layers", {0, gpu::kMaxDomLayers}, kLive, "",
                "deep opacity map layers for hair self-shadowing (0: PCF on the hair's depth instead)"),
        [](Settings & x) -> auto& { return x.render.shadows.domLayers; }));
    add(field(
        number("dom_spacing", "m", {0.0005, 0.2}, kLive, "", "depth of one deep opacity layer"),
        [](Settings & x) -> auto& { return x.render.shadows.domSpacingMetres; }));
    add(field(
        number("dom_density", "", {0.0, 20.0}, kLive, "",
               "kappa of the hair's transmittance exp(-kappa * opacity) toward the light"),
        [](Settings & x) -> auto& { return x.render.shadows.domKappa; }));
    add(field(
        number("shadow_strands", "", {0.01, 1.0}, kLive, "",
               "share of the strands drawn into the light's maps (fewer, wider: the same coverage)"),
        [](Settings & x) -> auto& { return x.render.shadows.strandFraction; }));

    // ---- Transparency ----
    group = SettingGroup::Transparency;
    add(choiceField(
        choice("transparency", {}, kRenderer, "",
               "the tessellation path's hair blending: sorted per-pixel lists, or opaque coverage with MSAA "
               "(the compute path always keeps lists)"),
        std::vector<NamedChoice<Transparency>>{{"oit", Transparency::Oit}, {"msaa", Transparency::Msaa}},
        [](Settings & x) -> auto& { return x.render.transparency.mode; }));
    add(field(
        integer("oit_k", {1, gpu::kMaxOitK}, kLive, "",
                "nearest hair fragments sorted per pixel (the rest blended unsorted)"),
        [](Settings & x) -> auto& { return x.render.transparency.oitK; }));
    add(field(
        integer("oit_nodes_per_pixel", {0, 256}, kRenderer, "",
                "the tessellation path's fragment pool per pixel, 0 = automatic (up to 24 as memory allows; fragments "
                "past it are "
                "dropped and counted)"),
        [](Settings & x) -> auto& { return x.render.transparency.oitNodesPerPixel; }));
    add(field(
        integer(
            "fragment_budget", {0, 65536}, kLive, "",
            "the compute path's fragment buffer at most in MiB, 0 = automatic (1/8 of the device's memory, within one "
            "buffer's range); a frame that needs more is drawn in pieces, the same picture"),
        [](Settings & x) -> auto& { return x.render.fragmentBudgetMiB; }));
    add(field(
        number("hair_opacity", "", {0.01, 1.0}, kLive, "", "opacity of one strand that covers its pixel"),
        [](Settings & x) -> auto& { return x.render.transparency.hairOpacity; }));

    // ---- The hair's look (shading/hair_look.h) ----
    group = SettingGroup::Look;
    add(choiceField(
        choice("shading", {}, kLive, "", "hair shading model (lut: tables from the reference BSDF)"),
        std::vector<NamedChoice<ShadingModel>>{
            {"karis", ShadingModel::Karis}, {"kajiya", ShadingModel::Kajiya}, {"lut", ShadingModel::Lut}},
        [](Settings & x) -> auto& { return x.render.hair.model; }));
    add(field(
        onOff("multiple_scattering", kLive, "",
              "the light scattered between fibres (Karis's approximation) in the karis and lut models; "
              "kajiya has none"),
        [](Settings & x) -> auto& { return x.render.hair.multipleScattering; }));
    SettingSpec preset = choice("hair_preset", {}, kLive, "",
                                "a hair colour by name: sets melanin and pheomelanin (custom: neither preset's)");
    for (const HairPreset& p : kHairPresets)
        preset.choices.push_back(p.name);
    preset.choices.push_back("custom");
    preset.saved = false;
    preset.get = [](const Settings& x) {
        const HairLook& look = x.render.hair;
        for (size_t i = 0; i < kHairPresets.size(); ++i)
            if (!look.useColor && look.eumelanin == kHairPresets[i].eumelanin &&
                look.pheomelanin == kHairPresets[i].pheomelanin)
                return SettingValue{.number = double(i)};
        return SettingValue{.number = double(kHairPresets.size())};
    };
    preset.put = [](Settings& x, const SettingValue& v) {
        size_t i = size_t(v.number);
        if (i < kHairPresets.size())
            applyHairPreset(x.render.hair, kHairPresets[i].name); // "custom" keeps the look as it is
    };
    add(preset);
    add(field(
        number("melanin", "", shading::kMelaninRange, kLive, "",
               "eumelanin concentration (black ~8, brown ~1.3, blonde ~0.2)"),
        [](Settings & x) -> auto& { return x.render.hair.eumelanin; }));
    add(field(
        number("pheomelanin", "", shading::kMelaninRange, kLive, "", "pheomelanin concentration (red)"),
        [](Settings & x) -> auto& { return x.render.hair.pheomelanin; }));
    SettingSpec color{.name = "hair_color",
                      .type = T::Color,
                      .range = shading::kColorRange,
                      .help = "the colour the hair should look (linear RGB), instead of melanin (melanin: from "
                              "the melanin concentrations)",
                      .change = kLive,
                      .unsetText = "melanin"};
    color.get = [](const Settings& x) {
        return x.render.hair.useColor ? valueOf(x.render.hair.color) : SettingValue{.unset = true};
    };
    color.put = [](Settings& x, const SettingValue& v) {
        x.render.hair.useColor = !v.unset;
        if (!v.unset)
            x.render.hair.color = glm::vec3(v.vector);
    };
    add(color);
    add(field(
        number("beta_m", "", shading::kBetaRange, kLive, "", "longitudinal roughness of the fibre (highlight width)"),
        [](Settings & x) -> auto& { return x.render.hair.betaM; }));
    add(field(
        number("beta_n", "", shading::kBetaRange, kLive, "", "azimuthal roughness of the fibre"),
        [](Settings & x) -> auto& { return x.render.hair.betaN; }));
    add(field(
        number("cuticle_tilt", "deg", shading::kAlphaDegRange, kLive, "", "cuticle scale tilt (shifts the highlights)"),
        [](Settings & x) -> auto& { return x.render.hair.cuticleTiltDeg; }));
    add(field(
        number("ior", "", shading::kEtaRange, kLive, "", "index of refraction of the fibre"),
        [](Settings & x) -> auto& { return x.render.hair.eta; }));
    add(field(
        number("color_variation", "", fraction, kLive, "", "per-strand spread of the hair colour"),
        [](Settings & x) -> auto& { return x.render.hair.variation; }));
    add(field(
        number("streaks", "", fraction, kLive, "", "lighter and darker streaks along strands"),
        [](Settings & x) -> auto& { return x.render.hair.streaks; }));
    add(field(
        number("absorption_along", "", fraction, kLive, "",
               "how much the absorption falls from root to tip (1: from 1.25 to 0.75 times the "
               "material's, lighter tips; 0: the same all along)"),
        [](Settings & x) -> auto& { return x.render.hair.along; }));
    return s;
}

std::string typeWord(const SettingSpec& spec)
{
    switch (spec.type) {
    case SettingType::Number:
        return "number";
    case SettingType::Integer:
        return "integer";
    case SettingType::OnOff:
        return "on_off";
    case SettingType::Choice:
        return "choice";
    case SettingType::Vector:
        return "vector";
    case SettingType::Color:
        return "color";
    }
    return "number";
}

} // namespace

const char* groupName(SettingGroup group)
{
    switch (group) {
    case SettingGroup::Growth:
        return "growth";
    case SettingGroup::Simulation:
        return "simulation";
    case SettingGroup::Strands:
        return "strands";
    case SettingGroup::Light:
        return "light";
    case SettingGroup::Transparency:
        return "transparency";
    case SettingGroup::Look:
        return "look";
    }
    return "growth";
}

const char* changeName(SettingChange change)
{
    switch (change) {
    case SettingChange::Live:
        return "live";
    case SettingChange::Renderer:
        return "renderer";
    case SettingChange::Solver:
        return "solver";
    case SettingChange::Restart:
        return "restart";
    }
    return "live";
}

std::string SettingSpec::allowed() const
{
    std::string text;
    switch (type) {
    case SettingType::Number:
    case SettingType::Integer:
        text = rangeText(range, unit);
        break;
    case SettingType::OnOff:
        text = "on | off";
        break;
    case SettingType::Choice:
        text = joined(choices, " | ");
        break;
    case SettingType::Vector:
        text = "x,y,z in " + rangeText(range, unit);
        break;
    case SettingType::Color:
        text = "r,g,b in " + rangeText(range, unit);
        break;
    }
    return optional() ? text + " | " + unsetText : text;
}

const std::vector<SettingSpec>& settingSpecs()
{
    static const std::vector<SettingSpec> specs = buildSpecs();
    return specs;
}

const SettingSpec* findSetting(std::string_view name)
{
    for (const SettingSpec& spec : settingSpecs())
        if (spec.name == name)
            return &spec;
    return nullptr;
}

const SettingSpec& settingSpec(std::string_view name, const std::string& where)
{
    if (const SettingSpec* spec = findSetting(name))
        return *spec;
    fail(where, "unknown setting '" + std::string(name) + "' (see 'wisp settings')");
}

std::string settingNames()
{
    std::string names;
    for (const SettingSpec& spec : settingSpecs())
        names += (names.empty() ? "" : ", ") + spec.name;
    return names;
}

void checkSetting(const SettingSpec& spec, const SettingValue& v, const std::string& where)
{
    if (v.unset) {
        if (!spec.optional())
            fail(where, "must have a value (allowed: " + spec.allowed() + ")");
        return;
    }
    switch (spec.type) {
    case SettingType::Number:
    case SettingType::Integer:
        checkNumber(spec, v.number, where);
        break;
    case SettingType::OnOff:
        if (v.number != 0.0 && v.number != 1.0)
            fail(where, numberText(v.number) + " is not allowed: on | off");
        break;
    case SettingType::Choice:
        if (!(v.number >= 0.0 && v.number < double(spec.choices.size()) && v.number == std::floor(v.number)))
            fail(where, numberText(v.number) + " is not allowed: " + spec.allowed());
        break;
    case SettingType::Vector:
    case SettingType::Color:
        for (int i = 0; i < 3; ++i)
            checkNumber(spec, v.vector[i], where, size_t(i) + 1);
        break;
    }
}

SettingValue parseSetting(const SettingSpec& spec, std::string_view text, const std::string& where)
{
    SettingValue v;
    std::string quoted = "'" + std::string(text) + "'";
    if (spec.optional() && text == spec.unsetText) {
        v.unset = true;
        return v;
    }
    switch (spec.type) {
    case SettingType::Number:
    case SettingType::Integer:
        if (spec.optional()) {
            // Not only a number: the message says what else it takes ("part": each part's own value).
            try {
                v.number = readNumber(text, where);
            } catch (const UserError& e) {
                std::string also =
                    spec.unsetText == "part"
                        ? ", one part's value by --part PART:" + spec.name.substr(0, spec.name.find('_')) + "=VALUE"
                        : std::string();
                throw UserError(e.what() + std::string(" (a number, or '") + spec.unsetText + "'" + also + ")");
            }
        } else {
            v.number = readNumber(text, where);
        }
        break;
    case SettingType::OnOff:
        if (text == "on" || text == "true" || text == "1")
            v.number = 1.0;
        else if (text == "off" || text == "false" || text == "0")
            v.number = 0.0;
        else
            fail(where, quoted + " is not allowed: on | off");
        break;
    case SettingType::Choice: {
        auto found = std::find(spec.choices.begin(), spec.choices.end(), text);
        if (found == spec.choices.end())
            fail(where, quoted + " is not allowed: " + spec.allowed());
        v.number = double(found - spec.choices.begin());
        break;
    }
    case SettingType::Vector:
    case SettingType::Color: {
        std::vector<std::string_view> parts = split(text);
        if (parts.size() != 3)
            fail(where, quoted + " is not three numbers " +
                            (spec.type == SettingType::Color ? std::string("r,g,b") : std::string("x,y,z")));
        for (int i = 0; i < 3; ++i)
            v.vector[i] = readNumber(parts[size_t(i)], where, size_t(i) + 1);
        break;
    }
    }
    checkSetting(spec, v, where);
    return v;
}

SettingValue settingFromJson(const SettingSpec& spec, const Json& json, const std::string& where)
{
    if (json.is_string())
        return parseSetting(spec, json.get<std::string>(), where);
    SettingValue v;
    bool typed = false;
    std::string wanted;
    switch (spec.type) {
    case SettingType::Number:
    case SettingType::Integer:
        wanted = "a number";
        typed = json.is_number();
        if (typed)
            v.number = json.get<double>();
        break;
    case SettingType::OnOff:
        wanted = "true or false";
        typed = json.is_boolean();
        if (typed)
            v.number = json.get<bool>() ? 1.0 : 0.0;
        break;
    case SettingType::Choice:
        wanted = "a string (" + spec.allowed() + ")";
        if (json.is_number()) // numeric choices (samples) may be written as numbers
            return parseSetting(spec, json.dump(), where);
        break;
    case SettingType::Vector:
    case SettingType::Color:
        wanted = "an array of 3 numbers";
        typed = json.is_array() && json.size() == 3;
        for (size_t i = 0; typed && i < 3; ++i) {
            std::string at = where + "/" + std::to_string(i);
            if (!json[i].is_number())
                fail(at, "must be a number, got " + jsonTypeName(json[i]));
            v.vector[int(i)] = json[i].get<double>();
            checkNumber(spec, v.vector[int(i)], at);
        }
        break;
    }
    if (!typed)
        fail(where, "must be " + wanted + (spec.optional() ? " or \"" + spec.unsetText + "\"" : std::string()) +
                        ", got " + jsonTypeName(json));
    checkSetting(spec, v, where);
    return v;
}

std::string settingText(const SettingSpec& spec, const SettingValue& v)
{
    if (v.unset)
        return spec.unsetText;
    switch (spec.type) {
    case SettingType::Number:
    case SettingType::Integer:
        return numberText(v.number);
    case SettingType::OnOff:
        return v.number != 0.0 ? "on" : "off";
    case SettingType::Choice: {
        size_t i = size_t(v.number);
        return i < spec.choices.size() ? spec.choices[i] : numberText(v.number);
    }
    case SettingType::Vector:
    case SettingType::Color:
        return numberText(v.vector.x) + "," + numberText(v.vector.y) + "," + numberText(v.vector.z);
    }
    return "";
}

Json settingJson(const SettingSpec& spec, const SettingValue& v)
{
    if (v.unset)
        return spec.unsetText;
    switch (spec.type) {
    case SettingType::Number:
    case SettingType::Integer:
        if (v.number == std::floor(v.number) && std::abs(v.number) < 9e15)
            return Json(int64_t(v.number));
        return Json(v.number);
    case SettingType::OnOff:
        return v.number != 0.0;
    case SettingType::Choice: {
        std::string text = settingText(spec, v);
        Json parsed = Json::parse(text, nullptr, false);
        return !parsed.is_discarded() && parsed.is_number() && parsed.dump() == text ? parsed : Json(text);
    }
    case SettingType::Vector:
    case SettingType::Color:
        return Json::array({v.vector.x, v.vector.y, v.vector.z});
    }
    return nullptr;
}

double parseNumber(std::string_view text, const Range& range, const std::string& unit, const std::string& where,
                   size_t ordinal)
{
    double v = readNumber(text, where, ordinal);
    if (!range.contains(v))
        fail(where, valueName(numberText(v), ordinal, false) + " is out of range: allowed " + rangeText(range, unit));
    return v;
}

std::vector<double> parseNumbers(std::string_view text, size_t count, const char* form, const Range& range,
                                 const std::string& unit, const std::string& where)
{
    std::vector<std::string_view> parts = split(text);
    if (parts.size() != count)
        fail(where, "'" + std::string(text) + "' is not " + std::to_string(count) + " numbers " + form);
    std::vector<double> out;
    for (size_t i = 0; i < count; ++i)
        out.push_back(parseNumber(parts[i], range, unit, where, i + 1));
    return out;
}

void setSetting(Settings& settings, const SettingSpec& spec, const SettingValue& value, const std::string& where)
{
    checkSetting(spec, value, where);
    spec.put(settings, value);
}

void applySetting(Settings& settings, const std::string& assignment)
{
    size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        fail("--set " + assignment, "expected NAME=VALUE (see 'wisp settings')");
    std::string name = assignment.substr(0, eq);
    const SettingSpec& spec = settingSpec(name, "--set " + assignment);
    std::string where = "--set " + name;
    setSetting(settings, spec, parseSetting(spec, std::string_view(assignment).substr(eq + 1), where), where);
}

std::string settingsTable()
{
    Settings defaults;
    auto column = [](const std::string& text, size_t width) {
        return text + std::string(width > text.size() ? width - text.size() : 1, ' ');
    };
    std::ostringstream out;
    out << column("NAME", 21) << column("UNIT", 7) << column("ALLOWED", 40) << column("DEFAULT", 12)
        << column("CHANGE", 9) << column("OPTION", 20) << "DESCRIPTION\n";
    for (const SettingSpec& s : settingSpecs()) {
        std::string allowed = s.type == SettingType::Vector || s.type == SettingType::Color
                                  ? rangeText(s.range, "") + " each" + (s.optional() ? " | " + s.unsetText : "")
                              : (s.type == SettingType::Number || s.type == SettingType::Integer)
                                  ? rangeText(s.range, "") + (s.optional() ? " | " + s.unsetText : "")
                                  : s.allowed();
        out << column(s.name, 21) << column(s.unit, 7) << column(allowed, 40)
            << column(settingText(s, s.get(defaults)), 12) << column(changeName(s.change), 9) << column(s.option, 20)
            << s.help << "\n";
    }
    return out.str();
}

Json settingsTableJson()
{
    Settings defaults;
    Json out = Json::array();
    for (const SettingSpec& s : settingSpecs()) {
        Json entry = {{"name", s.name}, {"group", groupName(s.group)}, {"type", typeWord(s)}};
        if (!s.unit.empty())
            entry["unit"] = s.unit;
        if (s.type == SettingType::Choice)
            entry["choices"] = s.choices;
        else if (s.type != SettingType::OnOff)
            entry["range"] = {s.range.min, s.range.max};
        if (s.optional())
            entry["unset"] = s.unsetText;
        entry["default"] = settingJson(s, s.get(defaults));
        entry["change"] = changeName(s.change);
        if (!s.option.empty())
            entry["option"] = s.option;
        entry["help"] = s.help;
        out.push_back(entry);
    }
    return out;
}

Json settingsJson(const Settings& settings)
{
    Json out = Json::object();
    for (const SettingSpec& s : settingSpecs())
        out[s.name] = settingJson(s, s.get(settings));
    return out;
}

std::vector<std::pair<std::string, std::string>> currentSettings(const Settings& settings)
{
    std::vector<std::pair<std::string, std::string>> out;
    for (const SettingSpec& s : settingSpecs())
        if (s.saved)
            out.emplace_back(s.name, settingText(s, s.get(settings)));
    return out;
}

PanelControl panelControl(const SettingSpec& spec)
{
    PanelControl c;
    c.min = spec.range.min;
    c.max = spec.range.max;
    c.enabled = spec.change != SettingChange::Restart;
    // Over wide ranges of positive values a slider is logarithmic, so small values can be set too.
    c.logarithmic = spec.range.min > 0.0 && spec.range.max / spec.range.min >= 100.0;
    switch (spec.type) {
    case SettingType::Number:
        c.kind = PanelControl::Kind::Slider;
        break;
    case SettingType::Integer:
        c.kind = PanelControl::Kind::IntegerSlider;
        break;
    case SettingType::OnOff:
        c.kind = PanelControl::Kind::Checkbox;
        break;
    case SettingType::Choice:
        c.kind = PanelControl::Kind::Combo;
        break;
    case SettingType::Color:
        c.kind = PanelControl::Kind::Color;
        break;
    case SettingType::Vector:
        c.kind = PanelControl::Kind::Vector;
        break;
    }
    return c;
}

SettingEdit editSetting(Settings& settings, const SettingSpec& spec, const SettingValue& value)
{
    SettingEdit edit{.error = "", .change = spec.change};
    if (spec.change == SettingChange::Restart) {
        edit.error = spec.name + " needs a restart (the hair is grown at start): restart 'wisp view' with --set " +
                     spec.name + "=" + settingText(spec, value);
        return edit;
    }
    try {
        setSetting(settings, spec, value, spec.name);
    } catch (const UserError& e) {
        edit.error = e.what();
    }
    return edit;
}

} // namespace wisp
