// Image comparison metrics and the diff heat-map. All arithmetic is in double so the figures do
// not depend on accumulation order subtleties of float.
#include "crtforge/runtime/image_compare.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace crtforge {
namespace {

constexpr double kPsnrCap = 100.0;
constexpr int kSsimWindow = 11;
constexpr double kSsimSigma = 1.5;
constexpr double kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;

std::string size_text(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

bool all_finite(const Image& image, int& bad_x, int& bad_y) {
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        if ((i % 4) != 3 && !std::isfinite(image.rgba[i])) {
            bad_x = static_cast<int>((i / 4) % static_cast<std::size_t>(image.width));
            bad_y = static_cast<int>((i / 4) / static_cast<std::size_t>(image.width));
            return false;
        }
    }
    return true;
}

// Rec. 709 luma of the image with each channel clamped to 0..1.
std::vector<double> clamped_luma(const Image& image) {
    std::vector<double> luma(image.pixel_count());
    for (std::size_t p = 0; p < luma.size(); ++p) {
        const float* c = image.rgba.data() + p * 4;
        const auto ch = [&](int i) { return std::clamp(static_cast<double>(c[i]), 0.0, 1.0); };
        luma[p] = 0.2126 * ch(0) + 0.7152 * ch(1) + 0.0722 * ch(2);
    }
    return luma;
}

double ssim_of_moments(double mx, double my, double xx, double yy, double xy) {
    const double vx = xx - mx * mx, vy = yy - my * my, cov = xy - mx * my;
    return ((2 * mx * my + kC1) * (2 * cov + kC2)) / ((mx * mx + my * my + kC1) * (vx + vy + kC2));
}

// One window over the whole image, equal weights (for images smaller than the Gaussian window).
double global_ssim(const std::vector<double>& x, const std::vector<double>& y) {
    double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        mx += x[i];
        my += y[i];
        xx += x[i] * x[i];
        yy += y[i] * y[i];
        xy += x[i] * y[i];
    }
    const double n = static_cast<double>(x.size());
    return ssim_of_moments(mx / n, my / n, xx / n, yy / n, xy / n);
}

// Mean SSIM with the 11x11 Gaussian window at every fully-inside position. The window is separable,
// so each of the five moment maps is filtered along rows, then along columns.
double gaussian_ssim(const std::vector<double>& x, const std::vector<double>& y, int w, int h) {
    std::array<double, kSsimWindow> weights;
    double total = 0;
    for (int i = 0; i < kSsimWindow; ++i) {
        const double d = i - kSsimWindow / 2;
        weights[i] = std::exp(-d * d / (2 * kSsimSigma * kSsimSigma));
        total += weights[i];
    }
    for (double& wgt : weights) wgt /= total;

    const int ow = w - kSsimWindow + 1, oh = h - kSsimWindow + 1;
    // Moments per pixel: x, y, x^2, y^2, xy; filtered horizontally into `rows` (ow x h).
    std::vector<std::array<double, 5>> rows(static_cast<std::size_t>(ow) * h);
    for (int r = 0; r < h; ++r) {
        for (int c = 0; c < ow; ++c) {
            std::array<double, 5> acc{};
            for (int k = 0; k < kSsimWindow; ++k) {
                const std::size_t i = static_cast<std::size_t>(r) * w + c + k;
                const double a = x[i], b = y[i], wk = weights[k];
                acc[0] += wk * a;
                acc[1] += wk * b;
                acc[2] += wk * a * a;
                acc[3] += wk * b * b;
                acc[4] += wk * a * b;
            }
            rows[static_cast<std::size_t>(r) * ow + c] = acc;
        }
    }
    double sum = 0;
    for (int r = 0; r < oh; ++r) {
        for (int c = 0; c < ow; ++c) {
            std::array<double, 5> m{};
            for (int k = 0; k < kSsimWindow; ++k) {
                const auto& v = rows[static_cast<std::size_t>(r + k) * ow + c];
                for (int j = 0; j < 5; ++j) m[j] += weights[k] * v[j];
            }
            sum += ssim_of_moments(m[0], m[1], m[2], m[3], m[4]);
        }
    }
    return sum / (static_cast<double>(ow) * oh);
}

