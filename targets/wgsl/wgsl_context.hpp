// Internal to the WGSL emitter: the per-stage state shared by the module-level printer
// (wgsl_module_emitter.cpp: types, constants, resources, entry points) and the function pipeline
// (wgsl_structure -> wgsl_analysis -> wgsl_printer: control flow, scopes and uses, then text).
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "targets/wgsl/spirv_module.hpp"
#include "targets/wgsl/wgsl_emitter.hpp"
#include "targets/wgsl/wgsl_names.hpp"

namespace crtforge::wgsl {

// Thrown inside the emitter only (caught in emit_wgsl and turned into a Diagnostic): keeps every
// "cannot translate" path one line long.
struct EmitError {
    std::string message;
    SourceLine line;
};
[[noreturn]] void fail(const std::string& message, const SourceLine& line = {});
[[noreturn]] void unsupported(const Instruction& inst, const std::string& why = {});

// A value as the function printer refers to it: the text of an expression and how tightly it
// binds, so that an operand gets parentheses exactly when it needs them.
struct Expr {
    enum class Kind {
        Primary,  // a name, literal, call, constructor, member access or index
        Unary,    // -x, !x, ~x
        Binary,   // a op b
    };
    std::string text;
    Kind kind = Kind::Primary;
    bool named = false;  // a let, var or parameter name, or a constant: free to repeat

    static Expr primary(std::string text) { return {std::move(text), Kind::Primary, false}; }
    static Expr unary(std::string text) { return {std::move(text), Kind::Unary, false}; }
    static Expr binary(std::string text) { return {std::move(text), Kind::Binary, false}; }
    static Expr name(std::string text) { return {std::move(text), Kind::Primary, true}; }
    std::string operand() const { return kind == Kind::Primary ? text : "(" + text + ")"; }
};

// What one stage's entry function reads and writes.
struct StageInterface {
    // One entry-point parameter or returned field. WGSL's stage I/O is scalars and vectors only, so
    // a matrix or array at location N is one of these per location: column / element k at N + k.
    struct Slot {
        std::string attribute;  // "@location(0)", "@builtin(position)"
        std::string name;       // the parameter's name, or the returned struct's member name
        std::string wgsl_type;  // the slot's WGSL type
        std::string value;      // outputs: what is returned (the local, or a column/element of it)
    };
    // A returned field at a location: the location, its SPIR-V scalar/vector type and its
    // interpolation attribute (what packing past WebGPU's limit groups by).
    struct Located {
        uint32_t location = 0, type = 0;
        std::string interpolation;
    };
    struct Input {
        uint32_t variable = 0;
        std::vector<Slot> params;  // the entry point's parameters for this input
        std::string read;          // how the body reads it (e.g. i32(vertex_index), mat2x2<f32>(m_0, m_1))
    };
    struct Output {
        uint32_t variable = 0;        // a plain output variable, or a gl_PerVertex-style block
        std::string local;            // the local var the body writes
        std::string wgsl_type;
        std::vector<Slot> fields;     // returned
        std::map<size_t, Located> located;  // fields[i] at a location -> where
        std::map<uint32_t, std::string> block_members;  // block member index -> local name
    };
    std::vector<Input> inputs;
    std::vector<Output> outputs;
};

// What one stage declared that a later stage declaring the same resource at the same binding
// shares (a program pass's vertex and fragment stages both read crtforge's CrtParams, and may
// sample the same texture): one declaration in the module, one name, one sampler binding.
struct SharedUniform {
    std::string struct_name, variable, body;  // body: the struct's declaration after its name
};
struct SharedTexture {
    std::string name, type, sampler;  // sampler: the split-off sampler's name ("" if none)
    uint32_t sampler_binding = 0;
};
// Where a vertex output location travels when the stage has more locations than WebGPU allows
// (kMaxInterStageLocations): packed with others of its scalar type and interpolation into one
// location, at components [first, first + count) of it.
struct PackedLocation {
    uint32_t location = 0;    // the packed location
    uint32_t first = 0, count = 0;
};
struct PackedContainer {
    uint32_t location = 0;
    std::string wgsl_type;      // vec2<f32>, vec4<i32>, f32, ...
    std::string interpolation;  // " @interpolate(flat, either)" or ""
};
// Dawn's limit on user-defined inter-stage variables (locations 0..14).
inline constexpr uint32_t kMaxInterStageLocations = 15;

struct SharedResources {
    std::map<std::pair<uint32_t, uint32_t>, SharedUniform> uniforms;   // (group, binding)
    std::map<std::pair<uint32_t, uint32_t>, SharedTexture> textures;   // (group, binding)
    std::map<uint32_t, uint32_t> next_sampler_binding;  // group -> first binding no stage uses
    std::map<std::string, std::string> helper_names;    // helper function -> its name in the module
    // The vertex stage's packing of its outputs (empty where they fit), which the fragment stage's
    // inputs follow: vertex output location -> where it travels, and the packed locations.
    std::map<uint32_t, PackedLocation> packed_locations;
    std::vector<PackedContainer> packed_containers;
    // Fragment input locations Vulkan interpolates without perspective (`noperspective`). WebGPU's
    // compatibility mode (GL ES backends) has no `@interpolate(linear)`, so the vertex stage sends
    // value * w and, at `clip_w_location`, w itself, both interpolated with perspective; their
    // quotient is the screen-linear value (exactly the value where w is 1, as in every crtforge pass).
    // Set only where both stages are emitted together (a stage alone keeps `linear`).
    bool emulate_linear = false;
    std::set<uint32_t> linear_locations;
    uint32_t clip_w_location = 0;
};

class ModuleEmitter {
public:
    ModuleEmitter(const SpirvModule& module, const EmitOptions& options, NameScope& global_names,
                  SharedResources& shared_resources, const std::string& stage_name, const std::string& entry_name);

