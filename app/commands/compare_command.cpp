// app/commands/compare_command.cpp: `wisp compare TEST.png REFERENCE.png`: how far a frame is from a
// reference of it (app/image/image_compare.h): RMSE, relMSE and SSIM over the frame and, with --mask (the
// same frame drawn without hair), over the hair alone; --out writes the per-pixel error in false
// colour. No GPU. Every input is read and checked before the error image is written.
#include "app/commands/commands.h"

#include "app/image/image_compare.h"
#include "app/image/image_io.h"
#include "core/error.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

namespace wisp {

namespace {

struct CompareOptions {
    std::string test, reference, mask, out;
    double maskThreshold = 0.0; // levels of 255
    double errorScale = 0.1;    // linear error shown at the top of the colour map
    bool json = false;
    CLI::App* command = nullptr;
};

std::string sizeText(const PngImage& image)
{
    return std::to_string(image.width) + " x " + std::to_string(image.height);
}

void requireSameSize(const PngImage& image, const std::string& what, const PngImage& test, const std::string& testPath)
{
    if (image.width != test.width || image.height != test.height)
        throw UserError("compare: " + what + " is " + sizeText(image) + " but the test image " + testPath + " is " +
                        sizeText(test) + ": the images must be the same size");
}

// A number for JSON: NaN (no SSIM window centre among the measured pixels) is null.
nlohmann::ordered_json number(double v)
{
    return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json errorJson(const ImageError& e)
{
    return {{"pixels", e.pixels},
            {"rmse", number(e.rmse)},
            {"rel_mse", number(e.relMse)},
            {"ssim", number(e.ssim)},
            {"ssim_pixels", e.ssimPixels}};
}

void printRow(const char* name, const ImageError& e)
{
    std::string ssim = std::isfinite(e.ssim) ? std::to_string(e.ssim) : "n/a";
    std::printf("%-6s %9zu  %10.6f  %10.6f  %9s\n", name, e.pixels, e.rmse, e.relMse, ssim.c_str());
}

int run(const CompareOptions& o)
{
    if (!o.out.empty())
        checkPngOutput(o.out); // before any work, as every command checks its outputs
    PngImage test = readPng(o.test, "compare: the test image");
    PngImage reference = readPng(o.reference, "compare: the reference");
    requireSameSize(reference, "the reference " + o.reference, test, o.test);
    if (test.width < uint32_t(kSsimWindow) || test.height < uint32_t(kSsimWindow))
        throw UserError("compare: the images are " + sizeText(test) + ": SSIM's " + std::to_string(kSsimWindow) +
                        " x " + std::to_string(kSsimWindow) + " window needs at least that many pixels");
    std::vector<uint8_t> mask;
    if (!o.mask.empty()) {
        PngImage withoutHair = readPng(o.mask, "compare: --mask");
        requireSameSize(withoutHair, "--mask " + o.mask, test, o.test);
        mask = hairMask(test, withoutHair, o.maskThreshold);
        if (std::find(mask.begin(), mask.end(), uint8_t(1)) == mask.end())
            throw UserError("compare: --mask " + o.mask + ": no pixel of the test image " + o.test +
                            " differs from it by more than " + std::to_string(int(o.maskThreshold)) +
                            " levels: there is no hair to measure (is it the frame without hair?)");
    }

    LinearImage a = linearImage(test), b = linearImage(reference);
    ImageError frame = imageError(a, b);
    std::optional<ImageError> hair;
    if (!mask.empty())
        hair = imageError(a, b, mask);
    if (!o.out.empty())
        writePng(o.out, test.width, test.height, falseColor(pixelErrors(a, b), o.errorScale));

    if (o.json) {
        nlohmann::ordered_json out = {
            {"test", o.test},
            {"reference", o.reference},
            {"width", test.width},
            {"height", test.height},
            {"metrics",
             {{"rmse", "sqrt(mean (test - reference)^2) over the pixels and R, G, B, linear (sRGB decoded)"},
              {"rel_mse", "mean (test - reference)^2 / (reference^2 + epsilon), the same terms"},
              {"rel_mse_epsilon", kRelMseEpsilon},
              {"ssim", "Wang et al. 2004: 11 x 11 Gaussian window (sigma 1.5), K1 0.01, K2 0.03, on Rec. 709 luma "
                       "of the sRGB-encoded values, mean over the window centres inside the frame"}}},
            {"frame", errorJson(frame)},
            {"hair", hair ? errorJson(*hair) : nlohmann::ordered_json(nullptr)}};
        if (hair)
            out["mask"] = {{"without_hair", o.mask}, {"threshold", o.maskThreshold}};
        if (!o.out.empty())
            out["error_image"] = {{"path", o.out}, {"scale", o.errorScale}};
        std::cout << out.dump(2) << "\n";
        return 0;
    }
    std::printf("%s against the reference %s, %s\n\n", o.test.c_str(), o.reference.c_str(), sizeText(test).c_str());
    std::printf("%-6s %9s  %10s  %10s  %9s\n", "", "pixels", "RMSE", "relMSE", "SSIM");
    printRow("frame", frame);
    if (hair)
        printRow("hair", *hair);
    std::printf("\nRMSE and relMSE on linear RGB (sRGB decoded), relMSE's epsilon %g; SSIM (Wang et al. 2004, 11 x 11 "
                "Gaussian window, sigma 1.5) on luma, not defined within %d px of the border\n",
                kRelMseEpsilon, kSsimWindow / 2);
    if (hair)
        std::printf("hair: the pixels where the test image differs from %s by more than %g levels (the hair and "
                    "its shadow)\n",
                    o.mask.c_str(), o.maskThreshold);
    if (!o.out.empty())
        std::printf("error image: %s (per-pixel RMS over R, G, B, linear; dark purple 0 to pale yellow %g or more)\n",
                    o.out.c_str(), o.errorScale);
    return 0;
}

} // namespace

CommandRun addCompareCommand(CLI::App& app)
{
    auto o = std::make_shared<CompareOptions>();
    CLI::App* cmd = app.add_subcommand("compare", "how far a frame is from a reference of it: RMSE, relative MSE and "
                                                  "SSIM over the frame and the hair, and an error image (no GPU)");
    o->command = cmd;
    cmd->add_option("test", o->test, "the image to measure (PNG)")->required();
    cmd->add_option("reference", o->reference, "the reference of the same frame (PNG, the same size)")->required();
    CLI::Option* mask =
        cmd->add_option("--mask", o->mask,
                        "the test image's frame drawn without hair (PNG): the metrics also over the pixels that differ "
                        "from it, the hair (and its shadow)");
    cmd->add_option("--mask-threshold", o->maskThreshold,
                    "levels of 255 a pixel must differ by to be hair (for a noisy frame without hair)")
        ->check(within(0.0, 254.0))
        ->capture_default_str()
        ->needs(mask);
    CLI::Option* out = cmd->add_option(
        "--out", o->out,
        "write the per-pixel error (RMS over R, G, B, linear) in false colour: dark purple none, pale yellow "
        "--error-scale or more (PNG)");
    cmd->add_option("--error-scale", o->errorScale, "the linear error at the top of the error image's colour map")
        ->check(within(1e-6, 1.0))
        ->capture_default_str()
        ->needs(out);
    cmd->add_flag("--json", o->json, "print one JSON object");
    return [o]() { return o->command->parsed() ? run(*o) : -1; };
}

} // namespace wisp
