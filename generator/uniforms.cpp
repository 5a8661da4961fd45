#include "crtforge/uniforms.hpp"

#include <cstring>

namespace crtforge {

std::map<std::string, Value> effective_values(const Variant& variant, const std::map<std::string, Value>& overrides) {
    std::map<std::string, Value> values;
    for (const VariantParam& p : variant.params) values[p.spec->name] = p.value;
    for (const auto& [name, value] : overrides) values[name] = value;
    return values;
}

namespace {

void put_floats(std::vector<uint8_t>& bytes, uint32_t offset, std::initializer_list<float> floats) {
    for (float f : floats) {
        std::memcpy(bytes.data() + offset, &f, sizeof f);
        offset += sizeof f;
    }
}

}  // namespace

Result<std::vector<uint8_t>> pack_uniforms(const CompiledVariant& compiled, const FrameInfo& frame,
                                           const std::map<std::string, Value>& overrides) {
    std::vector<uint8_t> bytes;
    if (compiled.reflection.uniform_blocks.empty()) return bytes;
    const ReflectedBlock& block = compiled.reflection.uniform_blocks.front();
    bytes.assign((block.size + 15u) / 16u * 16u, 0);
    const auto values = effective_values(compiled.variant, overrides);
    for (const ReflectedMember& m : block.members) {
        if (m.offset + m.size > bytes.size()) return make_error("uniform member '" + m.name + "' lies outside the block");
        if (m.name == "outputSize") {
            put_floats(bytes, m.offset, {static_cast<float>(frame.output_width), static_cast<float>(frame.output_height)});
        } else if (m.name == "sourceSize") {
            put_floats(bytes, m.offset, {static_cast<float>(frame.source_width), static_cast<float>(frame.source_height)});
        } else if (m.name == "time") {
            put_floats(bytes, m.offset, {static_cast<float>(frame.time)});
        } else {
            auto v = values.find(m.name);
            if (v == values.end()) return make_error("no value for uniform '" + m.name + "'");
            if (auto d = std::get_if<double>(&v->second)) {
                put_floats(bytes, m.offset, {static_cast<float>(*d)});
            } else if (auto c = std::get_if<Color>(&v->second)) {
                put_floats(bytes, m.offset, {static_cast<float>((*c)[0]), static_cast<float>((*c)[1]), static_cast<float>((*c)[2])});
            } else if (auto i = std::get_if<int64_t>(&v->second)) {
                const int32_t value = static_cast<int32_t>(*i);
                std::memcpy(bytes.data() + m.offset, &value, sizeof value);
            } else {
                return make_error("uniform '" + m.name + "' has a type that cannot live in a uniform block");
            }
        }
    }
    return bytes;
}

}  // namespace crtforge
