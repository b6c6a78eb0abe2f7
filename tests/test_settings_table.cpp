// tests/test_settings_table.cpp: the settings table is the one source of every front end: each
// setting round-trips through --set, a scene file and the panel's code path; an out-of-range value
// is refused with the same words by --set, its option, a scene and the panel; every option of the
// table is on the commands that use it; the JSON outputs name every setting.
#include "app/scene/scene_file.h"
#include "app/scene/session_options.h"
#include "app/settings/settings_table.h"
#include "core/error.h"
#include "physics/hair_style.h"
#include "shading/hair_look.h"
#include "test_support.h"

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <set>

using namespace wisp;

namespace {

template <typename F> std::string errorOf(F&& f)
{
    try {
        f();
    } catch (const UserError& e) {
        return e.what();
    }
    return "";
}

// A valid value of `spec` other than its default.
SettingValue otherValue(const SettingSpec& spec)
{
    SettingValue now = spec.get(Settings{});
    SettingValue v = now;
    v.unset = false;
    switch (spec.type) {
    case SettingType::Number:
    case SettingType::Integer:
        v.number = now.number == spec.range.max || now.unset ? spec.range.min : spec.range.max;
        if (spec.optional() && now.unset)
            v.number = 0.5 * (spec.range.min + spec.range.max);
        break;
    case SettingType::OnOff:
        v.number = now.number != 0.0 ? 0.0 : 1.0;
        break;
    case SettingType::Choice:
        v.number = now.number == 0.0 ? 1.0 : 0.0;
        break;
    case SettingType::Vector:
    case SettingType::Color:
        v.vector = glm::dvec3(spec.range.max, spec.range.min, spec.range.max);
        break;
    }
    return v;
}

// Every setting's value in `s`, as text.
std::map<std::string, std::string> textsOf(const Settings& s)
{
    std::map<std::string, std::string> out;
    for (const SettingSpec& spec : settingSpecs())
        out[spec.name] = settingText(spec, spec.get(s));
    return out;
}

// `settings` saved as a scene's settings, read back from the JSON text and applied to defaults.
Settings throughAScene(const Settings& settings)
{
    Scene scene;
    scene.settings = currentSettings(settings);
    Scene read = parseScene(sceneJson(scene), "s.json");
    EXPECT_EQ(read, scene);
    Settings out;
    HairSource source;
    applyScene(read, "s.json", out, source);
    return out;
}

// A command's shared options parsed from `line`, resolved.
SessionOptions commandLine(const std::string& line, SessionCommandLine::Uses uses = {})
{
    CLI::App app;
    CLI::App* cmd = app.add_subcommand("cmd");
    SessionCommandLine options(cmd, uses);
    try {
        app.parse("cmd " + line, false);
    } catch (const CLI::ParseError& e) {
        throw UserError(e.what());
    }
    return options.resolve();
}

} // namespace

TEST(SettingsTable, NamesAreUniqueAndEveryEntryIsComplete)
{
    std::set<std::string> names, options;
    for (const SettingSpec& spec : settingSpecs()) {
        EXPECT_TRUE(names.insert(spec.name).second) << spec.name;
        EXPECT_FALSE(spec.help.empty()) << spec.name;
        EXPECT_TRUE(spec.get && spec.put) << spec.name;
        if (!spec.option.empty()) {
            EXPECT_TRUE(options.insert(spec.option).second) << spec.option;
        }
        if (spec.type == SettingType::Choice) {
            EXPECT_GE(spec.choices.size(), 2u) << spec.name;
        } else if (spec.type != SettingType::OnOff) {
            EXPECT_LT(spec.range.min, spec.range.max) << spec.name;
        }
        // The default is a value the table itself accepts.
        Settings defaults;
        EXPECT_EQ(errorOf([&] { checkSetting(spec, spec.get(defaults), spec.name); }), "") << spec.name;
    }
    // Test knobs are not settings.
    EXPECT_EQ(findSetting("reverse_order"), nullptr);
    EXPECT_EQ(findSetting("max_patch_vertices"), nullptr);
    // What no front end could set before the table.
    for (const char* name :
         {"gravity", "wind_frequency", "penalty_stiffness", "collision_margin", "repulsion", "grid_atomics"})
        EXPECT_NE(findSetting(name), nullptr) << name;
}

