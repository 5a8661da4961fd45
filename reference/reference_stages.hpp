// The reference model of each stage: for every hook a form provides (warp, sample_uv, fetch,
// color, finish, alpha — the generated main()'s fixed order), a function evaluating that form's formula
// as its document writes it, in double precision. Each reads its params by the spec's names.
// The models of one family live in one file (reference_crt_stages.cpp, reference_palette.cpp,
// reference_super_win.cpp); reference_renderer.cpp runs them in the variant's stage order.
#pragma once

#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "crtforge/value.hpp"
#include "reference/reference_math.hpp"
#include "reference/reference_sampler.hpp"

namespace crtforge::reference {

// A fault injected into the oracle by tests (set_reference_fault): proof that validate notices a
// wrong reference, not only a wrong shader. Empty: none.
struct ReferenceFault {
    std::string scale_param;   // this param reads as its value times `factor`
    double factor = 1.0;
    std::string skip_stage;    // this stage is left out of every pass
    double sampler_shift = 0;  // every texture read moves right by this many texels
};
const ReferenceFault& reference_fault();
void install_reference_fault(const ReferenceFault& fault);

// What a model may read that the templates do not provide (a param or texture renamed or removed
// in a user's templates): noted, answered with zero, and turned into one Diagnostic after the
// render — never an exception out of a worker thread. Shared by the render's threads.
class MissingNames {
public:
    void note(const std::string& what) const {
        std::lock_guard<std::mutex> lock(mutex_);
        names_.insert(what);
    }
    std::set<std::string> names() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return names_;
    }

private:
    mutable std::mutex mutex_;
    mutable std::set<std::string> names_;
};

// A pass's param values, read by name once per sample by every stage: an open-addressed table
// hashed on a name's length and three of its characters, so a lookup neither allocates nor walks a
// std::map (which took a quarter of a supersampled reference's time).
class Params {
public:
    Params(const std::map<std::string, Value>& values, const MissingNames& missing);
    double num(std::string_view name) const;  // float or int param
    bool flag(std::string_view name) const;
    Vec3 color(std::string_view name) const;

private:
    const Value* value(std::string_view name) const;
    // The value of that name and type, or nullptr (noted as missing).
    template <typename T>
    const T* find(std::string_view name, const char* type) const;

    static size_t slot_hash(std::string_view name) {
        return name.empty() ? 0 : name.size() * 131u + static_cast<unsigned char>(name[0]) * 31u +
                                      static_cast<unsigned char>(name[name.size() / 2]) * 7u + static_cast<unsigned char>(name.back());
    }
    std::vector<std::pair<std::string_view, const Value*>> slots_;  // power-of-two size, views into the map's keys

    const MissingNames& missing_;
};

// What every stage may read about the fragment being shaded (cf. the CRT-effect document's
// "pixel", "uv" and "centered") and the textures of its pass.
struct Fragment {
    Vec2 screen_uv;   // unwarped 0..1
    Vec2 pixel;       // output pixel coordinate, centres at +0.5
    Vec2 uv;          // after the warp stages
    Vec2 centered;    // uv * 2 - 1
    Vec2 output_size, source_size;
    Vec2 source_scale{1, 1};  // the picture on the screen ([source] fit): crt_source_uv()
    double time = 0;
    long long frame_count = 0;
    const Sampler* source = nullptr;
    std::map<std::string, const Sampler*> textures;
    std::function<Vec2(Vec2)> warp;  // the pass's warp stages, for a point other than this pixel

    const MissingNames* missing = nullptr;
    // The pass's texture of that name; one the pass lacks is noted and reads as transparent black.
    const Sampler& texture(const std::string& name) const;
    Vec2 source_uv(Vec2 screen) const {
        return {(screen.x - 0.5) * source_scale.x + 0.5, (screen.y - 0.5) * source_scale.y + 0.5};
    }
};

// Each hook returns false when it has no model of `form`; a null hook: the stage has none.
struct StageModel {
    const char* stage;
    bool (*warp)(const std::string& form, const Params& p, const Fragment& f, Vec2& uv) = nullptr;
    bool (*sample_uv)(const std::string& form, const Params& p, const Fragment& f, Vec2& uv) = nullptr;
    bool (*fetch)(const std::string& form, const Params& p, const Fragment& f, Vec2 sample_uv, Vec3& color) = nullptr;
    bool (*color)(const std::string& form, const Params& p, const Fragment& f, Vec3& color) = nullptr;
    bool (*finish)(const std::string& form, const Params& p, const Fragment& f, Vec3& color) = nullptr;
    bool (*alpha)(const std::string& form, const Params& p, const Fragment& f, double& alpha) = nullptr;
};

// The model of a stage, or nullptr when the reference has none.
const StageModel* find_stage_model(const std::string& stage);

// One list per file.
std::vector<StageModel> crt_stage_models();
std::vector<StageModel> palette_stage_models();
std::vector<StageModel> super_win_stage_models();

inline Vec3 one_hot(int channel) { return {channel == 0 ? 1.0 : 0.0, channel == 1 ? 1.0 : 0.0, channel == 2 ? 1.0 : 0.0}; }
inline double luma601(Vec3 c) { return 0.299 * c.r + 0.587 * c.g + 0.114 * c.b; }

}  // namespace crtforge::reference