    const SpirvModule& m;
    const EmitOptions& options;
    std::string stage_name;  // "vertex" / "fragment"
    std::string entry_name;  // the WGSL entry point's name
    std::map<uint32_t, std::vector<std::string>> struct_member_names;  // struct type id -> WGSL member names
    std::map<uint32_t, std::vector<WgslMember>> struct_layouts;        // struct type id -> members with offsets
    std::map<uint32_t, uint32_t> struct_sizes;                         // struct type id -> WGSL size

    // Module-scope text, keyed so stages can share identical declarations.
    std::map<std::string, std::string> struct_decls;    // struct name -> declaration
    std::vector<std::string> struct_order;
    std::map<std::pair<uint32_t, uint32_t>, std::string> resource_decls;  // (group, binding) -> declaration
    std::vector<WgslBinding> bindings;
    std::map<std::string, std::string> helpers;          // helper function name -> definition
    std::vector<std::string> functions;                  // emitted non-entry functions
    std::string entry;                                   // the entry point
    bool needs_derivative_uniformity_off = false;

    std::string type_name(uint32_t type_id);
    // Type used where a value lives in the uniform address space (same as type_name for scalars).
    std::string struct_name(uint32_t type_id);
    Expr constant(uint32_t id);
    bool is_constant(uint32_t id) const { return m.constants.count(id) != 0; }
    const Type& type(uint32_t id) const { return m.type(id); }
    uint32_t scalar_of(uint32_t type_id) const;   // element scalar of a scalar/vector type
    uint32_t component_count(uint32_t type_id) const;  // 1 for scalars

    // Module-scope resources and the sampler each combined image sampler was split into.
    std::map<uint32_t, std::string> resource_names;      // variable id -> WGSL name
    std::map<uint32_t, std::string> sampler_names;       // combined image sampler id -> sampler name
    std::map<std::string, bool> border_textures;          // WGSL texture name -> linear (EmitOptions::emulate_border)
    // The name of a helper function (defined once per module, named before any function is printed).
    std::string helper(const std::string& wanted, const std::string& definition_after_name);
    StageInterface interface;
    std::map<uint32_t, const Instruction*> private_globals;  // Private-storage variables
    NameScope& global_names;  // module-scope names of the whole WGSL module
    SharedResources& shared_resources;
    NameScope stage_names;    // those plus this stage's entry parameters and locals
    std::map<uint32_t, std::string> function_names;  // non-entry functions
    // A module-scope identifier: unique in the whole module, and reserved for this stage's locals.
    std::string module_scope_name(const std::string& wanted);

    void emit();

private:
    void declare_resources();
    // A scalar or vector of stage I/O at one location, reached from the whole value by `path`
    // ("", "[2]" for a matrix column or array element, "[1][0]" for nested ones).
    struct IoSlot {
        uint32_t type = 0;
        std::string path;
    };
    std::vector<IoSlot> io_slots(uint32_t type_id);
    // The whole value rebuilt from its slots' parameters, params[next...] in io_slots order.
    std::string rebuild_from_slots(uint32_t type_id, const std::vector<StageInterface::Slot>& params, size_t& next);
    void declare_interface(const EntryPoint& entry);
    // Vertex outputs beyond kMaxInterStageLocations packed into fewer locations (shared_resources).
    void pack_vertex_outputs();
    // The fragment stage's read of a packed vertex output (its packed location declared as a parameter).
    std::string packed_read(const PackedLocation& packed);
    std::map<uint32_t, StageInterface::Slot> packed_params_;  // packed location -> this stage's parameter
    // The vertex stage's screen-linear outputs sent as value * w, plus w (SharedResources::linear_locations).
    void emulate_linear_outputs();
    // The fragment stage's read of that w (a parameter of its own, or out of a packed location).
    std::string clip_w_read();
    std::optional<StageInterface::Slot> clip_w_param_;
    std::string declare_struct(uint32_t type_id);
    void emit_entry(const EntryPoint& entry);
    std::map<uint32_t, std::string> struct_names_;
};

// Prints a function. For the entry function (`is_entry`) only the body statements come out, to go
// inside the WGSL entry point, and every return becomes `return <entry_return>;` (bare `return;`
// when it is empty). Other functions come out whole, signature included.
std::string emit_function_body(ModuleEmitter& module, const Function& function, bool is_entry,
                               const std::string& entry_return, NameScope& local_names);

}  // namespace crtforge::wgsl