TEST(SettingsTable, EverySettingRoundTripsThroughSetASceneAndThePanel)
{
    Settings all; // every setting changed at once, in the table's order
    for (const SettingSpec& spec : settingSpecs()) {
        SettingValue v = otherValue(spec);
        std::string text = settingText(spec, v);
        SCOPED_TRACE(spec.name + "=" + text);

        // --set NAME=VALUE, then the value read back as text.
        Settings viaSet;
        ASSERT_EQ(errorOf([&] { applySetting(viaSet, spec.name + "=" + text); }), "");
        EXPECT_EQ(settingText(spec, spec.get(viaSet)), text);
        EXPECT_EQ(spec.get(viaSet), v);

        // The panel: the value its control produces, through the window's edit.
        Settings viaPanel;
        SettingEdit edit = editSetting(viaPanel, spec, v);
        if (spec.change == SettingChange::Restart) {
            EXPECT_NE(edit.error.find("needs a restart"), std::string::npos) << edit.error;
            EXPECT_EQ(panelControl(spec).enabled, false);
        } else {
            EXPECT_EQ(edit.error, "");
            EXPECT_EQ(edit.change, spec.change);
            EXPECT_EQ(spec.get(viaPanel), v);
        }

        // A scene file's "settings", written and read back (a derived setting through the ones it is
        // made of).
        EXPECT_EQ(textsOf(throughAScene(viaSet)), textsOf(viaSet));

        // The JSON of the outputs, read back as a scene reads JSON.
        nlohmann::ordered_json json = settingJson(spec, v);
        EXPECT_EQ(settingFromJson(spec, json, spec.name), v) << json.dump();

        setSetting(all, spec, v, spec.name);
    }
    EXPECT_EQ(textsOf(throughAScene(all)), textsOf(all));
    EXPECT_EQ(settingsJson(all).size(), settingSpecs().size());
}

TEST(SettingsTable, OutOfRangeValuesAreRefusedEverywhereWithTheSameWords)
{
    struct Case {
        const char* name;
        const char* option; // "" when it has none
        const char* value;
        const char* why;
    };
    for (const Case& c : {Case{"friction", "--friction", "2", "2 is out of range: allowed 0 .. 1"},
                          Case{"guides", "--guides", "0", "0 is out of range: allowed 1 .. 2000000"},
                          Case{"step_hz", "--step-hz", "nan", "'nan' is not a finite number"},
                          Case{"substeps", "--substeps", "2.5", "2.5 is not a whole number"},
                          Case{"grid_atomics", "--grid-atomics", "double", "'double' is not allowed: fixed | float"},
                          Case{"shadow_size", "", "10", "10 is out of range: allowed 64 .. 8192 texels"},
                          Case{"rim_intensity", "", "25", "25 is out of range: allowed 0 .. 20"},
                          Case{"fill_elevation", "", "90", "90 is out of range: allowed -89 .. 89 deg"},
                          Case{"interpolation", "", "cubic", "'cubic' is not allowed: single | multi | mixed"},
                          Case{"wind", "--wind", "0,0,1e9",
                               "the third value (1000000000) is out of range: allowed -100 .. 100 m/s^2"}}) {
        SCOPED_TRACE(c.name);
        std::string why = c.why;
        Settings settings;
        EXPECT_EQ(errorOf([&] { applySetting(settings, std::string(c.name) + "=" + c.value); }),
                  "--set " + std::string(c.name) + ": " + why);
        EXPECT_EQ(errorOf([&] { commandLine(std::string("--set ") + c.name + "=" + c.value); }),
                  "--set " + std::string(c.name) + ": " + why);
        if (*c.option) {
            EXPECT_EQ(errorOf([&] { commandLine(std::string(c.option) + " " + c.value); }),
                      std::string(c.option) + ": " + why);
        }
        const SettingSpec& spec = settingSpec(c.name);
        std::string json = spec.type == SettingType::Vector   ? "[" + std::string(c.value) + "]"
                           : spec.type == SettingType::Choice ? "\"" + std::string(c.value) + "\""
                                                              : std::string(c.value);
        if (std::string(c.value) != "nan") { // JSON has no NaN
            std::string scene = errorOf(
                [&] { parseScene(std::string(R"({"settings": {")") + c.name + "\": " + json + "}}", "s.json"); });
            std::string pointer = "s.json: /settings/" + std::string(c.name);
            if (spec.type == SettingType::Vector) { // JSON names the element
                EXPECT_EQ(scene, pointer + "/2: 1000000000 is out of range: allowed -100 .. 100 m/s^2");
            } else {
                EXPECT_EQ(scene, pointer + ": " + why);
            }
        }
        if (spec.change != SettingChange::Restart && spec.type != SettingType::Choice &&
            std::string(c.value) != "nan") {
            SettingValue v = spec.type == SettingType::Vector ? SettingValue{.vector = {0.0, 0.0, 1e9}}
                                                              : SettingValue{.number = std::stod(c.value)};
            EXPECT_EQ(editSetting(settings, spec, v).error, std::string(c.name) + ": " + why);
        }
    }
    // A scene's own keys that are settings take the table's ranges and words.
    EXPECT_EQ(errorOf([] { parseScene(R"({"hair": {"guides": 0}})", "s.json"); }),
              "s.json: /hair/guides: 0 is out of range: allowed 1 .. 2000000");
    EXPECT_EQ(errorOf([] { parseScene(R"({"keys": [{"time": 0, "light": {"elevation": 95}}]})", "s.json"); }),
              "s.json: /keys/0/light/elevation: 95 is out of range: allowed -89 .. 89 deg");
    EXPECT_EQ(errorOf([] { parseScene(R"({"physics": {"repulsion": 3}})", "s.json"); }),
              "s.json: /physics/repulsion: 3 is out of range: allowed 0 .. 1");
}

