// app/commands/bsdf_command.cpp: the `bsdf` subcommand: options with their ranges (from shading/hair_bsdf.h),
// the directions' checks, and the three outputs (f, a model's S / |wi.z|, the comparison table).
#include "app/commands/bsdf_command.h"

#include "app/scene/session_options.h"
#include "core/error.h"
#include "shading/hair_models.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace wisp {

namespace {

using shading::HairModel;

struct BsdfOptions {
    shading::HairParams params;
    std::vector<float> sigmaA, melanin, color, wo, wi;
    std::string model; // "", or a name from shading::modelName
    bool compare = false;
    bool json = false;
    CLI::App* command = nullptr;
};

glm::vec3 direction(const std::vector<float>& v, const char* option)
{
    glm::vec3 d(v[0], v[1], v[2]);
    if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z))
        throw UserError(std::string("bsdf: ") + option + " must be three finite numbers X,Y,Z");
    float len = glm::length(d);
    if (!(len > 1e-12f))
        throw UserError(std::string("bsdf: ") + option + " is a zero vector: it has no direction");
    return glm::normalize(d);
}

CLI::Validator range(Range r)
{
    return within(r.min, r.max);
}

void applyAbsorption(BsdfOptions& o)
{
    if (!o.sigmaA.empty())
        o.params.sigmaA = glm::vec3(o.sigmaA[0], o.sigmaA[1], o.sigmaA[2]);
    else if (!o.melanin.empty())
        o.params.sigmaA = shading::sigmaAFromMelanin(o.melanin[0], o.melanin.size() > 1 ? o.melanin[1] : 0.0f);
    else if (!o.color.empty())
        o.params.sigmaA = shading::sigmaAFromColor(glm::vec3(o.color[0], o.color[1], o.color[2]), o.params.betaN);
}

void printCompare(const BsdfOptions& o)
{
    shading::CompareOptions c;
    std::vector<shading::ModelError> errors = shading::compareModels(o.params, c);
    const shading::HairParams& p = o.params;
    if (o.json) {
        nlohmann::json out = {{"reference", "Chiang 2016 as pbrt-v3, averaged across the fibre"},
                              {"eta", p.eta},
                              {"beta_m", p.betaM},
                              {"beta_n", p.betaN},
                              {"alpha_deg", p.alphaDeg},
                              {"sigma_a", {p.sigmaA.x, p.sigmaA.y, p.sigmaA.z}},
                              {"outgoing", c.outgoing},
                              {"incoming", c.incoming},
                              {"h_samples", c.hSamples},
                              {"lut_size", gpu::kHairLutSize},
                              {"models", nlohmann::json::array()}};
        for (const shading::ModelError& e : errors)
            out["models"].push_back({{"model", shading::modelName(e.model)},
                                     {"relative_rms", e.relativeRms},
                                     {"brightness", e.brightness},
                                     {"finite_non_negative", e.finiteNonNegative}});
        std::cout << out.dump(2) << "\n";
        return;
    }
    std::printf("real-time hair models against the reference (Chiang 2016 as pbrt-v3, averaged across the fibre)\n"
                "eta %g, beta_m %g, beta_n %g, alpha %g deg, sigma_a %g %g %g\n"
                "%d x %d direction pairs (Fibonacci spheres), %d h samples, lookup tables %ux%u\n\n",
                double(p.eta), double(p.betaM), double(p.betaN), double(p.alphaDeg), double(p.sigmaA.x),
                double(p.sigmaA.y), double(p.sigmaA.z), c.outgoing, c.incoming, c.hSamples, gpu::kHairLutSize,
                gpu::kHairLutSize);
    std::printf("%-8s  %12s  %10s\n", "model", "relative RMS", "brightness");
    for (const shading::ModelError& e : errors)
        std::printf("%-8s  %12.4f  %10.3f%s\n", shading::modelName(e.model), e.relativeRms, e.brightness,
                    e.finiteNonNegative ? "" : "  (non-finite or negative values!)");
    std::printf("\nrelative RMS: sqrt(sum (S_model - S_ref)^2 / sum S_ref^2) over all pairs and RGB;\n"
                "brightness: sum lum(S_model) / sum lum(S_ref)\n");
}

// CLI11's ranges let NaN through: name the option here.
void requireFinite(const BsdfOptions& o)
{
    const shading::HairParams& p = o.params;
    std::pair<const char*, float> scalars[] = {
        {"--h", p.h}, {"--eta", p.eta}, {"--beta-m", p.betaM}, {"--beta-n", p.betaN}, {"--alpha", p.alphaDeg}};
    for (auto [name, value] : scalars)
        if (!std::isfinite(value))
            throw UserError(std::string("bsdf: ") + name + " must be a finite number");
    std::pair<const char*, const std::vector<float>*> lists[] = {
        {"--sigma-a", &o.sigmaA}, {"--melanin", &o.melanin}, {"--color", &o.color}};
    for (auto [name, values] : lists)
        for (float v : *values)
            if (!std::isfinite(v))
                throw UserError(std::string("bsdf: ") + name + " must be finite numbers");
}

