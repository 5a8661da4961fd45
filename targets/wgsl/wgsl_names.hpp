// WGSL spelling: identifiers that are legal and unique, and literals that round-trip exactly.
#pragma once

#include <cstdint>
#include <set>
#include <string>

namespace crtforge::wgsl {

// `wanted` made into a legal WGSL identifier (invalid characters -> '_', keywords and reserved
// words get a trailing '_', no leading "__"), then made unique within `taken`, which it joins.
std::string unique_identifier(const std::string& wanted, std::set<std::string>& taken);

// f32 bits as the shortest decimal that reads back as the same f32 ("0.3", "1e-05", "-2.0").
// Infinities and NaNs, which WGSL literals cannot spell, come out as bitcast<f32>(0x...u).
std::string f32_literal(uint32_t bits);
std::string i32_literal(int32_t value);
std::string u32_literal(uint32_t value);

}  // namespace crtforge::wgsl
