#include "tests/test_support.hpp"

#include <cerrno>
#include <cstdio>
#include <fstream>
#include <random>

#include <catch2/catch.hpp>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "crtforge/files.hpp"
#include "crtforge/reference/reference_renderer.hpp"

namespace fs = std::filesystem;

namespace crtforge::test {

std::string golden_dir() { return CRTFORGE_SOURCE_DIR "/golden"; }

std::string slurp(const std::filesystem::path& path) {
    auto text = read_text_file(path.string());
    return text.ok() ? std::move(text).value() : std::string();
}

void write_file(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

std::string shipped_template_dir() { return CRTFORGE_SOURCE_DIR "/templates"; }

namespace {

std::shared_ptr<TemplateLibrary> load_shipped() {
    auto loaded = TemplateLibrary::load(shipped_template_dir());
    if (!loaded.ok()) FAIL("shipped templates do not load: " << loaded.error().str());
    for (const auto& [name, error] : loaded.value()->broken_presets()) FAIL("shipped preset " << name << " does not load: " << error.str());
    return loaded.value();
}

}  // namespace

const TemplateLibrary& shipped_library() {
    static std::shared_ptr<TemplateLibrary> lib = load_shipped();
    return *lib;
}

const TemplateLibrary& validation_library() {
    static std::shared_ptr<TemplateLibrary> lib = [] {
        auto loaded = load_shipped();
        if (auto s = add_golden_presets(*loaded, std::string(CRTFORGE_SOURCE_DIR) + "/golden"); !s.ok())
            FAIL("golden/stages does not load: " << s.error().str());
        return loaded;
    }();
    return *lib;
}

TempDir::TempDir() {
    std::random_device rd;
    path_ = (fs::temp_directory_path() / ("crtforge-test-" + std::to_string(rd()) + std::to_string(rd()))).string();
    fs::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
}

ScratchTemplates::ScratchTemplates() : dir_(tmp_ / "templates") {
    fs::copy(shipped_template_dir(), dir_, fs::copy_options::recursive);
}

Result<std::shared_ptr<TemplateLibrary>> ScratchTemplates::load() const {
    auto lib = TemplateLibrary::load(dir_);
    if (lib.ok() && !lib.value()->broken_presets().empty()) return lib.value()->broken_presets().begin()->second;
    return lib;
}

void ScratchTemplates::write(const std::string& rel, const std::string& text) const {
    std::ofstream(dir_ + "/" + rel, std::ios::binary | std::ios::trunc) << text;
}

void ScratchTemplates::remove(const std::string& rel) const { fs::remove(dir_ + "/" + rel); }

std::string ScratchTemplates::read(const std::string& rel) const { return slurp(dir_ + "/" + rel); }

Result<Preset> resolve_preset_texts(const std::vector<std::pair<std::string, std::string>>& files, const std::string& name) {
    const TemplateLibrary& lib = shipped_library();
    std::vector<PresetFile> parsed;
    for (const auto& [path, text] : files) {
        auto f = parse_preset_file(text, path, &lib);
        if (!f.ok()) return f.error();
        parsed.push_back(f.value());
    }
    return lib.resolve(parsed, name);
}

CommandResult run_command(const std::string& command) {
    TempDir tmp;
    const std::string out = tmp / "out.txt", err = tmp / "err.txt";
    const std::string cmd = "(" + command + ") >'" + out + "' 2>'" + err + "' </dev/null";
    // fork + exec rather than std::system: wait4 gives this command's own resource use (its peak
    // memory), where getrusage(RUSAGE_CHILDREN) would give the largest of every child so far.
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    CommandResult r;
    int status = 0;
    rusage usage{};
    if (pid < 0) return r;
    pid_t waited = -1;
    do waited = ::wait4(pid, &status, 0, &usage);  // a signal to the test process must not orphan the command
    while (waited < 0 && errno == EINTR);
    if (waited != pid) return r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.peak_rss_kib = usage.ru_maxrss;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
}

CommandResult run_crtforge(const std::string& args, const std::string& env) {
    return run_command(env + (env.empty() ? "" : " ") + std::string("'") + CRTFORGE_BINARY + "' " + args);
}

size_t count_of(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

SpirvBinary compile_glsl_or_fail(const std::string& source, ShaderStage stage, bool optimize) {
    CompileOptions options;
    options.stage = stage;
    options.optimize = optimize;
    options.source_name = "<test shader>";
    auto spirv = compile_to_spirv(source, options);
    if (!spirv.ok()) FAIL(spirv.error().str());
    return std::move(spirv.value());
}

CompiledVariant compile_or_fail(const TemplateLibrary& lib, const std::string& preset_name,
                                const VariantOptions& options) {
    const Preset* preset = lib.find_preset(preset_name);
    REQUIRE(preset != nullptr);
    auto compiled = compile_variant(lib, *preset, options, Cache());
    if (!compiled.ok()) FAIL(preset_name << ": " << compiled.error().str());
    return std::move(compiled.value());
}

std::vector<Image> render_scene_or_fail(TargetRenderer& renderer, const Preset& preset, const std::vector<CompiledVariant>& passes,
                                        const SceneShot& shot, TargetId target, const std::vector<TargetOutput>* outputs) {
    SceneRenderRequest r;
    r.preset = &preset;
    r.passes = &passes;
    r.target = target;
    r.outputs = outputs;
    r.source = shot.source;
    r.width = shot.width;
    r.height = shot.height;
    r.frames = shot.frames;
    auto images = renderer.render_scene(r);
    if (!images.ok()) FAIL(preset.name << " through " << target_info(target).name << ": " << images.error().str());
    return std::move(images.value());
}

std::vector<Image> reference_scene_or_fail(const TemplateLibrary& lib, const Preset& preset, const SceneShot& shot, int supersample) {
    ReferenceSceneJob job;
    job.library = &lib;
    job.preset = &preset;
    job.source = shot.source;
    job.width = shot.width;
    job.height = shot.height;
    job.frames = shot.frames;
    job.supersample = supersample;
    auto images = render_reference_scene(job);
    if (!images.ok()) FAIL(preset.name << " by the reference: " << images.error().str());
    return std::move(images.value());
}

std::vector<GoldenEntry> golden_plan_or_fail(const TemplateLibrary& lib, const std::string& golden_dir) {
    auto plan = golden_plan(lib, golden_dir);
    if (!plan.ok()) FAIL(plan.error().str());
    return plan.value();
}

Image require_image(Result<Image> image, int width, int height) {
    INFO((image.ok() ? std::string() : image.error().str()));
    REQUIRE(image.ok());
    REQUIRE(image.value().width == width);
    REQUIRE(image.value().height == height);
    REQUIRE(image.value().consistent());
    return std::move(image).value();
}

Image draw_fragment(RenderEngine& engine, const SpirvBinary& fragment, bool optimize, int width, int height) {
    auto job = frame_job<RenderJob>(Image{}, width, height, OutputFormat::Rgba16Float, SamplerFilter::Nearest);
    job.vertex_spirv = compile_glsl_or_fail(shipped_library().vertex_source(), ShaderStage::Vertex, optimize);
    job.fragment_spirv = fragment;
    return require_image(engine.render(job), width, height);
}

void check_same_picture(const Image& drawn, const Image& expected, double margin) {
    REQUIRE(drawn.width == expected.width);
    REQUIRE(drawn.height == expected.height);
    double sum = 0.0;
    for (int y = 0; y < expected.height; ++y)
        for (int x = 0; x < expected.width; ++x)
            for (int ch = 0; ch < 3; ++ch) {
                INFO(x << "," << y << " channel " << ch);
                CHECK(drawn.pixel(x, y)[ch] == Approx(expected.pixel(x, y)[ch]).margin(margin));
                sum += expected.pixel(x, y)[ch];
            }
    CHECK(sum > 0.1 * expected.width * expected.height);
}

const OutputFile& file_with_role(const TargetOutput& out, const std::string& role) {
    for (const auto& f : out.files)
        if (f.manifest_role() == role) return f;
    FAIL("no file with role " << role);
    throw;  // unreachable
}

std::string slang_program(const SlangProgram& p) {
    auto varyings = [&](const std::string& io) {
        std::string out = p.varyings;
        for (size_t at = out.find("{io}"); at != std::string::npos; at = out.find("{io}", at + io.size())) out.replace(at, 4, io);
        return out;
    };
    return "#version 450\n"
           "layout(push_constant) uniform Push { vec4 SourceSize; " + p.push + "} params;\n"
           "layout(std140, set = 0, binding = 0) uniform UBO { mat4 MVP; } global;\n" + p.head +
           "#pragma stage vertex\n"
           "layout(location = 0) in vec4 Position;\n"
           "layout(location = 1) in vec2 TexCoord;\n"
           "layout(location = 0) out vec2 vTexCoord;\n" + varyings("out") +
           "void main() { gl_Position = global.MVP * Position; vTexCoord = TexCoord;\n" + p.vertex_body + "}\n"
           "#pragma stage fragment\n"
           "layout(location = 0) in vec2 vTexCoord;\n" + varyings("in") +
           "layout(location = 0) out vec4 FragColor;\n" + p.fragment;
}

}  // namespace crtforge::test
