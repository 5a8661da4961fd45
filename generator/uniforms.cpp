#include "crtforge/uniforms.hpp"

#include <cmath>
#include <cstring>

namespace crtforge {

std::map<std::string, Value> effective_values(const Variant& variant, const std::map<std::string, Value>& overrides) {
    std::map<std::string, Value> values;
    for (const VariantParam& p : variant.params) values[p.spec->name] = p.value;
    for (const auto& [name, value] : overrides) values[name] = value;
    return values;
}

Result<MemberData> member_data(const Value& value, const std::string& type) {
    if (auto d = std::get_if<double>(&value)) return MemberData{std::vector<float>{static_cast<float>(*d)}};
    if (auto i = std::get_if<int64_t>(&value)) return MemberData{static_cast<int32_t>(*i)};
    // A bool uniform (the uber-shader's) is 4 bytes in std140: 0 or 1.
    if (auto b = std::get_if<bool>(&value)) return MemberData{static_cast<int32_t>(*b ? 1 : 0)};
    if (auto c = std::get_if<Color>(&value)) {
        std::vector<float> rgb{static_cast<float>((*c)[0]), static_cast<float>((*c)[1]), static_cast<float>((*c)[2])};
        if (type == "vec4") rgb.push_back(1.0f);
        return MemberData{std::move(rgb)};
    }
    return make_error("a " + type + " uniform cannot hold this value (enums are never uniforms)");
}

Result<std::vector<uint8_t>> pack_block(const ReflectedBlock& block,
                                        const std::function<Result<MemberData>(const ReflectedMember&)>& resolve) {
    std::vector<uint8_t> bytes((block.size + 15u) / 16u * 16u, 0);
    for (const ReflectedMember& m : block.members) {
        auto data = resolve(m);
        if (!data.ok()) return data.error();
        const size_t size = std::holds_alternative<int32_t>(data.value()) ? sizeof(int32_t)
                                                                          : std::get<std::vector<float>>(data.value()).size() * sizeof(float);
        if (m.offset + size > bytes.size() || size > m.size)
            return make_error("uniform member '" + m.name + "' does not fit its reflected slot");
        if (auto i = std::get_if<int32_t>(&data.value())) std::memcpy(bytes.data() + m.offset, i, sizeof *i);
        else {
            const auto& floats = std::get<std::vector<float>>(data.value());
            std::memcpy(bytes.data() + m.offset, floats.data(), floats.size() * sizeof(float));
        }
    }
    return bytes;
}

double shader_time(const Variant& variant, const std::map<std::string, Value>& values, double seconds) {
    const VariantParam* param = variant.angular_speed();
    if (!param) return seconds;
    auto v = values.find(param->spec->name);
    const double* s = v == values.end() ? nullptr : std::get_if<double>(&v->second);
    if (!s || *s == 0.0 || !std::isfinite(*s)) return seconds;
    // By |S|: the result is never negative (hosts such as the Godot shaders read a negative time as
    // "not set"), and time * S still equals seconds * S modulo 2 pi.
    constexpr double kTau = 6.283185307179586476925;
    const double speed = std::fabs(*s);
    double phase = std::fmod(seconds * speed, kTau);
    if (phase < 0) phase += kTau;
    return phase / speed;
}

Result<std::vector<uint8_t>> pack_uniforms(const CompiledVariant& compiled, const FrameInfo& frame,
                                           const std::map<std::string, Value>& overrides) {
    if (compiled.reflection.uniform_blocks.empty()) return std::vector<uint8_t>{};
    const auto values = effective_values(compiled.variant, overrides);
    return pack_block(compiled.reflection.uniform_blocks.front(), [&](const ReflectedMember& m) -> Result<MemberData> {
        if (m.name == "outputSize")
            return MemberData{std::vector<float>{static_cast<float>(frame.output_width), static_cast<float>(frame.output_height)}};
        if (m.name == "sourceSize")
            return MemberData{std::vector<float>{static_cast<float>(frame.source_width), static_cast<float>(frame.source_height)}};
        if (m.name == "viewportSize")
            return MemberData{std::vector<float>{static_cast<float>(frame.viewport_width ? frame.viewport_width : frame.output_width),
                                                 static_cast<float>(frame.viewport_height ? frame.viewport_height : frame.output_height)}};
        if (m.name == "time") return MemberData{std::vector<float>{static_cast<float>(shader_time(compiled.variant, values, frame.time))}};
        // An int: a 32-bit counter wraps after ~2.3 years of 60 Hz frames; hosts reduce it by the pass's modulo first.
        if (m.name == "frameCount") return MemberData{static_cast<int32_t>(frame.frame_count & 0x7fffffff)};
        auto v = values.find(m.name);
        if (v == values.end()) return make_error("no value for uniform '" + m.name + "'");
        return member_data(v->second, m.type);
    });
}

}  // namespace crtforge
