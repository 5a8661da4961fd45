#include "fuzz/fuzz_support.hpp"

#include <cstdio>
#include <cstdlib>

namespace crtforge::fuzz {

namespace {

[[noreturn]] void give_up(const std::string& what, const Diagnostic& error) {
    std::fprintf(stderr, "crtforge fuzz: %s: %s\n", what.c_str(), error.str().c_str());
    std::abort();
}

}  // namespace

const TemplateLibrary& shipped_library() {
    static const std::shared_ptr<TemplateLibrary> library = [] {
        auto loaded = TemplateLibrary::load(TemplateLibrary::default_dir());
        if (!loaded.ok()) give_up("cannot load the shipped templates", loaded.error());
        return loaded.value();
    }();
    return *library;
}

const SpirvBinary& fullscreen_vertex() {
    static const SpirvBinary vertex = [] {
        CompileOptions options;
        options.stage = ShaderStage::Vertex;
        options.source_name = shipped_library().vertex_path();
        auto compiled = compile_to_spirv(shipped_library().vertex_source(), options);
        if (!compiled.ok()) give_up("cannot compile the full-screen vertex shader", compiled.error());
        return compiled.value();
    }();
    return vertex;
}

}  // namespace crtforge::fuzz