TEST(SettingsTable, EveryOptionOfTheTableIsOnTheCommandsThatUseIt)
{
    for (const SettingSpec& spec : settingSpecs()) {
        if (spec.option.empty())
            continue;
        SCOPED_TRACE(spec.option);
        SettingValue v = otherValue(spec);
        std::string arg = spec.type == SettingType::OnOff ? spec.option : spec.option + " " + settingText(spec, v);
        SessionOptions o = commandLine(arg);
        EXPECT_EQ(spec.get(o.settings), spec.type == SettingType::OnOff ? SettingValue{.number = 1.0} : v);
        // simulate draws nothing: it has no drawing options.
        bool onSimulate = !drawsOnly(spec.group);
        std::string error = errorOf([&] { commandLine(arg, {.scene = true, .noHair = false, .draws = false}); });
        EXPECT_EQ(error.empty(), onSimulate) << error;
    }
    // --set over the options, the options over a scene.
    test::TempDir dir;
    test::writeFile(dir / "s.json", R"({"settings": {"friction": 0.5, "divisions": 7}, "hair": {"guides": 40}})");
    SessionOptions o =
        commandLine("--scene '" + (dir / "s.json").string() + "' --friction 0.25 --set friction=0.75 --guides 41");
    EXPECT_FLOAT_EQ(o.settings.sim.gridFriction, 0.75f);
    EXPECT_EQ(o.settings.growth.guides, 41u);
    EXPECT_EQ(o.settings.render.strands.divisions, 7u);
    EXPECT_NE(errorOf([] {
                  commandLine("--set width=0.001", {.scene = true, .noHair = false, .draws = false});
              }).find("--set width: this command does not use it"),
              std::string::npos);
}

TEST(SettingsTable, ThePanelShowsEachTypeAsItsControl)
{
    using Kind = PanelControl::Kind;
    EXPECT_EQ(panelControl(settingSpec("friction")).kind, Kind::Slider);
    EXPECT_EQ(panelControl(settingSpec("divisions")).kind, Kind::IntegerSlider);
    EXPECT_EQ(panelControl(settingSpec("lod")).kind, Kind::Checkbox);
    EXPECT_EQ(panelControl(settingSpec("shading")).kind, Kind::Combo);
    EXPECT_EQ(panelControl(settingSpec("hair_color")).kind, Kind::Color);
    EXPECT_EQ(panelControl(settingSpec("wind")).kind, Kind::Vector);
    EXPECT_TRUE(panelControl(settingSpec("width")).logarithmic); // 1e-5 .. 0.01 m
    EXPECT_FALSE(panelControl(settingSpec("friction")).logarithmic);
    EXPECT_FALSE(panelControl(settingSpec("guides")).enabled); // grown at start
}

// multiple_scattering is on by default, a checkbox, and --set turns it off (what the frame's
// parameters take from it: tests/test_hair_look_render.cpp).
TEST(SettingsTable, MultipleScatteringIsOnByDefaultAndTurnsOff)
{
    Settings s;
    EXPECT_TRUE(s.render.hair.multipleScattering);
    EXPECT_EQ(settingText(settingSpec("multiple_scattering"), settingSpec("multiple_scattering").get(s)), "on");
    applySetting(s, "multiple_scattering=off");
    EXPECT_FALSE(s.render.hair.multipleScattering);
    EXPECT_EQ(settingSpec("multiple_scattering").group, SettingGroup::Look);
    EXPECT_EQ(panelControl(settingSpec("multiple_scattering")).kind, PanelControl::Kind::Checkbox);
}