HairModel modelFromName(const std::string& name)
{
    for (HairModel m : shading::kHairModels)
        if (name == shading::modelName(m))
            return m;
    throw UserError("bsdf: --model " + name + " is not one of karis, kajiya, lut");
}

int run(BsdfOptions& o)
{
    requireFinite(o);
    applyAbsorption(o);
    shading::validate(o.params);
    if (o.compare) {
        printCompare(o);
        return 0;
    }
    if (o.wo.empty() || o.wi.empty())
        throw UserError("bsdf: --wo X,Y,Z and --wi X,Y,Z are required (or --compare)");
    glm::vec3 wo = direction(o.wo, "--wo");
    glm::vec3 wi = direction(o.wi, "--wi");
    glm::vec3 f;
    if (!o.model.empty()) {
        HairModel model = modelFromName(o.model);
        shading::HairLut lut;
        if (model == HairModel::Lut)
            lut = shading::buildHairLut(o.params);
        glm::vec3 s = shading::evaluateModel(model, shading::packHairMaterial(o.params), lut, wo, wi);
        f = std::abs(wi.z) > 0.0f ? s / std::abs(wi.z) : s; // as pbrt's f
    } else {
        f = shading::HairBsdf(o.params).f(wo, wi);
    }
    std::printf("%.9g %.9g %.9g\n", double(f.x), double(f.y), double(f.z));
    return 0;
}

} // namespace

std::function<int()> addBsdfCommand(CLI::App& app)
{
    auto o = std::make_shared<BsdfOptions>();
    CLI::App* cmd = app.add_subcommand(
        "bsdf", "the hair BSDF on the CPU: the reference f for --wo/--wi (pbrt-v3's f, local frame, fibre along x), "
                "a real-time model (--model), or every model's error over the sphere (--compare)");
    o->command = cmd;
    shading::HairParams& p = o->params;
    cmd->add_option("--h", p.h, "offset across the fibre of the reference (the models average over it)")
        ->check(range(shading::kHRange))
        ->capture_default_str();
    cmd->add_option("--eta", p.eta, "index of refraction of the fibre")
        ->check(range(shading::kEtaRange))
        ->capture_default_str();
    cmd->add_option("--beta-m", p.betaM, "longitudinal roughness")
        ->check(range(shading::kBetaRange))
        ->capture_default_str();
    cmd->add_option("--beta-n", p.betaN, "azimuthal roughness")
        ->check(range(shading::kBetaRange))
        ->capture_default_str();
    cmd->add_option("--alpha", p.alphaDeg, "cuticle scale tilt, degrees")
        ->check(range(shading::kAlphaDegRange))
        ->capture_default_str();
    CLI::Option* sigma =
        cmd->add_option("--sigma-a", o->sigmaA, "absorption R,G,B per unit fibre radius (default: melanin 1.3)")
            ->delimiter(',')
            ->expected(3)
            ->check(range(shading::kSigmaARange));
    CLI::Option* melanin =
        cmd->add_option("--melanin", o->melanin, "EU[,PHEO]: eumelanin and pheomelanin concentrations (Chiang 2016)")
            ->delimiter(',')
            ->expected(1, 2)
            ->check(range(shading::kMelaninRange));
    CLI::Option* color =
        cmd->add_option("--color", o->color,
                        "R,G,B: the colour the hair should render as (Chiang 2016 eq. 9, with --beta-n)")
            ->delimiter(',')
            ->expected(3)
            ->check(range(shading::kColorRange));
    sigma->excludes(melanin)->excludes(color);
    melanin->excludes(color);
    CLI::Option* wo =
        cmd->add_option("--wo", o->wo, "X,Y,Z direction to the viewer (normalised)")->delimiter(',')->expected(3);
    CLI::Option* wi =
        cmd->add_option("--wi", o->wi, "X,Y,Z direction to the light (normalised)")->delimiter(',')->expected(3);
    CLI::Option* model =
        cmd->add_option("--model", o->model, "print a real-time model's S / |wi.z| instead: karis, kajiya or lut")
            ->check(CLI::IsMember({"karis", "kajiya", "lut"}));
    CLI::Option* compare =
        cmd->add_flag("--compare", o->compare,
                      "print each real-time model's relative RMS error against the reference over the sphere");
    cmd->add_flag("--json", o->json, "with --compare: one JSON object")->needs(compare);
    compare->excludes(wo)->excludes(wi)->excludes(model);
    return [o]() { return o->command->parsed() ? run(*o) : -1; };
}

} // namespace wisp
