// WGSL spelling: identifiers that are legal and unique, and literals that round-trip exactly.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>

namespace crtforge::wgsl {

// The identifiers taken in one scope. Names are only ever added, so every "base_k" below a base's
// `next` suffix is taken and unique_identifier() starts its probe there: linear in the names, where
// probing from 1 was quadratic (an uber-shader's thousands of inlined `color`s took 20 s).
class NameScope {
public:
    bool count(const std::string& name) const { return taken_.count(name) != 0; }
    void insert(const std::string& name) { taken_.insert(name); }
    void insert(const NameScope& other) { taken_.insert(other.taken_.begin(), other.taken_.end()); }

private:
    friend std::string unique_identifier(const std::string& wanted, NameScope& scope);
    std::set<std::string> taken_;
    std::map<std::string, int> next_;
};

// `wanted` made into a legal WGSL identifier (invalid characters -> '_', keywords and reserved
// words get a trailing '_', no leading "__"), then made unique within `scope`, which it joins.
std::string unique_identifier(const std::string& wanted, NameScope& scope);

// f32 bits as the shortest decimal that reads back as the same f32 ("0.3", "1e-05", "-2.0").
// Infinities and NaNs, which WGSL literals cannot spell, come out as bitcast<f32>(0x...u).
std::string f32_literal(uint32_t bits);
std::string i32_literal(int32_t value);
std::string u32_literal(uint32_t value);

}  // namespace crtforge::wgsl