TEST(SettingsTable, SettingsListsEveryNameWithWhatAChangeNeeds)
{
    std::string table = settingsTable();
    for (const SettingSpec& spec : settingSpecs())
        EXPECT_NE(table.find("\n" + spec.name + " "), std::string::npos) << spec.name;
    EXPECT_NE(table.find("single | multi | mixed"), std::string::npos);
    nlohmann::ordered_json json = settingsTableJson();
    ASSERT_EQ(json.size(), settingSpecs().size());
    EXPECT_EQ(json[0]["name"], settingSpecs()[0].name);
    for (const auto& entry : json)
        EXPECT_TRUE(entry.contains("default") && entry.contains("change") && entry.contains("help")) << entry.dump();
}

// hair_style sets what a style asks of the drawing with its growth: the afro's coils, finer than its
// guides' vertices, with the divisions to draw them; a straight style sets them back.
TEST(SettingsTable, AStyleSetsItsDrawnCoilAndTheDivisionsToDrawIt)
{
    Settings s;
    applySetting(s, "hair_style=afro");
    const StrandSettings& drawn = s.render.strands;
    EXPECT_GT(drawn.coilRadiusMetres, 0.0f);
    EXPECT_GT(drawn.coilTurnsPerMetre, 0.0f);
    float turn = 1.0f / drawn.coilTurnsPerMetre;
    float segment = s.growth.lengthMetres / float(s.growth.verticesPerStrand - 1);
    EXPECT_LT(turn, 3.0f * segment) << "a coil the guides' vertices could hold needs no drawing";
    float pointsPerTurn = float(drawn.divisions) / (s.growth.lengthMetres * drawn.coilTurnsPerMetre);
    EXPECT_GE(pointsPerTurn, 6.0f) << "the style's own strands are drawn at the coil's full radius";
    EXPECT_EQ(settingText(settingSpec("hair_style"), settingSpec("hair_style").get(s)), "afro");
    // Its strands of 96 divisions cost four times another style's segments: it draws fewer a guide.
    EXPECT_LT(drawn.strandsPerGuide, StrandSettings{}.strandsPerGuide);

    applySetting(s, "hair_style=bob");
    EXPECT_EQ(s.render.strands.coilRadiusMetres, 0.0f);
    EXPECT_EQ(s.render.strands.divisions, StrandSettings{}.divisions);
    EXPECT_EQ(s.render.strands.strandsPerGuide, StrandSettings{}.strandsPerGuide);

    // The drawn strands' own lengths: the default is the bob's, the crop's short hair thins out
    // over more of its length, and a style sets it again after a change.
    EXPECT_EQ(s.render.strands.lengthJitter, StrandSettings{}.lengthJitter);
    EXPECT_GT(StrandSettings{}.lengthJitter, 0.0f);
    applySetting(s, "strand_length_jitter=0");
    EXPECT_EQ(s.render.strands.lengthJitter, 0.0f);
    applySetting(s, "hair_style=crop");
    EXPECT_GT(s.render.strands.lengthJitter, StrandSettings{}.lengthJitter);
    EXPECT_THROW(applySetting(s, "strand_length_jitter=1.5"), UserError);
}

