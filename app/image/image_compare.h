// app/image/image_compare.h: how far a picture is from a reference of the same frame, as rendering papers
// measure it: RMSE and relative MSE on linear RGB, SSIM (Wang et al. 2004) on luma, over the whole
// frame or over a mask (the hair: the pixels where a frame differs from the same frame drawn without
// hair), and a false-colour image of the per-pixel error on a perceptually ordered colour map. CPU
// only; `wisp compare` (app/commands/compare_command.cpp) is its command.
#pragma once

#include "app/image/image_io.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace wisp {

// SSIM's constants, as Wang et al. 2004 (section III.C) give them: an 11 x 11 circular-symmetric
// Gaussian window of standard deviation 1.5 pixels, K1 = 0.01, K2 = 0.03, dynamic range L = 1.
inline constexpr int kSsimWindow = 11;
inline constexpr double kSsimSigma = 1.5;
inline constexpr double kSsimK1 = 0.01;
inline constexpr double kSsimK2 = 0.03;
// relMSE's epsilon: mean (a - b)^2 / (b^2 + epsilon), so that black reference pixels stay finite.
inline constexpr double kRelMseEpsilon = 0.01;

// Linear RGB (the PNG's sRGB transfer undone), [0, 1], top row first. Alpha is not kept: Wisp's
// frames are opaque.
struct LinearImage {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec3> rgb;
};

// The sRGB transfer functions of IEC 61966-2-1, per channel, on [0, 1].
double decodeSrgb(double encoded);
double encodeSrgb(double linear);
LinearImage linearImage(const PngImage& png);

// The pixels (1: in the mask) where `withHair` and `withoutHair` differ by more than `threshold`
// levels of 255 in any of R, G, B: the hair, and what it changes around it (its shadow on the skin).
// The images are the same size.
std::vector<uint8_t> hairMask(const PngImage& withHair, const PngImage& withoutHair, double threshold);

struct ImageError {
    size_t pixels = 0;   // the pixels measured (the mask's, or all)
    double rmse = 0.0;   // sqrt(mean over those pixels and R, G, B of (test - reference)^2)
    double relMse = 0.0; // mean of (test - reference)^2 / (reference^2 + kRelMseEpsilon), the same terms
    // The mean of SSIM's map over the measured pixels that are window centres: the window lies
    // inside the frame (Wang et al.'s 'valid' map), so a border of kSsimWindow / 2 pixels has no
    // SSIM. NaN when no measured pixel is such a centre.
    double ssim = 0.0;
    size_t ssimPixels = 0;
};

// `test` against `reference` (the same size, at least kSsimWindow pixels each way), over the
// pixels where `mask` is non-zero (empty: every pixel).
ImageError imageError(const LinearImage& test, const LinearImage& reference, const std::vector<uint8_t>& mask = {});

// SSIM's map (Wang et al. 2004 eq. 13 with the Gaussian-weighted statistics of eq. 14-16) on the
// Rec. 709 luma of the sRGB-encoded values: (width - 10) x (height - 10) values, the first for the
// window centred on pixel (5, 5).
std::vector<double> ssimMap(const LinearImage& test, const LinearImage& reference);

// Each pixel's error: the root mean square over R, G, B of (test - reference), linear.
std::vector<float> pixelErrors(const LinearImage& test, const LinearImage& reference);

// The colour map of the error image: t in [0, 1] (0 no error, 1 the scale or more) to linear RGB.
// Built in OKLab (Ottosson 2020) with lightness rising linearly from dark purple through red and
// orange to pale yellow (the order of matplotlib's inferno), so equal steps of error are equal steps
// of perceived lightness and the map reads in grey too; the chroma is the most that stays in sRGB.
glm::vec3 errorColor(double t);
// The error image: each pixel's error / `scale` through errorColor(), RGBA8 sRGB-encoded.
std::vector<uint8_t> falseColor(const std::vector<float>& errors, double scale);

} // namespace wisp
