// Comparing a rendered frame with its reference: error figures for reports and a diff picture
// for humans. Only R, G, B take part; alpha is ignored.
#pragma once

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/image.hpp"

namespace crtforge {

struct ImageMetrics {
    double max_abs = 0;  // largest |test - reference| over all RGB samples
    double rmse = 0;     // root mean square of the differences over all RGB samples
    double psnr = 0;     // 20*log10(1/rmse) dB, peak 1.0; capped at 100 (also when rmse is 0)
    double ssim = 1;     // mean SSIM of Rec. 709 luma, see compare_images
    int worst_x = 0, worst_y = 0;  // first pixel (row-major, row 0 = top) where max_abs occurs
};

// Errors: either image empty or malformed, sizes differ (the message names both), or a
// non-finite value in either (the test image's is a Validation error, the reference's an Input
// error): every figure is finite, ready for JSON.
//
// SSIM (Wang et al. 2004): luma Y = 0.2126 R + 0.7152 G + 0.0722 B computed after clamping every
// channel of both images to 0..1 (so HDR highlights cannot dominate the statistic; max_abs, rmse
// and psnr use the unclamped values), an 11x11 Gaussian window with sigma 1.5 at every position
// where it fits inside the image (step 1, no padding), C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 1.
// Images narrower or shorter than 11 pixels use one window covering the whole image, unweighted.
Result<ImageMetrics> compare_images(const Image& test, const Image& reference);

// ImageMetrics::psnr of an RMSE (for figures combined from several comparisons).
double psnr_of(double rmse);

// A picture of where the images differ: per pixel the largest |difference| over RGB, d, mapped
// through black (d = 0) -> blue (tolerance/3) -> magenta (2/3) -> red (d = tolerance) -> yellow
// (2x) -> white (>= 4x tolerance). Alpha is 1. A tolerance <= 0 (or not finite) maps every
// difference > 0 to white; so does a non-finite difference. If the sizes differ the map covers
// both images (the larger width and height) and pixels only one of them has are white. A
// malformed image gives an empty map.
Image diff_heatmap(const Image& test, const Image& reference, double tolerance);

}  // namespace crtforge