// Every word of every choice setting, set by --set, lands in its field as the value it names
// (written out here, not read from the table: a choice listed in an order other than its enum's, or
// a word bound to the wrong value, fails), and reads back as the same word. A choice setting with
// no case here fails too, so a new one comes with its own.
TEST(SettingsTable, EveryChoiceParsesToTheValueItNames)
{
    using GridAtomics = SimSettings::GridAtomics;
    // setting -> (word -> a check that `s` holds the value the word names)
    using Check = std::function<bool(const Settings&)>;
    std::map<std::string, std::map<std::string, Check>> cases;
    auto is = [](auto field, auto value) -> Check { return [=](const Settings& s) { return field(s) == value; }; };
    auto parting = [](const Settings& s) { return s.growth.parting; };
    cases["parting"] = {{"none", is(parting, Parting::None)},
                        {"centre", is(parting, Parting::Centre)},
                        {"side", is(parting, Parting::Side)}};
    auto atomics = [](const Settings& s) { return s.sim.gridAtomics; };
    cases["grid_atomics"] = {{"fixed", is(atomics, GridAtomics::Fixed)}, {"float", is(atomics, GridAtomics::Float)}};
    auto interpolation = [](const Settings& s) { return s.render.strands.interpolation; };
    cases["interpolation"] = {{"single", is(interpolation, Interpolation::Single)},
                              {"multi", is(interpolation, Interpolation::Multi)},
                              {"mixed", is(interpolation, Interpolation::Mixed)}};
    auto raster = [](const Settings& s) { return s.render.hairRaster; };
    cases["hair_raster"] = {{"graphics", is(raster, HairRaster::Graphics)},
                            {"compute", is(raster, HairRaster::Compute)},
                            {"auto", is(raster, HairRaster::Auto)}};
    auto transparency = [](const Settings& s) { return s.render.transparency.mode; };
    cases["transparency"] = {{"oit", is(transparency, Transparency::Oit)},
                             {"msaa", is(transparency, Transparency::Msaa)}};
    auto model = [](const Settings& s) { return s.render.hair.model; };
    cases["shading"] = {{"karis", is(model, ShadingModel::Karis)},
                        {"kajiya", is(model, ShadingModel::Kajiya)},
                        {"lut", is(model, ShadingModel::Lut)}};
    auto samples = [](const Settings& s) { return s.render.samples; };
    cases["samples"] = {{"1", is(samples, 1u)}, {"2", is(samples, 2u)}, {"4", is(samples, 4u)}, {"8", is(samples, 8u)}};
    // The named styles and presets: the word sets that style's growth, or that preset's melanins.
    for (const HairStyle& h : hairStyles()) {
        std::string name = h.name;
        cases["hair_style"][name] = [name](const Settings& s) {
            for (const HairStyle& style : hairStyles())
                if (style.name == name)
                    return isHairStyle(s.growth, style);
            return false;
        };
    }
    for (const HairPreset& p : kHairPresets) {
        float eumelanin = p.eumelanin, pheomelanin = p.pheomelanin;
        cases["hair_preset"][p.name] = [=](const Settings& s) {
            return !s.render.hair.useColor && s.render.hair.eumelanin == eumelanin &&
                   s.render.hair.pheomelanin == pheomelanin;
        };
    }
    // "custom" keeps what is set: the field as the defaults have it.
    cases["hair_style"]["custom"] = [](const Settings& s) { return s.growth == Settings{}.growth; };
    cases["hair_preset"]["custom"] = [](const Settings& s) {
        const HairLook &look = s.render.hair, defaults = Settings{}.render.hair;
        return look.useColor == defaults.useColor && look.eumelanin == defaults.eumelanin &&
               look.pheomelanin == defaults.pheomelanin;
    };

    std::set<std::string> choiceSettings;
    for (const SettingSpec& spec : settingSpecs()) {
        if (spec.type != SettingType::Choice)
            continue;
        choiceSettings.insert(spec.name);
        ASSERT_TRUE(cases.count(spec.name)) << spec.name << ": a choice setting with no case in this test";
        const std::map<std::string, Check>& words = cases.at(spec.name);
        EXPECT_EQ(std::set<std::string>(spec.choices.begin(), spec.choices.end()).size(), spec.choices.size())
            << spec.name << ": a word listed twice";
        EXPECT_EQ(spec.choices.size(), words.size()) << spec.name;
        for (const std::string& word : spec.choices) {
            ASSERT_TRUE(words.count(word)) << spec.name << "=" << word << ": a word with no case in this test";
            Settings s;
            applySetting(s, spec.name + "=" + word);
            EXPECT_TRUE(words.at(word)(s)) << spec.name << "=" << word << " set another value";
            if (word != "custom") { // "custom" reads back as the style (or preset) the defaults are
                EXPECT_EQ(settingText(spec, spec.get(s)), word) << spec.name;
            }
            // Another word first, then this one: the value does not depend on what was there.
            for (const std::string& other : spec.choices) {
                if (other == "custom" || word == "custom")
                    continue;
                Settings t;
                applySetting(t, spec.name + "=" + other);
                applySetting(t, spec.name + "=" + word);
                EXPECT_TRUE(words.at(word)(t)) << spec.name << "=" << other << " then " << word;
            }
        }
    }
    for (const auto& [name, words] : cases)
        EXPECT_TRUE(choiceSettings.count(name)) << name << ": not a choice setting of the table";
}

// The default draws a full head of hair, about 100,000 strands, from its guides and the
// strands drawn around each.
TEST(SettingsTable, TheDefaultDrawsAboutAHundredThousandStrands)
{
    Settings s;
    uint64_t strands = uint64_t(s.growth.guides) * s.render.strands.strandsPerGuide;
    EXPECT_GE(strands, 95'000u);
    EXPECT_LE(strands, 110'000u);
    applySetting(s, "hair_style=bob"); // the default is the bob, its drawing too
    EXPECT_EQ(uint64_t(s.growth.guides) * s.render.strands.strandsPerGuide, strands);
}
