// The validation pipeline host (see scene_runner.hpp).
#include "validate/scene_runner.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>

#include "crtforge/bounded_memo.hpp"
#include "crtforge/cache.hpp"
#include "crtforge/exporter.hpp"
#include "crtforge/files.hpp"
#include "crtforge/lut_file.hpp"
#include "crtforge/luts.hpp"
#include "crtforge/runtime/gpu_watchdog.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/scene.hpp"

namespace crtforge {

namespace {

constexpr std::pair<PixelFormat, OutputFormat> kFormatPairs[] = {
    {PixelFormat::Rgba8, OutputFormat::Rgba8Unorm},    {PixelFormat::Rgba8Srgb, OutputFormat::Rgba8Srgb},
    {PixelFormat::Rgba16F, OutputFormat::Rgba16Float}, {PixelFormat::Rgba32F, OutputFormat::Rgba32Float},
    {PixelFormat::Rgb10A2, OutputFormat::Rgb10A2Unorm}, {PixelFormat::R16F, OutputFormat::R16Float},
    {PixelFormat::Rg16F, OutputFormat::Rg16Float},
};

SamplerFilter to_filter(Filter f) { return f == Filter::Nearest ? SamplerFilter::Nearest : SamplerFilter::Linear; }

// Whether every value of `image` is a byte / 255 (what an 8-bit PNG decodes to, and the generated
// LUTs hold): such a LUT is RetroArch's R8G8B8A8_UNORM texture, whose mip chain is 8-bit too.
bool holds_8bit_values(const Image& image) {
    return std::all_of(image.rgba.begin(), image.rgba.end(), [](float v) {
        const float scaled = v * 255.0f;
        return v >= 0.0f && v <= 1.0f && std::fabs(scaled - std::round(scaled)) <= 1e-3f;
    });
}

// holds_8bit_values of a shared image, answered once per image: a decoded LUT is shared by every
// preset that names its file (a bezel pack's 4K pictures, scanned value by value, were a cold
// corpus sweep's 2 %). An entry keeps a weak reference, so an address a new image takes again is
// not mistaken for the old one.
bool holds_8bit_values(const SharedImage& image) {
    static std::mutex mutex;
    static std::map<const Image*, std::pair<std::weak_ptr<const Image>, bool>> known;
    const Image* at = image.identity().get();
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (auto it = known.find(at); it != known.end() && it->second.first.lock() == image.identity()) return it->second.second;
    }
    const bool eight_bit = holds_8bit_values(*image);
    std::lock_guard<std::mutex> lock(mutex);
    if (known.size() >= 1024) std::erase_if(known, [](const auto& entry) { return entry.second.first.expired(); });
    if (known.size() < 1024) known[at] = {image.identity(), eight_bit};
    return eight_bit;
}

Result<WrapMode> to_wrap(Wrap w, const std::string& where) {
    switch (w) {
        case Wrap::ClampToEdge: return WrapMode::ClampToEdge;
        case Wrap::Repeat: return WrapMode::Repeat;
        case Wrap::MirroredRepeat: return WrapMode::MirroredRepeat;
        case Wrap::ClampToBorder: return WrapMode::ClampToBorder;  // engines without a border colour refuse it
    }
    return make_error("unknown wrap mode", {}, 0, where);
}

// File LUTs decoded earlier in this process, by the file's bytes: the corpus imports each preset
// into a folder of its own, and hundreds of presets (a bezel pack) share the same large pictures.
// At most 64 Mpx (1 GiB as RGBA float).
BoundedMemo<SharedImage>& decoded_luts() {
    static BoundedMemo<SharedImage> memo(size_t{64} << 20, [](const SharedImage& image) { return image->pixel_count(); });
    return memo;
}

}  // namespace

OutputFormat output_format(PixelFormat format) {
    for (const auto& [pixel, output] : kFormatPairs)
        if (pixel == format) return output;
    return OutputFormat::Rgba16Float;
}

PixelFormat pixel_format(OutputFormat format) {
    for (const auto& [pixel, output] : kFormatPairs)
        if (output == format) return pixel;
    return PixelFormat::Rgba16F;
}

Result<std::map<std::string, SharedImage>> read_file_luts(const Preset& preset) {
    std::map<std::string, SharedImage> out;
    for (const LutSpec& lut : preset.luts) {
        if (!lut.generator.empty()) continue;
        const std::string path = lut_file_path(lut);
        // The key is the file's name ending (the reader goes by it) and bytes; read_image then
        // checks the picture itself, and its error is the one reported.
        auto bytes = read_text_file(path, kMaxLutFileBytes);
        std::string key;
        std::optional<BoundedMemo<SharedImage>::Claim> claim;  // the other worker, starting a preset of the same pack, waits
        if (bytes.ok()) {
            key = Cache::key({"lut", std::filesystem::path(path).extension().string(), bytes.value()});
            claim.emplace(decoded_luts(), key);
            if (auto known = decoded_luts().find(key)) {
                out[lut.name] = *known;
                continue;
            }
        }
        auto image = read_image(path);
        if (!image.ok()) return image.error();
        SharedImage shared(std::move(image.value()));
        if (!key.empty()) decoded_luts().put(key, shared);
        out[lut.name] = std::move(shared);
    }
    return out;
}

