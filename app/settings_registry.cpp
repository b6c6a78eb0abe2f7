// app/settings_registry.cpp: the table of settings. Each entry reads and writes one member of the
// settings structs, with the range constants those structs define.
#include "app/settings_registry.h"

#include "core/error.h"
#include "renderer/settings.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <type_traits>

namespace wisp {

namespace {

[[noreturn]] void bad(const std::string& name, const std::string& value, const std::string& why)
{
    throw UserError("--set " + name + "=" + value + ": " + why);
}

double number(const std::string& name, const std::string& value, double lo, double hi, const std::string& unit)
{
    double v = 0.0;
    auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (ec != std::errc() || end != value.data() + value.size() || !std::isfinite(v))
        bad(name, value, "not a number");
    if (v < lo || v > hi) {
        std::ostringstream s;
        s << "out of range: allowed " << lo << " .. " << hi << (unit.empty() ? "" : " " + unit);
        bad(name, value, s.str());
    }
    return v;
}

uint32_t integer(const std::string& name, const std::string& value, double lo, double hi)
{
    double v = number(name, value, lo, hi, "");
    if (v != std::floor(v))
        bad(name, value, "not a whole number");
    return uint32_t(v);
}

bool onOff(const std::string& name, const std::string& value)
{
    if (value == "on" || value == "1" || value == "true")
        return true;
    if (value == "off" || value == "0" || value == "false")
        return false;
    bad(name, value, "allowed: on | off");
}

template <typename T>
std::string text(T v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}

#define WISP_NEED(refs, member, name)                                                 \
    if (!(refs).member)                                                                \
    throw UserError("--set " + std::string(name) + ": this command does not use it")

std::string rangeText(const Range& r)
{
    return text(r.min) + " .. " + text(r.max);
}

// A render setting held in one member: a number within a Range, or on/off.
#define WISP_RENDER_NUMBER(NAME, UNIT, RANGE, DESCRIPTION, MEMBER, TYPE)                                   \
    add({NAME, UNIT, rangeText(RANGE), DESCRIPTION,                                                      \
         [](const SettingsRefs& r) { return r.render ? text(r.render->MEMBER) : "-"; },                   \
         [](const SettingsRefs& r, const std::string& v) {                                              \
             WISP_NEED(r, render, NAME);                                                                  \
             if constexpr (std::is_integral_v<TYPE>)                                                      \
                 r.render->MEMBER = TYPE(integer(NAME, v, RANGE.min, RANGE.max));                         \
             else                                                                                         \
                 r.render->MEMBER = TYPE(number(NAME, v, RANGE.min, RANGE.max, UNIT));                    \
         }})
#define WISP_RENDER_ON_OFF(NAME, DESCRIPTION, MEMBER)                                                     \
    add({NAME, "", "on | off", DESCRIPTION,                                                              \
         [](const SettingsRefs& r) { return r.render ? std::string(r.render->MEMBER ? "on" : "off") : "-"; }, \
         [](const SettingsRefs& r, const std::string& v) {                                              \
             WISP_NEED(r, render, NAME);                                                                  \
             r.render->MEMBER = onOff(NAME, v);                                                           \
         }})

std::vector<SettingSpec> buildSpecs()
{
    std::vector<SettingSpec> specs;
    auto add = [&](SettingSpec spec) { specs.push_back(std::move(spec)); };

    add({"guides", "", "1 .. " + text(kMaxGuides), "guide strands grown on the scalp",
         [](const SettingsRefs& r) { return r.growth ? text(r.growth->guides) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, growth, "guides");
             r.growth->guides = integer("guides", v, 1, kMaxGuides);
         }});
    add({"vertices_per_strand", "", "4 .. 64", "vertices per simulated guide",
         [](const SettingsRefs& r) { return r.growth ? text(r.growth->verticesPerStrand) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, growth, "vertices_per_strand");
             r.growth->verticesPerStrand = integer("vertices_per_strand", v, kMinVerticesPerStrand, kMaxVerticesPerStrand);
         }});
    add({"strands_per_guide", "", "1 .. 4096", "strands drawn per guide (more than 64 through instancing)",
         [](const SettingsRefs& r) { return r.render ? text(r.render->strands.strandsPerGuide) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "strands_per_guide");
             r.render->strands.strandsPerGuide = integer("strands_per_guide", v, kStrandsPerGuideRange.min, kStrandsPerGuideRange.max);
         }});
    add({"divisions", "", "1 .. 1024", "segments per drawn strand (more than 64 through more patches)",
         [](const SettingsRefs& r) { return r.render ? text(r.render->strands.divisions) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "divisions");
             r.render->strands.divisions = integer("divisions", v, kDivisionsRange.min, kDivisionsRange.max);
         }});
    add({"interpolation", "", "single | multi | mixed", "strands around one guide (clumps), between three, or both",
         [](const SettingsRefs& r) {
             if (!r.render)
                 return std::string("-");
             Interpolation i = r.render->strands.interpolation;
             return std::string(i == Interpolation::Single ? "single" : i == Interpolation::Multi ? "multi" : "mixed");
         },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "interpolation");
             if (v == "single")
                 r.render->strands.interpolation = Interpolation::Single;
             else if (v == "multi")
                 r.render->strands.interpolation = Interpolation::Multi;
             else if (v == "mixed")
                 r.render->strands.interpolation = Interpolation::Mixed;
             else
                 bad("interpolation", v, "allowed: single | multi | mixed");
         }});
    add({"deviation", "m", "0 .. 0.1", "strength of random strand deviations",
         [](const SettingsRefs& r) { return r.render ? text(r.render->strands.deviationMetres) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "deviation");
             r.render->strands.deviationMetres = float(number("deviation", v, kDeviationRange.min, kDeviationRange.max, "m"));
         }});
    add({"clump_radius", "m", "0 .. 0.1", "radius of the disc single-strand interpolation fills",
         [](const SettingsRefs& r) { return r.render ? text(r.render->strands.clumpRadiusMetres) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "clump_radius");
             r.render->strands.clumpRadiusMetres =
                 float(number("clump_radius", v, kClumpRadiusRange.min, kClumpRadiusRange.max, "m"));
         }});
    add({"width", "m", "1e-05 .. 0.01", "strand width at the root",
         [](const SettingsRefs& r) { return r.render ? text(r.render->strands.widthMetres) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "width");
             r.render->strands.widthMetres = float(number("width", v, kStrandWidthRange.min, kStrandWidthRange.max, "m"));
         }});
    add({"lod", "", "on | off", "fewer, wider strands with camera distance",
         [](const SettingsRefs& r) { return r.render ? std::string(r.render->strands.lod ? "on" : "off") : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "lod");
             r.render->strands.lod = onOff("lod", v);
         }});
    add({"lod_min", "", "0.01 .. 1", "the smallest share of strands LOD keeps, however far the camera",
         [](const SettingsRefs& r) { return r.render ? text(r.render->strands.lodMinFraction) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "lod_min");
             r.render->strands.lodMinFraction = float(number("lod_min", v, 0.01, 1.0, ""));
         }});
    add({"show_guides", "", "on | off", "also draw the simulated guides as lines",
         [](const SettingsRefs& r) { return r.render ? std::string(r.render->strands.showGuides ? "on" : "off") : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "show_guides");
             r.render->strands.showGuides = onOff("show_guides", v);
         }});
    add({"max_patch_vertices", "", "2 .. 4160", "vertices one tessellation patch may emit (lavapipe needs <= ~128)",
         [](const SettingsRefs& r) { return r.render ? text(r.render->strands.maxPatchVertices) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "max_patch_vertices");
             r.render->strands.maxPatchVertices =
                 integer("max_patch_vertices", v, kPatchVerticesRange.min, kPatchVerticesRange.max);
         }});
    add({"step_hz", "1/s", "30 .. 1000", "fixed simulation steps per simulated second",
         [](const SettingsRefs& r) { return r.sim ? text(r.sim->stepHz) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, sim, "step_hz");
             r.sim->stepHz = float(number("step_hz", v, 30, 1000, "1/s"));
         }});
    add({"substeps", "", "1 .. 16", "integrate/FTL passes per step",
         [](const SettingsRefs& r) { return r.sim ? text(r.sim->substeps) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, sim, "substeps");
             r.sim->substeps = integer("substeps", v, 1, 16);
         }});
    add({"friction", "", "0 .. 1", "hair-hair friction: blend toward the grid velocity",
         [](const SettingsRefs& r) { return r.sim ? text(r.sim->gridFriction) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, sim, "friction");
             r.sim->gridFriction = float(number("friction", v, 0, 1, ""));
         }});
    add({"grid", "", "8 .. 256", "hair-hair grid nodes per axis",
         [](const SettingsRefs& r) { return r.sim ? text(r.sim->gridResolution) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, sim, "grid");
             r.sim->gridResolution = integer("grid", v, 8, 256);
         }});
    add({"samples", "", "1 | 2 | 4 | 8", "MSAA samples",
         [](const SettingsRefs& r) { return r.render ? text(r.render->samples) : "-"; },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "samples");
             uint32_t n = integer("samples", v, 1, 8);
             if (n != 1 && n != 2 && n != 4 && n != 8)
                 bad("samples", v, "allowed: 1 | 2 | 4 | 8");
             r.render->samples = n;
         }});
    WISP_RENDER_ON_OFF("shadows", "the key light's shadows (head and hair cast on each other)", shadows.enabled);
    WISP_RENDER_NUMBER("shadow_size", "texels", kShadowMapSizeRange, "shadow and deep opacity map size per side",
                       shadows.mapSize, uint32_t);
    WISP_RENDER_NUMBER("pcf_samples", "", kPcfSamplesRange, "percentage-closer filtering taps per shadow lookup",
                       shadows.pcfSamples, uint32_t);
    WISP_RENDER_NUMBER("pcf_radius", "texels", kPcfRadiusRange, "radius of the PCF disk", shadows.pcfRadiusTexels, float);
    WISP_RENDER_NUMBER("dom_layers", "", kDomLayersRange,
                       "deep opacity map layers for hair self-shadowing (0: PCF on the hair's depth instead)",
                       shadows.domLayers, uint32_t);
    WISP_RENDER_NUMBER("dom_spacing", "m", kDomSpacingRange, "depth of one deep opacity layer", shadows.domSpacingMetres,
                       float);
    WISP_RENDER_NUMBER("dom_density", "", kDomKappaRange,
                       "kappa of the hair's transmittance exp(-kappa * opacity) toward the light", shadows.domKappa, float);
    WISP_RENDER_NUMBER("shadow_strands", "", kShadowStrandsRange,
                       "share of the strands drawn into the light's maps (fewer, wider: the same coverage)",
                       shadows.strandFraction, float);
    add({"hair_raster", "", "graphics | compute | auto",
         "how the hair is drawn: tessellation and geometry shaders, or compute (tiles, analytic coverage, the "
         "nearest oit_k sorted); auto: compute on GPUs, graphics on CPU drivers",
         [](const SettingsRefs& r) {
             if (!r.render)
                 return std::string("-");
             HairRaster m = r.render->hairRaster;
             return std::string(m == HairRaster::Graphics ? "graphics" : m == HairRaster::Compute ? "compute" : "auto");
         },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "hair_raster");
             if (v == "graphics")
                 r.render->hairRaster = HairRaster::Graphics;
             else if (v == "compute")
                 r.render->hairRaster = HairRaster::Compute;
             else if (v == "auto")
                 r.render->hairRaster = HairRaster::Auto;
             else
                 bad("hair_raster", v, "allowed: graphics | compute | auto");
         }});
    add({"transparency", "", "oit | msaa", "hair blending: sorted per-pixel lists, or opaque coverage with MSAA",
         [](const SettingsRefs& r) {
             return r.render ? std::string(r.render->transparency.mode == Transparency::Oit ? "oit" : "msaa") : "-";
         },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "transparency");
             if (v == "oit")
                 r.render->transparency.mode = Transparency::Oit;
             else if (v == "msaa")
                 r.render->transparency.mode = Transparency::Msaa;
             else
                 bad("transparency", v, "allowed: oit | msaa");
         }});
    WISP_RENDER_NUMBER("oit_k", "", kOitKRange, "nearest hair fragments sorted per pixel (the rest blended unsorted)",
                       transparency.oitK, uint32_t);
    WISP_RENDER_NUMBER("oit_nodes_per_pixel", "", kOitNodesPerPixelRange,
                       "OIT fragment pool per pixel, 0 = automatic (up to 24 as memory allows; fragments past it are dropped and counted)",
                       transparency.oitNodesPerPixel, uint32_t);
    WISP_RENDER_NUMBER("hair_opacity", "", kOpacityRange, "opacity of one strand that covers its pixel",
                       transparency.hairOpacity, float);
    add({"shading", "", "karis | kajiya | lut", "hair shading model (lut: tables from the reference BSDF)",
         [](const SettingsRefs& r) {
             if (!r.render)
                 return std::string("-");
             ShadingModel m = r.render->hair.model;
             return std::string(m == ShadingModel::Karis ? "karis" : m == ShadingModel::Kajiya ? "kajiya" : "lut");
         },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "shading");
             if (v == "karis")
                 r.render->hair.model = ShadingModel::Karis;
             else if (v == "kajiya")
                 r.render->hair.model = ShadingModel::Kajiya;
             else if (v == "lut")
                 r.render->hair.model = ShadingModel::Lut;
             else
                 bad("shading", v, "allowed: karis | kajiya | lut");
         }});
    add({"hair_preset", "", kHairPresets, "a hair colour by name (sets melanin and pheomelanin)",
         [](const SettingsRefs& r) { return std::string(r.render ? "-" : "-"); },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "hair_preset");
             if (!applyHairPreset(r.render->hair, v))
                 bad("hair_preset", v, std::string("allowed: ") + kHairPresets);
         }});
    WISP_RENDER_NUMBER("melanin", "", kMelaninRange, "eumelanin concentration (black ~8, brown ~1.3, blonde ~0.2)",
                       hair.eumelanin, float);
    WISP_RENDER_NUMBER("pheomelanin", "", kMelaninRange, "pheomelanin concentration (red)", hair.pheomelanin, float);
    add({"hair_color", "", "R,G,B in 0.0001 .. 1", "the colour the hair should look, instead of melanin (linear RGB)",
         [](const SettingsRefs& r) {
             if (!r.render || !r.render->hair.useColor)
                 return std::string("-");
             glm::vec3 c = r.render->hair.color;
             return text(c.r) + "," + text(c.g) + "," + text(c.b);
         },
         [](const SettingsRefs& r, const std::string& v) {
             WISP_NEED(r, render, "hair_color");
             glm::vec3 c;
             size_t start = 0;
             for (int i = 0; i < 3; ++i) {
                 size_t comma = v.find(',', start);
                 if ((i < 2) != (comma != std::string::npos))
                     bad("hair_color", v, "expected three numbers R,G,B");
                 std::string part = v.substr(start, i < 2 ? comma - start : std::string::npos);
                 c[i] = float(number("hair_color", part, 1e-4, 1.0, ""));
                 start = comma + 1;
             }
             r.render->hair.color = c;
             r.render->hair.useColor = true;
         }});
    WISP_RENDER_NUMBER("beta_m", "", kRoughnessRange, "longitudinal roughness of the fibre (highlight width)",
                       hair.betaM, float);
    WISP_RENDER_NUMBER("beta_n", "", kRoughnessRange, "azimuthal roughness of the fibre", hair.betaN, float);
    WISP_RENDER_NUMBER("cuticle_tilt", "deg", kCuticleTiltRange, "cuticle scale tilt (shifts the highlights)",
                       hair.cuticleTiltDeg, float);
    WISP_RENDER_NUMBER("ior", "", kEtaRange, "index of refraction of the fibre", hair.eta, float);
    WISP_RENDER_NUMBER("color_variation", "", kVariationRange, "per-strand spread of the hair colour",
                       hair.variation, float);
    WISP_RENDER_NUMBER("streaks", "", kVariationRange, "lighter and darker streaks along strands", hair.streaks, float);
    WISP_RENDER_ON_OFF("reverse_order", "draw the strands last to first (to check order independence)",
                       strands.reverseOrder);
    return specs;
}

