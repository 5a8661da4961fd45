// The compile cache's key of a source (generator/spirv_source_key.cpp) and the memo's claims
// (bounded_memo.hpp): what is left out of a key can change no module, what can is kept, and a
// module found under a key is the one a fresh compile of the source would give.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <bit>
#include <optional>
#include <thread>

#include "crtforge/bounded_memo.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "generator/spirv_source_key.hpp"

namespace {

using namespace crtforge;

// A generated pass as the assembler writes one: a header naming the preset, a form macro, a
// #line naming the folder it was assembled in, baked params as specialization constants.
std::string pass_source(const std::string& preset, const std::string& folder, const std::string& gain, const std::string& bias,
                        const std::string& extra = "") {
    return "#version 450\n#extension GL_GOOGLE_cpp_style_line_directive : require\n"
           "// crtforge: preset " + preset + ", precision high, uniforms none\n"
           "#define CRT_FORM_ra_" + preset + "_pass0 1\n" + extra +
           "layout(constant_id = 0) const float GAIN = " + gain + ";\n"
           "layout(constant_id = 1) const float BIAS = " + bias + ";\n"
           "#line 1 \"" + folder + "/overlay/stages/ra_" + preset + "/pass0.frag\"\n"
           "layout(location = 0) in vec2 uv;\nlayout(location = 0) out vec4 color;\n"
           "void main() { color = vec4(uv.x * GAIN + BIAS, uv.y, 0.0, 1.0); }\n";
}

float value_of(const SourceKey& key, uint32_t id) {
    REQUIRE(key.float_values.count(id));
    REQUIRE(key.float_values.at(id).words.size() == 1);
    return std::bit_cast<float>(key.float_values.at(id).words[0]);
}

}  // namespace

TEST_CASE("a source's cache key leaves out what no module depends on and keeps what one does", "[compile][cache]") {
    const SourceKey a = source_key(pass_source("one", "/tmp/crtforge-corpus-aaaaaa", "0.5", "-0.25"));
    const SourceKey b = source_key(pass_source("two_longer", "/tmp/crtforge-corpus-bbbbbb", "1.5", "1e-05"));
    CHECK(a.text == b.text);  // the header, the unread form macro, the folder and the values are out
    CHECK(value_of(a, 0) == 0.5f);
    CHECK(value_of(a, 1) == -0.25f);
    CHECK(value_of(b, 0) == 1.5f);
    CHECK(value_of(b, 1) == 1e-05f);
    // A line removed from the key stays a line: __LINE__ and #line numbering are untouched.
    const std::string written = pass_source("one", "x", "0.5", "0.5");
    CHECK(std::count(a.text.begin(), a.text.end(), '\n') == std::count(written.begin(), written.end(), '\n'));

    // Code counts.
    CHECK(source_key(pass_source("one", "/tmp/a", "0.5", "0.5", "const float k = 2.0;\n")).text != a.text);
    // A form macro something reads is kept, with its name.
    const std::string read = "#ifdef CRT_FORM_ra_one_pass0\n#endif\n";
    CHECK(source_key(pass_source("one", "/tmp/a", "0.5", "0.5", read)).text !=
          source_key(pass_source("two", "/tmp/a", "0.5", "0.5", read)).text);
    // A comment a backslash continues, or one with a `*/` that may close a block comment, is kept.
    for (const std::string comment : {"// note \\\n", "// a */ b\n"})
        CHECK(source_key(pass_source("one", "/tmp/a", "0.5", "0.5", comment)).text !=
              source_key(pass_source("one", "/tmp/a", "0.5", "0.5", "// other\n")).text);
    // Integer and boolean specialization constants keep their values in the key.
    const auto with_int = [](const std::string& v) {
        return source_key(pass_source("one", "/tmp/a", "0.5", "0.5", "layout(constant_id = 5) const int MODE = " + v + ";\n"));
    };
    CHECK(with_int("1").text != with_int("2").text);
    CHECK_FALSE(with_int("1").float_values.count(5));
    // A source that reads __FILE__, or that declares one constant id twice, is its own key.
    const std::string file = pass_source("one", "/tmp/a", "0.5", "0.5", "int f = __FILE__;\n");
    CHECK(source_key(file).text == file);
    CHECK(source_key(file).float_values.empty());
    const std::string twice = pass_source("one", "/tmp/a", "0.5", "0.5", "layout(constant_id = 1) const float OTHER = 2.0;\n");
    CHECK(source_key(twice).text == twice);
    // Values that are no plain literal stay in the key.
    for (const std::string odd : {"1.0 + 1.0", "inf", "GAIN2", "0x10"}) {
        INFO(odd);
        const SourceKey k = source_key(pass_source("one", "/tmp/a", odd, "0.5"));
        CHECK_FALSE(k.float_values.count(0));
        CHECK(k.text.find("= " + odd + ";") != std::string::npos);
    }
}

TEST_CASE("a memo claim makes a second worker wait for the first's value", "[cache]") {
    BoundedMemo<int> memo(16, [](int) { return size_t{1}; });
    std::atomic<bool> asking{false};
    std::optional<int> seen;
    std::thread second;
    {
        const auto claim = memo.claim("key");
        second = std::thread([&] {
            asking = true;
            const auto mine = memo.claim("key");  // granted once the first claim is over
            seen = memo.find("key");
        });
        while (!asking) std::this_thread::yield();
        memo.put("key", 7);
    }  // the first claim ends: the second worker finds the value the first put
    second.join();
    CHECK(seen == 7);
    const auto other = memo.claim("other");  // a claim of another key does not wait
    const auto again = memo.claim("key");    // nor one of a key no one holds
    CHECK_FALSE(memo.find("other"));
}

TEST_CASE("spirv-val remembers the modules it passed, never a module that differs from one", "[compile][cache]") {
    CompileOptions options;
    auto module = compile_to_spirv("#version 450\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec4(0.5); }\n", options);
    REQUIRE(module.ok());
    const SpirvBinary& words = module.value();
    CHECK(validate_spirv(words).ok());  // passed by the compiler already: remembered
    CHECK(validate_spirv(words).ok());
    // The same size, one word changed (the id bound to 0: no id may be used): not the remembered module.
    SpirvBinary broken = words;
    broken[3] = 0;
    const Status once = validate_spirv(broken), twice = validate_spirv(broken);
    CHECK_FALSE(once.ok());
    CHECK_FALSE(twice.ok());
    // A module cut short, and a module with a word appended, are judged on their own bytes too.
    SpirvBinary shorter(words.begin(), words.end() - 1);
    CHECK_FALSE(validate_spirv(shorter).ok());
    SpirvBinary longer = words;
    longer.push_back(0x00010000u);  // half an instruction header: a word count of 1, opcode 0
    CHECK_FALSE(validate_spirv(longer).ok());
    CHECK(validate_spirv(words).ok());
}
