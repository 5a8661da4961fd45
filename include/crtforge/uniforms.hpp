// Filling the std140 uniform buffer of a compiled variant: builtins from the frame being drawn,
// params from the variant (or caller overrides), at the offsets reflected from SPIR-V.
#pragma once

#include <cstdint>
#include <functional>
#include <variant>
#include <map>
#include <string>
#include <vector>

#include "crtforge/exporter.hpp"

namespace crtforge {

// What the host knows about the frame: the sizes and the clock.
struct FrameInfo {
    int output_width = 0, output_height = 0;  // the pass's output (the screen's rectangle for the last pass)
    int source_width = 0, source_height = 0;  // its main input
    double time = 0.0;                        // seconds
    long long frame_count = 0;                // already reduced by the pass's frame_count_mod
    int viewport_width = 0, viewport_height = 0;  // the screen's rectangle in the display (0: the output's)
    static double time_of_frame(int frame, double fps = 60.0) { return frame / fps; }
};

// What one block member holds: floats (float, vec2, vec3, vec4) or an int.
using MemberData = std::variant<std::vector<float>, int32_t>;

// A param value as the member type wants it (a colour fills a vec4 with alpha 1).
Result<MemberData> member_data(const Value& value, const std::string& member_type);

// The std140 bytes of `block` (sized to whole 16-byte registers), each member written at its
// reflected offset with what `resolve` gives for it. Shared by every host that fills a block.
Result<std::vector<uint8_t>> pack_block(const ReflectedBlock& block,
                                        const std::function<Result<MemberData>(const ReflectedMember&)>& resolve);

// The seconds the shader's `time` gets: `seconds` reduced, in double precision, by one period of the
// pass's angular speed S (Variant::angular_speed(), its value from `values`): fmod(seconds * |S|,
// 2 pi) / |S|, in [0, 2 pi / |S|), so time * S is the exact phase modulo 2 pi at any hour. A float32 time would lose the phase
// (a 20 rad/s wave is a radian off by 1e7 s in fp32, and mediump collapses by 1e4 s); with no speed,
// or S = 0, `seconds` as it is.
double shader_time(const Variant& variant, const std::map<std::string, Value>& values, double seconds);

// The bytes of the uniform block (empty when the variant has none). Param values default to the
// variant's; `overrides` replaces some (name -> value), e.g. to drive a modulation.
Result<std::vector<uint8_t>> pack_uniforms(const CompiledVariant& compiled, const FrameInfo& frame,
                                           const std::map<std::string, Value>& overrides = {});

// Every param value the variant's shader sees (baked and uniform), with overrides applied: what a
// reference renderer needs to evaluate the same math.
std::map<std::string, Value> effective_values(const Variant& variant,
                                              const std::map<std::string, Value>& overrides = {});

}  // namespace crtforge