#undef WISP_RENDER_NUMBER
#undef WISP_RENDER_ON_OFF

}  // namespace

const std::vector<SettingSpec>& settingSpecs()
{
    static const std::vector<SettingSpec> specs = buildSpecs();
    return specs;
}

void applySetting(const SettingsRefs& refs, const std::string& assignment)
{
    size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        throw UserError("--set " + assignment + ": expected NAME=VALUE (see 'wisp settings')");
    std::string name = assignment.substr(0, eq);
    for (const SettingSpec& spec : settingSpecs())
        if (spec.name == name) {
            spec.set(refs, assignment.substr(eq + 1));
            return;
        }
    throw UserError("--set " + assignment + ": unknown setting '" + name + "' (see 'wisp settings')");
}

std::string settingsTable()
{
    GrowthSettings growth;
    SimSettings sim;
    RenderSettings render;
    SettingsRefs defaults{&growth, &sim, &render};
    std::ostringstream out;
    out << "NAME                 UNIT  RANGE                    DEFAULT    DESCRIPTION\n";
    for (const SettingSpec& s : settingSpecs()) {
        std::string value = s.get(defaults);
        out << s.name << std::string(21 - std::min<size_t>(20, s.name.size()), ' ') << s.unit
            << std::string(6 - std::min<size_t>(5, s.unit.size()), ' ') << s.range
            << std::string(25 - std::min<size_t>(24, s.range.size()), ' ') << value
            << std::string(11 - std::min<size_t>(10, value.size()), ' ') << s.description << "\n";
    }
    return out.str();
}

}  // namespace wisp
