// export_preset PRESET TARGET OUT_DIR: exports one preset for one target with an installed crtforge,
// the way an engine's build step would embed it.
#include <cstdio>

#include <crtforge/crtforge.hpp>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: export_preset PRESET TARGET OUT_DIR\n");
        return 2;
    }
    // The installed copy's templates, wherever the prefix has been moved to since.
    crtforge::set_install_prefix(CRTFORGE_INSTALL_PREFIX);
    auto library = crtforge::TemplateLibrary::load(crtforge::data_path("templates"));
    if (!library.ok()) {
        std::fprintf(stderr, "%s\n", library.error().str().c_str());
        return 2;
    }
    auto target = crtforge::lookup_target(argv[2]);
    if (!target.ok()) {
        std::fprintf(stderr, "%s\n", target.error().str().c_str());
        return 2;
    }
    crtforge::ExportRequest request;
    request.presets = {argv[1]};
    request.targets = {target.value()->id};
    auto exported = crtforge::run_export(*library.value(), request, crtforge::Cache());
    if (!exported.ok()) {
        std::fprintf(stderr, "%s\n", exported.error().str().c_str());
        return exported.error().kind == crtforge::ErrorKind::Validation ? 1 : 2;
    }
    if (auto written = crtforge::write_files(argv[3], exported.value().files); !written.ok()) {
        std::fprintf(stderr, "%s\n", written.error().str().c_str());
        return 2;
    }
    std::printf("%zu files for preset %s, target %s in %s\n", exported.value().files.size(), argv[1], argv[2], argv[3]);
    return 0;
}
