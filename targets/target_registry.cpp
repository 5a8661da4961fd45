// The list of targets: each targets/<lang>/ folder contributes the records of its targets.
// A new target is a new folder with its writer and records(), plus one line here.
#include "crtforge/targets.hpp"

#include "targets/glsl/glsl_writer.hpp"
#include "targets/godot/godot_writer.hpp"
#include "targets/hlsl/hlsl_writer.hpp"
#include "targets/spirv/spirv_writer.hpp"
#include "targets/wgsl/wgsl_writer.hpp"

namespace crtforge {

const std::vector<TargetInfo>& all_targets() {
    static const std::vector<TargetInfo> targets = [] {
        std::vector<TargetInfo> out;
        for (auto records : {spirv::records, glsl::records, hlsl::records, godot::records, wgsl::records})
            for (TargetInfo& t : records()) out.push_back(std::move(t));
        return out;
    }();
    return targets;
}

const TargetInfo* find_target(const std::string& name) {
    for (const auto& t : all_targets())
        if (name == t.name) return &t;
    return nullptr;
}

Result<const TargetInfo*> lookup_target(const std::string& name) {
    if (const TargetInfo* t = find_target(name)) return t;
    std::vector<std::string> names;
    for (const auto& t : all_targets()) names.emplace_back(t.name);
    return make_error("unknown target '" + name + "' (targets: " + join_list(names) + ")", {}, 0, "--target");
}

const TargetInfo& target_info(TargetId id) {
    for (const auto& t : all_targets())
        if (t.id == id) return t;
    return all_targets().front();
}

Result<TargetOutput> generate_target(TargetId id, const TargetInput& input) { return target_info(id).generate(input); }

}  // namespace crtforge
