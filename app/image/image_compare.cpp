// app/image/image_compare.cpp: the image metrics (RMSE, relMSE, SSIM over a mask), the hair's mask from a
// frame without hair, and the error image's colour map.
#include "app/image/image_compare.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace wisp {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The window's weights along one axis; the 2D window is their outer product (the Gaussian is
// separable), normalized to sum 1 as the 2D weights w_i of Wang et al. eq. 14 are.
std::array<double, kSsimWindow> gaussianWeights()
{
    std::array<double, kSsimWindow> w{};
    double sum = 0.0;
    for (int i = 0; i < kSsimWindow; ++i) {
        double d = i - kSsimWindow / 2;
        w[size_t(i)] = std::exp(-d * d / (2.0 * kSsimSigma * kSsimSigma));
        sum += w[size_t(i)];
    }
    for (double& v : w)
        v /= sum;
    return w;
}

// The Gaussian-weighted mean of `values` (width x height) over each window inside the frame: the
// separable filter, rows then columns, 'valid' as Wang et al.'s filter2(..., 'valid').
std::vector<double> windowMeans(const std::vector<double>& values, uint32_t width, uint32_t height)
{
    static const std::array<double, kSsimWindow> w = gaussianWeights();
    size_t outW = width - (kSsimWindow - 1), outH = height - (kSsimWindow - 1);
    std::vector<double> rows(outW * height);
    for (size_t y = 0; y < height; ++y)
        for (size_t x = 0; x < outW; ++x) {
            double s = 0.0;
            for (size_t i = 0; i < size_t(kSsimWindow); ++i)
                s += w[i] * values[y * width + x + i];
            rows[y * outW + x] = s;
        }
    std::vector<double> out(outW * outH);
    for (size_t y = 0; y < outH; ++y)
        for (size_t x = 0; x < outW; ++x) {
            double s = 0.0;
            for (size_t i = 0; i < size_t(kSsimWindow); ++i)
                s += w[i] * rows[(y + i) * outW + x];
            out[y * outW + x] = s;
        }
    return out;
}

// Rec. 709 luma of the encoded values: the grey image SSIM was defined on (8-bit, gamma-encoded).
std::vector<double> luma(const LinearImage& image)
{
    std::vector<double> y(image.rgb.size());
    for (size_t i = 0; i < y.size(); ++i) {
        glm::vec3 c = image.rgb[i];
        y[i] = 0.2126 * encodeSrgb(c.r) + 0.7152 * encodeSrgb(c.g) + 0.0722 * encodeSrgb(c.b);
    }
    return y;
}

// OKLab (Ottosson 2020, "A perceptual color space for image processing") to linear sRGB.
glm::dvec3 oklabToLinearSrgb(double L, double a, double b)
{
    double l = L + 0.3963377774 * a + 0.2158037573 * b;
    double m = L - 0.1055613458 * a - 0.0638541728 * b;
    double s = L - 0.0894841775 * a - 1.2914855480 * b;
    l = l * l * l;
    m = m * m * m;
    s = s * s * s;
    return {+4.0767416621 * l - 3.3077115913 * m + 0.2309699292 * s,
            -1.2684380046 * l + 2.6097574011 * m - 0.3413193965 * s,
            -0.0041960863 * l - 0.7034186147 * m + 1.7076147010 * s};
}

} // namespace