Result<SharedImage> scene_lut_image(const LutSpec& lut, const std::map<std::string, SharedImage>& file_luts) {
    if (lut.generator.empty()) {
        auto file = file_luts.find(lut.name);
        if (file == file_luts.end()) return make_error("no image for file LUT '" + lut.name + "'", lut.where.file, lut.where.line);
        return file->second;
    }
    auto generated = generate_lut(lut.generator, lut.params);
    if (!generated.ok()) return generated.error();
    Image image = Image::make(generated.value().width, generated.value().height);
    for (size_t i = 0; i < generated.value().rgba.size(); ++i) image.rgba[i] = static_cast<float>(generated.value().rgba[i] / 255.0);
    return SharedImage(std::move(image));
}

Result<std::vector<Image>> run_scene(const SceneRenderRequest& r, const PassRenderer& render_pass) {
    if (!r.preset || !r.passes || r.passes->size() != r.preset->passes.size() || !r.source)
        return make_error("scene render request without its preset, compiled passes or source");
    if (r.outputs && r.outputs->size() != r.passes->size()) return make_error("scene render request: one output per pass expected");
    const Preset& preset = *r.preset;
    std::map<std::string, SharedImage> luts;
    std::set<std::string> luts_8bit;  // only the mipmapped ones are looked at (unorm8 changes only a chain)
    for (const LutSpec& lut : preset.luts) {
        auto image = scene_lut_image(lut, r.file_luts);
        if (!image.ok()) return image.error();
        const bool chained = std::any_of(preset.passes.begin(), preset.passes.end(), [&](const Pass& p) {
            return std::any_of(p.inputs.begin(), p.inputs.end(), [&](const PassInput& in) {
                return in.mipmap && in.from.kind == TextureSource::Kind::Lut && in.from.name == lut.name;
            });
        });
        if (chained && holds_8bit_values(image.value())) luts_8bit.insert(lut.name);
        luts[lut.name] = std::move(image.value());
    }
    const bool stateful = preset.keeps_state();
    std::vector<int> run = r.frames;
    if (stateful) {
        const int last = r.frames.empty() ? -1 : *std::max_element(r.frames.begin(), r.frames.end());
        run.clear();
        for (int f = 0; f <= last; ++f) run.push_back(f);
    }

    auto index_of = [&](const std::string& alias) {
        for (size_t i = 0; i < preset.passes.size(); ++i)
            if (preset.passes[i].alias == alias) return i;
        return preset.passes.size();
    };
    // An output lives until the last pass of its frame that reads it, or into the next frame where
    // a pass reads it as feedback: a frame of 40 full-size float outputs, kept whole for the next
    // frame too, took a bezel pack's render to gigabytes of fresh memory.
    std::vector<bool> fed_back(preset.passes.size(), false);
    std::vector<std::vector<size_t>> last_read_by(preset.passes.size());  // pass -> the outputs it reads last
    {
        std::vector<size_t> last_reader(preset.passes.size(), preset.passes.size());
        for (size_t k = 0; k < preset.passes.size(); ++k)
            for (const PassInput& in : preset.passes[k].inputs) {
                const size_t i = index_of(in.from.name);
                if (i >= preset.passes.size()) continue;
                if (in.from.kind == TextureSource::Kind::Feedback) fed_back[i] = true;
                if (in.from.kind == TextureSource::Kind::Pass) last_reader[i] = k;
            }
        for (size_t i = 0; i + 1 < preset.passes.size(); ++i)  // the last pass's output is the frame's picture
            if (!fed_back[i]) last_read_by[last_reader[i] < preset.passes.size() ? last_reader[i] : i].push_back(i);
    }

    std::map<int, SharedImage> kept;
    std::vector<SharedImage> previous(preset.passes.size());  // last frame's outputs; empty before the first
    std::deque<SharedImage> history;                          // earlier originals, newest first
    size_t drawn = 0;
    for (int frame : run) {
        auto source_image = r.source(frame);
        if (!source_image.ok()) return source_image.error();
        const SharedImage original(std::move(source_image.value()));
        const PixelSize source{original->width, original->height};
        const PixelRect screen = screen_rect(preset, {r.width, r.height}, source, r.fit);
        const std::vector<PixelSize> sizes = pass_sizes(preset, source, {screen.width, screen.height});
        if (auto s = check_pass_sizes(preset, sizes, {screen.width, screen.height}); !s.ok()) return s.error();
        std::vector<SharedImage> current(preset.passes.size());
        // Every reader shares one image: a LUT or an earlier output is never copied per reader.
        auto resolve = [&](const TextureSource& from) -> SharedImage {
            switch (from.kind) {
                case TextureSource::Kind::Original:
                    if (from.frames_back == 0) return original;
                    if (static_cast<size_t>(from.frames_back) <= history.size()) return history[from.frames_back - 1];
                    return Image::make(source.width, source.height);
                case TextureSource::Kind::Pass: return current[index_of(from.name)];
                case TextureSource::Kind::Feedback: {
                    const size_t i = index_of(from.name);
                    return previous[i]->empty() ? SharedImage(Image::make(sizes[i].width, sizes[i].height)) : previous[i];
                }
                case TextureSource::Kind::Lut: return luts.at(from.name);
            }
            return {};
        };
        // An 8-bit picture (RenderJob::unorm8): an rgba8 pass's output (the last pass's is the
        // display, in r.format) or an 8-bit LUT; the original and float outputs are not.
        auto is_8bit = [&](const TextureSource& from) {
            switch (from.kind) {
                case TextureSource::Kind::Original: return false;
                case TextureSource::Kind::Pass:
                case TextureSource::Kind::Feedback: {
                    const size_t i = index_of(from.name);
                    if (i >= preset.passes.size()) return false;
                    if (i + 1 == preset.passes.size()) return r.format == OutputFormat::Rgba8Unorm;
                    return preset.passes[i].format == PixelFormat::Rgba8;
                }
                case TextureSource::Kind::Lut: return luts_8bit.count(from.name) > 0;
            }
            return false;
        };
        for (size_t i = 0; i < preset.passes.size(); ++i) {
            const Pass& pass = preset.passes[i];
            const bool last = i + 1 == preset.passes.size();
            TargetRenderRequest pr;
            pr.compiled = &(*r.passes)[i];
            pr.target = r.target;
            pr.output = r.outputs ? &(*r.outputs)[i] : nullptr;
            const PassInput& main = pass.inputs.front();
            pr.input = resolve(main.from);
            pr.filter = to_filter(main.filter);
            auto wrap = to_wrap(main.wrap, "pass." + pass.alias + ".wrap");
            if (!wrap.ok()) return wrap.error();
            pr.wrap = wrap.value();
            pr.mipmap = main.mipmap;
            pr.mip_filter = to_filter(main.mip_filter);
            pr.unorm8 = main.mipmap && is_8bit(main.from);
            for (size_t k = 1; k < pass.inputs.size(); ++k) {
                auto w = to_wrap(pass.inputs[k].wrap, "pass." + pass.alias + ".textures." + pass.inputs[k].binding);
                if (!w.ok()) return w.error();
                pr.textures.push_back({pass.inputs[k].binding, resolve(pass.inputs[k].from), to_filter(pass.inputs[k].filter), w.value(),
                                       pass.inputs[k].mipmap, to_filter(pass.inputs[k].mip_filter),
                                       pass.inputs[k].mipmap && is_8bit(pass.inputs[k].from)});
            }
            pr.time = r.start_time + frame / preset.scene.fps;
            const long long count = static_cast<long long>(r.frame_count_base) + frame;
            pr.frame_count = pass.frame_count_mod ? count % pass.frame_count_mod : count;
            pr.overrides = r.overrides;
            pr.keep_on_device = !last;  // the display is the one picture the host reads
            pr.screen_width = screen.width;
            pr.screen_height = screen.height;
            if (last) {  // the display: the screen's rectangle over opaque black
                pr.width = r.width;
                pr.height = r.height;
                if (screen.width != r.width || screen.height != r.height) {
                    pr.viewport = {screen.x, screen.y, screen.width, screen.height};
                    pr.clear_color = {0, 0, 0, 1};
                }
                pr.format = r.format;
            } else {
                pr.width = sizes[i].width;
                pr.height = sizes[i].height;
                pr.format = output_format(pass.format);
            }
            const GpuWorkLabel drawing(fmt::format("preset '{}', pass {} '{}', frame {}", preset.name, i, pass.alias, frame));
            auto image = render_pass(std::move(pr));
            if (!image.ok()) return image.error();
            current[i] = SharedImage(std::move(image.value()));
            for (size_t done : last_read_by[i]) current[done] = SharedImage();
        }
        if (std::find(r.frames.begin(), r.frames.end(), frame) != r.frames.end()) kept[frame] = current.back();
        if (stateful) {
            previous = std::move(current);
            history.push_front(original);
            while (static_cast<int>(history.size()) > preset.history_depth()) history.pop_back();
        }
        if (r.on_frame) r.on_frame(++drawn, run.size());
    }
    std::vector<Image> out;
    for (int frame : r.frames) out.push_back(*kept.at(frame));
    return out;
}

}  // namespace crtforge
