// A pass as a manifest-only host knows it (see crtforge/validate/manifest_host.hpp).
#include "crtforge/validate/manifest_host.hpp"

#include <nlohmann/json.hpp>

#include "generator/manifest.hpp"

namespace crtforge {

namespace {

using json = nlohmann::ordered_json;

// A member's component type and shape from its GLSL spelling, as a host parses it.
bool parse_member_type(const std::string& type, ReflectedMember& m) {
    using Scalar = ReflectedMember::Scalar;
    std::string rest = type;
    m.scalar = Scalar::Float;
    if (rest == "float" || rest == "int" || rest == "uint" || rest == "bool") {
        m.scalar = rest == "float" ? Scalar::Float : rest == "int" ? Scalar::Int : rest == "uint" ? Scalar::Uint : Scalar::Bool;
        m.components = m.columns = 1;
        return true;
    }
    if (rest.size() == 5 && rest[0] != 'v' && rest.compare(1, 3, "vec") == 0) {  // ivecN, uvecN, bvecN
        m.scalar = rest[0] == 'i' ? Scalar::Int : rest[0] == 'u' ? Scalar::Uint : rest[0] == 'b' ? Scalar::Bool : Scalar::Other;
        rest = rest.substr(1);
    }
    if (rest.size() == 4 && rest.compare(0, 3, "vec") == 0 && rest[3] >= '2' && rest[3] <= '4') {
        m.components = static_cast<uint32_t>(rest[3] - '0');
        m.columns = 1;
        return m.scalar != Scalar::Other;
    }
    if (rest.size() == 4 && rest.compare(0, 3, "mat") == 0 && rest[3] >= '2' && rest[3] <= '4') {
        m.components = m.columns = static_cast<uint32_t>(rest[3] - '0');
        return true;
    }
    return false;
}

template <typename T>
bool read(const json& j, const char* key, T& out) {
    if (!j.is_object() || !j.contains(key)) return false;
    try {
        out = j.at(key).get<T>();
        return true;
    } catch (const json::exception&) {
        return false;
    }
}

}  // namespace

Result<std::vector<CompiledVariant>> as_manifest_host(const Preset& preset, const std::vector<CompiledVariant>& passes) {
    const json manifest = detail::preset_manifest(preset, passes);
    const json& list = manifest.contains("passes") ? manifest.at("passes") : json();
    if (!list.is_array() || list.size() != passes.size())
        return make_validation_error("manifest.json of preset '" + preset.name + "': its passes do not match the preset's");
    std::vector<CompiledVariant> out = passes;
    for (size_t i = 0; i < passes.size(); ++i) {
        const json& entry = list.at(i);
        const std::string where = "manifest.json, preset '" + preset.name + "' pass " + std::to_string(i);
        Reflection& r = out[i].reflection;
        r.uniform_blocks.clear();
        r.textures.clear();
        const json block = entry.contains("uniformBlock") ? entry.at("uniformBlock") : json();
        if (!block.is_null()) {
            ReflectedBlock b;
            if (!read(block, "name", b.name) || !read(block, "set", b.set) || !read(block, "binding", b.binding) || !read(block, "size", b.size) ||
                !block.contains("members") || !block.at("members").is_array())
                return make_validation_error(where + ": its uniformBlock lacks name, set, binding, size or members");
            for (const json& mj : block.at("members")) {
                ReflectedMember m;
                if (!read(mj, "name", m.name) || !read(mj, "type", m.type) || !read(mj, "offset", m.offset) || !read(mj, "size", m.size) ||
                    !parse_member_type(m.type, m))
                    return make_validation_error(where + ": a uniform member lacks its name, a known type, offset or size");
                if (m.offset + m.size > b.size)
                    return make_validation_error(where + ": member '" + m.name + "' ends past the block's size " + std::to_string(b.size));
                b.members.push_back(std::move(m));
            }
            r.uniform_blocks.push_back(std::move(b));
        }
        const json textures = entry.contains("textures") ? entry.at("textures") : json::array();
        if (!textures.is_array()) return make_validation_error(where + ": its textures are not a list");
        for (const json& tj : textures) {
            ReflectedTexture t;
            if (!read(tj, "name", t.name) || !read(tj, "set", t.set) || !read(tj, "binding", t.binding))
                return make_validation_error(where + ": a texture lacks its name, set or binding");
            r.textures.push_back(std::move(t));
        }
    }
    return out;
}

}  // namespace crtforge