// The heat-map ramp: stops at multiples of the tolerance.
std::array<float, 4> heat_colour(double ratio) {
    struct Stop {
        double at;
        double r, g, b;
    };
    static constexpr Stop stops[] = {{0.0, 0, 0, 0},       {1.0 / 3, 0, 0, 1}, {2.0 / 3, 1, 0, 1},
                                     {1.0, 1, 0, 0},       {2.0, 1, 1, 0},     {4.0, 1, 1, 1}};
    if (!(ratio < stops[5].at)) return {1, 1, 1, 1};  // also catches NaN
    for (int i = 1; i < 6; ++i) {
        if (ratio <= stops[i].at) {
            const Stop &a = stops[i - 1], &b = stops[i];
            const double t = (ratio - a.at) / (b.at - a.at);
            return {static_cast<float>(a.r + (b.r - a.r) * t), static_cast<float>(a.g + (b.g - a.g) * t),
                    static_cast<float>(a.b + (b.b - a.b) * t), 1.0f};
        }
    }
    return {1, 1, 1, 1};
}

}  // namespace

double psnr_of(double rmse) { return rmse > 0 ? std::min(kPsnrCap, 20.0 * std::log10(1.0 / rmse)) : kPsnrCap; }

Result<ImageMetrics> compare_images(const Image& test, const Image& reference) {
    if (test.empty() || !test.consistent()) return make_error("test image is empty or malformed (" + size_text(test) + ")");
    if (reference.empty() || !reference.consistent()) {
        return make_error("reference image is empty or malformed (" + size_text(reference) + ")");
    }
    if (test.width != reference.width || test.height != reference.height) {
        return make_error("image sizes differ: test is " + size_text(test) + ", reference is " + size_text(reference));
    }
    int bx = 0, by = 0;
    if (!all_finite(test, bx, by)) {
        return make_validation_error("test image has a non-finite value at (" + std::to_string(bx) + ", " +
                                     std::to_string(by) + ")");
    }
    if (!all_finite(reference, bx, by)) {
        return make_error("reference image has a non-finite value at (" + std::to_string(bx) + ", " +
                          std::to_string(by) + ")");
    }

    ImageMetrics m;
    double squares = 0;
    for (std::size_t p = 0; p < test.pixel_count(); ++p) {
        for (std::size_t c = 0; c < 3; ++c) {
            const double d = std::abs(static_cast<double>(test.rgba[p * 4 + c]) - reference.rgba[p * 4 + c]);
            squares += d * d;
            if (d > m.max_abs) {
                m.max_abs = d;
                m.worst_x = static_cast<int>(p % static_cast<std::size_t>(test.width));
                m.worst_y = static_cast<int>(p / static_cast<std::size_t>(test.width));
            }
        }
    }
    m.rmse = std::sqrt(squares / (3.0 * static_cast<double>(test.pixel_count())));
    m.psnr = psnr_of(m.rmse);

    const std::vector<double> x = clamped_luma(test), y = clamped_luma(reference);
    if (x == y) {
        m.ssim = 1.0;  // exact, whatever rounding the moments would add
    } else if (test.width < kSsimWindow || test.height < kSsimWindow) {
        m.ssim = global_ssim(x, y);
    } else {
        m.ssim = gaussian_ssim(x, y, test.width, test.height);
    }
    return m;
}

Image diff_heatmap(const Image& test, const Image& reference, double tolerance) {
    if (!test.consistent() || !reference.consistent()) return {};
    const int w = std::max(test.width, reference.width), h = std::max(test.height, reference.height);
    Image map = Image::make(w, h, {1, 1, 1, 1});
    const bool usable_tolerance = std::isfinite(tolerance) && tolerance > 0;
    for (int yy = 0; yy < std::min(test.height, reference.height); ++yy) {
        for (int xx = 0; xx < std::min(test.width, reference.width); ++xx) {
            const float *a = test.at(xx, yy), *b = reference.at(xx, yy);
            double d = 0;
            for (int c = 0; c < 3; ++c) {
                const double diff = std::abs(static_cast<double>(a[c]) - b[c]);
                d = std::isnan(diff) ? diff : std::max(d, diff);
                if (std::isnan(d)) break;
            }
            double ratio;
            if (d == 0) ratio = 0;
            else ratio = usable_tolerance ? d / tolerance : HUGE_VAL;
            map.set_pixel(xx, yy, heat_colour(ratio));
        }
    }
    return map;
}

}  // namespace crtforge
