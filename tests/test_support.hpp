// Shared test fixtures: the shipped template library, scratch copies of it that a test may break on
// purpose, temporary directories, and running the crtforge binary.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "crtforge/crtforge.hpp"
#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/validate/golden.hpp"
#include "crtforge/validate/target_render.hpp"

namespace crtforge::test {

// The shipped goldens: golden/ of the source tree.
std::string golden_dir();

// A file's bytes ("" when unreadable: the checks then fail on the content).
std::string slurp(const std::filesystem::path& path);

// Writes `text` to `path`, making its folders.
void write_file(const std::filesystem::path& path, const std::string& text);

// The shipped templates, loaded once per test binary.
const TemplateLibrary& shipped_library();
// The shipped templates plus golden/stages/ (the stage-isolation presets), as `crtforge golden`
// and `crtforge validate` load them: what golden/plan.toml plans over.
const TemplateLibrary& validation_library();
std::string shipped_template_dir();

// A fresh, empty directory removed at scope exit.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::string& path() const { return path_; }
    std::string operator/(const std::string& rel) const { return path_ + "/" + rel; }

private:
    std::string path_;
};

// A copy of the shipped templates in a TempDir; tests overwrite files in it to provoke errors.
class ScratchTemplates {
public:
    ScratchTemplates();
    const std::string& dir() const { return dir_; }
    void write(const std::string& rel, const std::string& text) const;  // relative to templates/
    void remove(const std::string& rel) const;
    std::string read(const std::string& rel) const;
    // The library as a command over every preset sees it: a broken preset is the load's error
    // (the first by name). TemplateLibrary::load(dir()) keeps broken presets apart instead.
    Result<std::shared_ptr<TemplateLibrary>> load() const;

private:
    TempDir tmp_;
    std::string dir_;
};

// Preset files (path, text) parsed and resolved against the shipped stages: the preset `name`.
Result<Preset> resolve_preset_texts(const std::vector<std::pair<std::string, std::string>>& files, const std::string& name);

struct CommandResult {
    int exit_code = -1;
    std::string out, err;
    long peak_rss_kib = 0;  // the command's peak resident memory (the largest of its processes)
};

// Runs a shell command line, capturing both streams.
CommandResult run_command(const std::string& command);

// Runs build/crtforge with the given arguments (a shell-quoted string), capturing both streams.
// `env` is prepended as environment assignments (e.g. "VK_ICD_FILENAMES=/nonexistent.json").
CommandResult run_crtforge(const std::string& args, const std::string& env = {});

// The fields every engine's job shares (RenderJob, GlRenderJob, DawnJob), filled in.
template <typename Job>
Job frame_job(Image input, int width, int height, OutputFormat format, SamplerFilter filter) {
    Job job;
    job.input = std::move(input);
    job.filter = filter;
    job.width = width;
    job.height = height;
    job.format = format;
    return job;
}

// The image of a render that must succeed (the test stops otherwise, quoting the error), checked
// to be width x height and consistent.
Image require_image(Result<Image> image, int width, int height);

// `fragment` drawn by `engine` over a width x height rgba16f target, behind the shipped vertex
// stage compiled alike (`optimize`): how a SPIR-V rewrite is compared with glslang's own module.
Image draw_fragment(RenderEngine& engine, const SpirvBinary& fragment, bool optimize, int width, int height);
// Every rgb value of `drawn` within `margin` of `expected`'s, and `expected` not near black (so the
// comparison compared a picture).
void check_same_picture(const Image& drawn, const Image& expected, double margin);

// The golden plan of a golden directory; fails the test on any error.
std::vector<GoldenEntry> golden_plan_or_fail(const TemplateLibrary& lib, const std::string& golden_dir);

// The emitted file with this manifest role ("shader", "screenShader", ...); fails the test if none.
const OutputFile& file_with_role(const TargetOutput& out, const std::string& role);

// How often `what` occurs in `text` (not overlapping).
size_t count_of(const std::string& text, const std::string& what);

// GLSL 450 through glslang (and, with `optimize`, spirv-opt and crtforge's SPIR-V rewrites);
// fails the test on any error.
SpirvBinary compile_glsl_or_fail(const std::string& source, ShaderStage stage, bool optimize = true);

// Compiles and emits one preset through every target; fails the test on any error.
CompiledVariant compile_or_fail(const TemplateLibrary& lib, const std::string& preset,
                                const VariantOptions& options = {});

// What a scene render of a test draws: the picture at each frame, the display and the frames kept.
struct SceneShot {
    std::function<Result<Image>(int frame)> source;
    int width = 0, height = 0;
    std::vector<int> frames;
};

// The display images of a scene through a target's consumer (`outputs`: the target's files per
// pass; none for spirv, which renders the compiled modules); fails the test on any error.
std::vector<Image> render_scene_or_fail(TargetRenderer& renderer, const Preset& preset, const std::vector<CompiledVariant>& passes,
                                        const SceneShot& shot, TargetId target = TargetId::Spirv,
                                        const std::vector<TargetOutput>* outputs = nullptr);

// The same from the fp64 reference, `supersample` x `supersample` samples per pixel.
std::vector<Image> reference_scene_or_fail(const TemplateLibrary& lib, const Preset& preset, const SceneShot& shot, int supersample = 1);

// A RetroArch .slang program for the import's tests: RetroArch's quad drawn with TexCoord handed
// on as vTexCoord (location 0), FragColor out, and what each test adds.
struct SlangProgram {
    std::string push;         // push-constant members after `vec4 SourceSize;`
    std::string head;         // lines before the stages (`#pragma parameter ...`)
    std::string varyings;     // more stage I/O, "{io}" written `out` in the vertex stage and `in` after
    std::string vertex_body;  // statements after `vTexCoord = TexCoord;`
    std::string fragment;     // the fragment stage's declarations and main()
};
std::string slang_program(const SlangProgram& program);

}  // namespace crtforge::test
