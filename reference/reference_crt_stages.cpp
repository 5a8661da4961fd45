// The single-pass CRT stages, transcribed from the source documents' mathematics (see the spec docs
// in templates/stages/*.toml): curvature, aberration, bloom, tone-map, scanlines, mask, glow,
// vignette. Double precision throughout; literal constants are the documents'.
#include "reference/reference_stages.hpp"

namespace crtforge::reference {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kArticlePi = 3.14159;  // the Atari and Quiet Frame articles' literal

// A filtered curvature form warps as its point form ("atari_filtered" -> "atari").
std::string curvature_base(const std::string& form) {
    const std::string suffix = "_filtered";
    return form.size() > suffix.size() && form.compare(form.size() - suffix.size(), suffix.size(), suffix) == 0
               ? form.substr(0, form.size() - suffix.size()) : form;
}

bool warp_curvature(const std::string& filtered_or_point, const Params& p, const Fragment&, Vec2& uv) {
    const double k = p.num("curvature");
    const std::string form = curvature_base(filtered_or_point);
    if (form == "atari") {  // r measured on the -1..1 square
        Vec2 c = uv * 2.0 - Vec2{1, 1};
        c = c * (1.0 + k * dot(c, c));
        uv = c * 0.5 + Vec2{0.5, 0.5};
    } else if (form == "crt_effect") {  // factor anchored to 1 on the unit circle
        Vec2 c = uv * 2.0 - Vec2{1, 1};
        c = c * (1.0 + (dot(c, c) - 1.0) * k);
        uv = c * 0.5 + Vec2{0.5, 0.5};
    } else if (form == "quiet_frame") {  // r measured on the -0.5..0.5 square
        Vec2 c = uv - Vec2{0.5, 0.5};
        c = c * (1.0 + dot(c, c) * k);
        uv = c + Vec2{0.5, 0.5};
    } else {
        return false;
    }
    return true;
}

bool shadow_cell_uv(const std::string& form, const Params& p, const Fragment& f, Vec2& sample_uv) {
    if (form != "shadow" && form != "shadow_filtered")
        return form == "grille" || form == "atari_grille" || form == "slot" || form == "grille_filtered";
    if (!p.flag("maskQuantize")) return true;
    // "One sample per cell": the mask's cell in screen pixels, its centre warped as the pixel was.
    const double size = p.num("maskSize");
    const Vec2 coord{f.pixel.x / size, f.pixel.y / size};
    const double stagger = fract(std::floor(coord.x) * 0.5);  // odd cell columns shift half a cell
    const Vec2 cell{std::floor(coord.x) + 0.5, std::floor(coord.y + stagger) - stagger + 0.5};
    sample_uv = f.warp({cell.x * size / f.output_size.x, cell.y * size / f.output_size.y});
    return true;
}

bool fetch_aberration(const std::string& form, const Params& p, const Fragment& f, Vec2 sample_uv, Vec3& color) {
    const Sampler& tex = *f.source;
    double offset = 0;
    if (form == "pixels") offset = p.num("aberration") / f.output_size.x;  // pixels -> uv
    else if (form == "uv") offset = p.num("rgbOffset");
    else return false;
    color.r = tex.rgb(sample_uv + Vec2{offset, 0}).r;
    color.b = tex.rgb(sample_uv - Vec2{offset, 0}).b;  // green stays the centred sample
    return true;
}

bool fetch_bloom(const std::string&, const Params& p, const Fragment& f, Vec2 sample_uv, Vec3& color) {
    const Sampler& tex = *f.source;
    const double d = p.num("bloomOffset"), threshold = p.num("bloomThreshold"), strength = p.num("bloomStrength");
    const Vec3 right = tex.rgb(sample_uv + Vec2{d, 0}), below = tex.rgb(sample_uv + Vec2{0, d});
    color.r += std::max((right.r + below.r) * 0.5 - threshold, 0.0) * strength;
    color.g += std::max((right.g + below.g) * 0.5 - threshold, 0.0) * strength;
    color.b += std::max((right.b + below.b) * 0.5 - threshold, 0.0) * strength;
    return true;
}

bool tonemap_saturate(const std::string&, const Params&, const Fragment&, Vec3& c) {
    c = {std::clamp(c.r, 0.0, 1.0), std::clamp(c.g, 0.0, 1.0), std::clamp(c.b, 0.0, 1.0)};
    return true;
}

// The mean of g(y) over the pixel's height [y - 0.5, y + 0.5]: 8-point Gauss-Legendre, exact to
// double precision for the smooth profiles it is used on (a sine of at most half a cycle per pixel).
template <typename G>
double pixel_height_mean(double y, G&& g) {
    static constexpr double kNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static constexpr double kWeights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    double sum = 0;
    for (int i = 0; i < 4; ++i) sum += kWeights[i] * (g(y - 0.5 * kNodes[i]) + g(y + 0.5 * kNodes[i]));
    return 0.5 * sum;  // the weights sum to 2 over [-1, 1]; the pixel is 1 high
}

// The same for a profile that is not smooth everywhere (a sine raised to a power below 1 has a
// cusp where it touches 0): the pixel cut into 8 slices, each integrated as above (64 points).
template <typename G>
double pixel_height_mean_sliced(double y, G&& g) {
    constexpr int kSlices = 8;
    double sum = 0;
    for (int i = 0; i < kSlices; ++i) {
        const double centre = y - 0.5 + (i + 0.5) / kSlices;
        sum += pixel_height_mean(0.0, [&](double t) { return g(centre + t / kSlices); });
    }
    return sum / kSlices;
}

bool apply_scanlines(const std::string& form, const Params& p, const Fragment& f, Vec3& color) {
    if (form == "quiet_frame_filtered") {
        const double intensity = p.num("scanlineIntensity");
        const double k = pixel_height_mean(f.pixel.y, [&](double y) { return 1.0 - intensity * 0.5 * (1.0 - std::sin(y * kArticlePi)); });
        color = color * k;
    } else if (form == "period") {
        // One full bright-to-bright period every scanlinePeriodPx device pixels.
        const double freq = f.output_size.y * 2.0 * kPi / p.num("scanlinePeriodPx");
        color = color * (1.0 - p.num("scanlineStrength") * (0.5 + 0.5 * std::sin(f.uv.y * freq)));
    } else if (form == "period_filtered") {
        // The point form's factor averaged over the pixel's height (numerically here), the
        // coordinate running 1 / outputSize.y a pixel through the pixel's centre.
        const double freq = f.output_size.y * 2.0 * kPi / p.num("scanlinePeriodPx");
        const double strength = p.num("scanlineStrength");
        const double k = pixel_height_mean(f.uv.y * f.output_size.y, [&](double y) {
            return 1.0 - strength * (0.5 + 0.5 * std::sin(y / f.output_size.y * freq));
        });
        color = color * k;
    } else if (form == "atari") {
        // iResolution is the source texture's size.
        double s = std::sin(f.uv.y * f.source_size.y * kArticlePi) * 0.5 + 0.5;
        s = std::pow(s, p.num("scanlineSharpness"));
        color = color * mix(1.0, s, p.num("scanlineIntensity"));
    } else if (form == "crt_effect") {
        double s = std::sin(f.pixel.y * kPi / p.num("scanlineSpacing")) * 0.5 + 0.5;
        s = std::pow(s, p.num("scanlineSharpness"));
        const double bright = 0.299 * color.r + 0.587 * color.g + 0.114 * color.b;
        const double intensity = p.num("scanlineIntensity");
        color = color * mix(1.0 - intensity, 1.0, s * mix(1.0, bright, p.num("scanlineBrightBoost")));
    } else if (form == "crt_effect_filtered") {
        // The point form's factor averaged over the pixel's height (64 points in 8 slices here,
        // not the shader's 4-point rule): linear in the sine term, so the mean of the factor.
        const double spacing = p.num("scanlineSpacing"), sharpness = p.num("scanlineSharpness");
        const double bright = 0.299 * color.r + 0.587 * color.g + 0.114 * color.b;
        const double intensity = p.num("scanlineIntensity"), boost = mix(1.0, bright, p.num("scanlineBrightBoost"));
        const double k = pixel_height_mean_sliced(f.pixel.y, [&](double y) {
            const double s = std::pow(std::sin(y * kPi / spacing) * 0.5 + 0.5, sharpness);
            return mix(1.0 - intensity, 1.0, s * boost);
        });
        color = color * k;
    } else if (form == "quiet_frame") {
        const double s = std::sin(f.pixel.y * kArticlePi);
        color = color * (1.0 - p.num("scanlineIntensity") * 0.5 * (1.0 - s));
    } else {
        return false;
    }
    return true;
}

// The filtered masks' mean multiplier over the pixel's square, per channel. The square is cut at
// every stripe edge (and, for the shadow mask, at every cell-row edge of each column's stagger);
// on each piece the profile 1 - border*(2t-1)^2 is one quadratic, which Simpson's rule integrates
// exactly. `width`: the stripe width in px; `cell`: the shadow cell height in px (0 = grille).
Vec3 filtered_mask_mean(const Params& p, const Fragment& f, double width, double cell) {
    const double border_k = p.num("maskBorder");
    auto profile = [&](double t) { const double u = 2.0 * t - 1.0; return 1.0 - border_k * u * u; };
    // Calls piece(k, lo, hi) for each part [lo, hi] of [a, b] inside period k (k * period onwards).
    auto pieces = [](double a, double b, double period, auto&& piece) {
        for (double k = std::floor(a / period); k * period < b; k += 1.0) {
            const double lo = std::max(a, k * period), hi = std::min(b, (k + 1.0) * period);
            if (hi > lo) piece(k, lo, hi);
        }
    };
    // The integral of the periodic profile over [a, b] in px, the period being `period` px.
    auto integral = [&](double a, double b, double period) {
        double sum = 0;
        pieces(a, b, period, [&](double k, double lo, double hi) {
            const double t0 = lo / period - k, t1 = hi / period - k;
            sum += (hi - lo) / 6.0 * (profile(t0) + 4.0 * profile(0.5 * (t0 + t1)) + profile(t1));
        });
        return sum;
    };
    double sums[3] = {0, 0, 0};
    pieces(f.pixel.x - 0.5, f.pixel.x + 0.5, width, [&](double stripe, double lo, double hi) {
        double rows = 1.0;
        if (cell > 0) {
            const double stagger = fract(std::floor(stripe / 3.0) * 0.5) * cell;  // odd cell columns: half a cell down
            rows = integral(f.pixel.y - 0.5 + stagger, f.pixel.y + 0.5 + stagger, cell);
        }
        sums[static_cast<int>(glsl_mod(stripe, 3.0))] += integral(lo, hi, width) * rows;
    });
    return Vec3{sums[0], sums[1], sums[2]} * 3.0;  // the square's area is 1 px^2; x3 keeps brightness
}

bool apply_mask(const std::string& form, const Params& p, const Fragment& f, Vec3& color) {
    if (form == "shadow_filtered" || form == "grille_filtered") {
        const double size = p.num("maskSize");
        const Vec3 m = form == "grille_filtered" ? filtered_mask_mean(p, f, size, 0.0) : filtered_mask_mean(p, f, size / 3.0, size);
        const double k = p.num("maskIntensity");
        color = color * Vec3{1.0 + (m.r - 1.0) * k, 1.0 + (m.g - 1.0) * k, 1.0 + (m.b - 1.0) * k};
    } else if (form == "shadow") {
        const double size = p.num("maskSize"), border_k = p.num("maskBorder");
        const Vec2 coord = f.pixel * (1.0 / size);
        const Vec2 sub{coord.x * 3.0, coord.y};
        const double stagger = fract(std::floor(coord.x) * 0.5);
        const int channel = static_cast<int>(glsl_mod(std::floor(sub.x), 3.0));
        const Vec2 cell{fract(sub.x) * 2.0 - 1.0, fract(sub.y + stagger) * 2.0 - 1.0};
        const double border = (1.0 - cell.x * cell.x * border_k) * (1.0 - cell.y * cell.y * border_k);
        const Vec3 m = one_hot(channel) * (3.0 * border);
        const double k = p.num("maskIntensity");
        color = color * Vec3{1.0 + (m.r - 1.0) * k, 1.0 + (m.g - 1.0) * k, 1.0 + (m.b - 1.0) * k};
    } else if (form == "grille") {
        const double stripe = fract(f.pixel.x / p.num("maskSize") * 0.333333);
        const int channel = static_cast<int>(std::floor(stripe * 3.0));
        const double edge = std::abs(fract(stripe * 3.0) * 2.0 - 1.0);
        const Vec3 m = one_hot(channel) * (3.0 * (1.0 - edge * edge * p.num("maskBorder")));
        const double k = p.num("maskIntensity");
        color = color * Vec3{1.0 + (m.r - 1.0) * k, 1.0 + (m.g - 1.0) * k, 1.0 + (m.b - 1.0) * k};
    } else if (form == "atari_grille") {
        const int channel = static_cast<int>(glsl_mod(std::floor(f.uv.x * f.source_size.x), 3.0));
        const double dim = p.num("maskDim"), blend = p.num("maskBlend");
        auto tint = [&](int c) { return mix(1.0, channel == c ? 1.0 : dim, blend); };
        color = color * Vec3{tint(0), tint(1), tint(2)};
    } else if (form == "slot") {
        const int column = static_cast<int>(glsl_mod(f.pixel.x, 3.0));
        const double dim = p.num("maskDim");
        color = color * Vec3{column == 0 ? 1.0 : dim, column == 1 ? 1.0 : dim, column == 2 ? 1.0 : dim};
    } else {
        return false;
    }
    return true;
}

bool apply_glow(const std::string&, const Params& p, const Fragment& f, Vec3& color) {
    color = color * (1.0 + p.num("pulseIntensity") * std::cos(f.pixel.x / p.num("pulseWidth") + f.time * p.num("pulseSpeed")));
    return true;
}

bool apply_vignette(const std::string& form, const Params& p, const Fragment& f, Vec3& color) {
    if (form == "atari") {
        const Vec2 v = f.screen_uv * 2.0 - Vec2{1, 1};
        color = color * (1.0 - dot(v, v) * p.num("vignetteStrength"));
    } else if (form == "crt_effect") {
        const double ex = std::max(1.0 - f.centered.x * f.centered.x, 0.0);
        const double ey = std::max(1.0 - f.centered.y * f.centered.y, 0.0);
        color = color * std::pow(ex * ey, p.num("vignetteExponent"));
    } else if (form == "quiet_frame") {
        // smoothstep(0.85, 0.4, r): 1 at the centre, falling to 0 toward the edge.
        const Vec2 d = f.uv - Vec2{0.5, 0.5};
        const double r = std::sqrt(dot(d, d)) * p.num("vignetteScale");
        color = color * (1.0 - smoothstep(0.4, 0.85, r));
    } else {
        return false;
    }
    return true;
}

bool outside_screen(const Fragment& f) { return f.uv.x < 0.0 || f.uv.x > 1.0 || f.uv.y < 0.0 || f.uv.y > 1.0; }

// The filtered forms' share of the pixel on the screen (templates/stages/curvature.glsl): each
// edge a straight line through the warp's Jacobian d uv / d pixel, box-filtered, the two axes'
// shares multiplied. Computed here from the Jacobian's definition, the derivative of the warp:
// dw/dc = s I + 2 k c c^T for w = c * s(c), s = 1 + k r^2 (atari, quiet_frame: r^2 = c.c) or
// 1 + k (r^2 - 1) (crt_effect).
double screen_coverage(const std::string& form, const Params& p, const Fragment& f) {
    const double k = p.num("curvature");
    const std::string base = curvature_base(form);
    const Vec2 c = base == "quiet_frame" ? f.screen_uv - Vec2{0.5, 0.5} : f.screen_uv * 2.0 - Vec2{1, 1};
    const double s = base == "crt_effect" ? 1.0 + (dot(c, c) - 1.0) * k : 1.0 + k * dot(c, c);
    // d uv_out / d uv_in = dw/dc for every form (atari and crt_effect: c = 2 uv - 1 and uv = w / 2 + 1/2).
    const double j00 = s + 2.0 * k * c.x * c.x, j01 = 2.0 * k * c.x * c.y, j11 = s + 2.0 * k * c.y * c.y;
    const double rate_x = std::max(std::hypot(j00 / f.output_size.x, j01 / f.output_size.y), 1e-8);
    const double rate_y = std::max(std::hypot(j01 / f.output_size.x, j11 / f.output_size.y), 1e-8);
    auto share = [](double inside, double rate) { return std::clamp(inside / rate + 0.5, 0.0, 1.0); };
    return share(std::min(f.uv.x, 1.0 - f.uv.x), rate_x) * share(std::min(f.uv.y, 1.0 - f.uv.y), rate_y);
}

bool is_filtered(const std::string& form) { return curvature_base(form) != form; }

// Retro CRT Effects' crt.frag writes vec4(0.0) outside: its preset sets bezelAlpha = 0.
bool bezel_alpha(const std::string& form, const Params& p, const Fragment& f, double& alpha) {
    if (is_filtered(form)) alpha = mix(p.num("bezelAlpha"), alpha, screen_coverage(form, p, f));
    else if (outside_screen(f)) alpha = p.num("bezelAlpha");
    return true;
}

bool apply_bezel(const std::string& form, const Params& p, const Fragment& f, Vec3& color) {
    if (is_filtered(form)) {
        const double t = screen_coverage(form, p, f);
        color = p.color("bezelColor") * (1.0 - t) + color * t;
    }
    else if (outside_screen(f)) color = p.color("bezelColor");
    return true;
}

}  // namespace

std::vector<StageModel> crt_stage_models() {
    return {
        {"curvature", warp_curvature, nullptr, nullptr, nullptr, apply_bezel, bezel_alpha},
        {"aberration", nullptr, nullptr, fetch_aberration, nullptr, nullptr},
        {"bloom", nullptr, nullptr, fetch_bloom, nullptr, nullptr},
        {"tonemap", nullptr, nullptr, nullptr, tonemap_saturate, nullptr},
        {"scanlines", nullptr, nullptr, nullptr, apply_scanlines, nullptr},
        {"mask", nullptr, shadow_cell_uv, nullptr, apply_mask, nullptr},
        {"glow", nullptr, nullptr, nullptr, apply_glow, nullptr},
        {"vignette", nullptr, nullptr, nullptr, apply_vignette, nullptr},
    };
}

}  // namespace crtforge::reference