double decodeSrgb(double e)
{
    return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

double encodeSrgb(double v)
{
    return v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

LinearImage linearImage(const PngImage& png)
{
    // 65536 levels: one table instead of a pow per channel.
    static const std::vector<float> table = [] {
        std::vector<float> t(65536);
        for (size_t v = 0; v < t.size(); ++v)
            t[v] = float(decodeSrgb(double(v) / 65535.0));
        return t;
    }();
    LinearImage image{.width = png.width, .height = png.height, .rgb = {}};
    image.rgb.resize(size_t(png.width) * png.height);
    for (size_t i = 0; i < image.rgb.size(); ++i)
        image.rgb[i] = {table[png.rgba[4 * i]], table[png.rgba[4 * i + 1]], table[png.rgba[4 * i + 2]]};
    return image;
}

std::vector<uint8_t> hairMask(const PngImage& withHair, const PngImage& withoutHair, double threshold)
{
    // 16-bit values: an 8-bit level is 257 of them.
    double limit = threshold * 257.0;
    std::vector<uint8_t> mask(size_t(withHair.width) * withHair.height);
    for (size_t i = 0; i < mask.size(); ++i)
        for (size_t c = 0; c < 3; ++c)
            if (std::abs(double(withHair.rgba[4 * i + c]) - double(withoutHair.rgba[4 * i + c])) > limit)
                mask[i] = 1;
    return mask;
}

std::vector<double> ssimMap(const LinearImage& test, const LinearImage& reference)
{
    uint32_t width = test.width, height = test.height;
    std::vector<double> x = luma(test), y = luma(reference);
    std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
        xx[i] = x[i] * x[i];
        yy[i] = y[i] * y[i];
        xy[i] = x[i] * y[i];
    }
    std::vector<double> muX = windowMeans(x, width, height), muY = windowMeans(y, width, height);
    std::vector<double> eXX = windowMeans(xx, width, height), eYY = windowMeans(yy, width, height),
                        eXY = windowMeans(xy, width, height);
    const double c1 = (kSsimK1 * 1.0) * (kSsimK1 * 1.0), c2 = (kSsimK2 * 1.0) * (kSsimK2 * 1.0); // L = 1
    std::vector<double> map(muX.size());
    for (size_t i = 0; i < map.size(); ++i) {
        double mx = muX[i], my = muY[i];
        double varX = eXX[i] - mx * mx, varY = eYY[i] - my * my, cov = eXY[i] - mx * my;
        map[i] = ((2.0 * mx * my + c1) * (2.0 * cov + c2)) / ((mx * mx + my * my + c1) * (varX + varY + c2));
    }
    return map;
}

ImageError imageError(const LinearImage& test, const LinearImage& reference, const std::vector<uint8_t>& mask)
{
    auto measured = [&](size_t i) { return mask.empty() || mask[i] != 0; };
    ImageError e;
    double squared = 0.0, relative = 0.0;
    for (size_t i = 0; i < test.rgb.size(); ++i) {
        if (!measured(i))
            continue;
        ++e.pixels;
        for (int c = 0; c < 3; ++c) {
            double a = test.rgb[i][c], b = reference.rgb[i][c];
            squared += (a - b) * (a - b);
            relative += (a - b) * (a - b) / (b * b + kRelMseEpsilon);
        }
    }
    double terms = 3.0 * double(e.pixels);
    e.rmse = e.pixels > 0 ? std::sqrt(squared / terms) : std::numeric_limits<double>::quiet_NaN();
    e.relMse = e.pixels > 0 ? relative / terms : std::numeric_limits<double>::quiet_NaN();

    std::vector<double> map = ssimMap(test, reference);
    size_t mapWidth = test.width - (kSsimWindow - 1), mapHeight = test.height - (kSsimWindow - 1);
    double sum = 0.0;
    for (size_t v = 0; v < mapHeight; ++v)
        for (size_t u = 0; u < mapWidth; ++u)
            if (measured((v + kSsimWindow / 2) * test.width + u + kSsimWindow / 2)) {
                sum += map[v * mapWidth + u];
                ++e.ssimPixels;
            }
    e.ssim = e.ssimPixels > 0 ? sum / double(e.ssimPixels) : std::numeric_limits<double>::quiet_NaN();
    return e;
}

std::vector<float> pixelErrors(const LinearImage& test, const LinearImage& reference)
{
    std::vector<float> errors(test.rgb.size());
    for (size_t i = 0; i < errors.size(); ++i) {
        glm::vec3 d = test.rgb[i] - reference.rgb[i];
        errors[i] = std::sqrt(glm::dot(d, d) / 3.0f);
    }
    return errors;
}

glm::vec3 errorColor(double t)
{
    t = std::clamp(std::isfinite(t) ? t : 1.0, 0.0, 1.0);
    double lightness = 0.2 + 0.75 * t;              // OKLab L: dark to pale, linearly
    double hue = (300.0 + 160.0 * t) * kPi / 180.0; // purple (300 deg), red, orange, yellow (100 deg)
    double wanted = 0.04 + 0.04 * t + 0.14 * std::sin(kPi * t);
    // The most chroma up to `wanted` that stays inside sRGB at this lightness and hue (bisection: at
    // a fixed lightness and hue, the colours inside sRGB are those below one chroma).
    auto inside = [&](double c) {
        glm::dvec3 rgb = oklabToLinearSrgb(lightness, c * std::cos(hue), c * std::sin(hue));
        return rgb.r >= 0.0 && rgb.g >= 0.0 && rgb.b >= 0.0 && rgb.r <= 1.0 && rgb.g <= 1.0 && rgb.b <= 1.0;
    };
    double lo = 0.0, hi = wanted;
    if (!inside(hi))
        for (int i = 0; i < 30; ++i) {
            double mid = 0.5 * (lo + hi);
            (inside(mid) ? lo : hi) = mid;
        }
    else
        lo = hi;
    glm::dvec3 rgb = glm::clamp(oklabToLinearSrgb(lightness, lo * std::cos(hue), lo * std::sin(hue)), 0.0, 1.0);
    return glm::vec3(rgb);
}

std::vector<uint8_t> falseColor(const std::vector<float>& errors, double scale)
{
    // 256 steps of the map, as the 8-bit output can show them.
    static const std::array<std::array<uint8_t, 3>, 256> table = [] {
        std::array<std::array<uint8_t, 3>, 256> t{};
        for (size_t i = 0; i < t.size(); ++i) {
            glm::vec3 c = errorColor(double(i) / 255.0);
            for (int k = 0; k < 3; ++k)
                t[i][size_t(k)] = uint8_t(std::lround(encodeSrgb(c[k]) * 255.0));
        }
        return t;
    }();
    std::vector<uint8_t> rgba(errors.size() * 4);
    for (size_t i = 0; i < errors.size(); ++i) {
        double t = std::clamp(double(errors[i]) / scale, 0.0, 1.0);
        const std::array<uint8_t, 3>& c = table[size_t(std::lround(t * 255.0))];
        rgba[4 * i] = c[0];
        rgba[4 * i + 1] = c[1];
        rgba[4 * i + 2] = c[2];
        rgba[4 * i + 3] = 255;
    }
    return rgba;
}

} // namespace wisp
