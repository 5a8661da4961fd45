// What the compile cache keys a GLSL source by: the text that decides the module glslang and
// spirv-opt make of it, without what cannot change that module and without the values of its
// float specialization constants (those are written into the module after, as the optimiser's
// memo does). Presets that share a pass then share its compile: a corpus preset's passes differ
// from another's only in comments naming the preset, a form macro nothing reads, the temporary
// folder in their #line names and the baked parameter values.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "generator/spirv_spec_values.hpp"

namespace crtforge {

struct SourceKey {
    std::string text;                            // the key's text
    std::map<uint32_t, SpecValue> float_values;  // taken out of `text`: each float constant's value by SpecId
};

// Left out of the key, each only where it cannot change the module (a line removed from the key
// stays as an empty line, so __LINE__ keeps its numbers):
//  - the file names of `#line` directives (debug info and messages only; kept where the source
//    reads __FILE__);
//  - a line holding only a `//` comment (not one a trailing backslash continues, nor one that
//    could close a block comment);
//  - the assembler's `#define CRT_FORM_<stage>_<form> 1` lines, where nothing else in the source
//    names CRT_FORM_;
//  - the value of `layout(constant_id = N) const float NAME = VALUE;` (the assembler's spelling,
//    BakedParams::Specialized): a float specialization constant's value is one literal word of
//    its OpSpecConstant, whatever it is.
SourceKey source_key(const std::string& source);

}  // namespace crtforge
