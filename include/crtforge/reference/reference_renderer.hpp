// The oracle for goldens: a CPU renderer in double precision that evaluates every stage from its
// documented formula (not from the GLSL), with Vulkan's sampling rules (texel centres at +0.5,
// clamp-to-edge, nearest or bilinear). It shares no code with the drivers under test.
#pragma once

#include <map>
#include <string>

#include "crtforge/runtime/image.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/variant.hpp"

namespace crtforge {

struct ReferenceJob {
    const Variant* variant = nullptr;      // stages, forms and values
    std::map<std::string, Value> overrides;  // param values replacing the variant's (e.g. uniforms)
    Image input;
    SamplerFilter filter = SamplerFilter::Linear;
    int width = 0, height = 0;
    double time = 0.0;                     // seconds
};

// Renders the variant's math. A stage or form the reference has no model for is an error, never
// a silently wrong image.
Result<Image> render_reference(const ReferenceJob& job);

}  // namespace crtforge
