// Godot 3's parser: see godot3_syntax.hpp.
#include "targets/godot/godot3_syntax.hpp"
#include "targets/float_literals.hpp"
#include "targets/word_scan.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>
#include <regex>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <spirv_cross/spirv_common.hpp>

namespace crtforge::godot::godot3 {

namespace {

// The index of the bracket closing the one at `open` ('(' or '{'), or npos.
size_t matching(const std::string& text, size_t open) {
    const char in = text[open], out = in == '(' ? ')' : '}';
    int depth = 0;
    for (size_t i = open; i < text.size(); ++i) {
        if (text[i] == in) ++depth;
        else if (text[i] == out && --depth == 0) return i;
    }
    return std::string::npos;
}

// `text` split at the `separator`s outside any brackets.
std::vector<std::string> split_top_level(const std::string& text, char separator) {
    std::vector<std::string> parts(1);
    int depth = 0;
    for (char c : text) {
        if (c == '(' || c == '[' || c == '{') ++depth;
        if (c == ')' || c == ']' || c == '}') --depth;
        if (c == separator && depth == 0) parts.emplace_back();
        else parts.back() += c;
    }
    return parts;
}

// The bodies ({ .. }) of the loops that start in [first, end) of `text`: for, while and do.
std::vector<std::pair<size_t, size_t>> loop_bodies(const std::string& text, size_t first, size_t end) {
    static const std::regex loop(R"(\b(for|while) \(|\bdo\b)");
    std::vector<std::pair<size_t, size_t>> out;
    const std::string part = text.substr(first, end - first);
    for (auto it = std::sregex_iterator(part.begin(), part.end(), loop); it != std::sregex_iterator(); ++it) {
        size_t after = first + static_cast<size_t>(it->position() + it->length());
        if ((*it)[1].matched) {  // for / while: the body follows the header's ')'
            const size_t close = matching(text, after - 1);
            if (close == std::string::npos) continue;
            after = close + 1;
        }
        const size_t brace = text.find_first_not_of(" \t\n", after);
        if (brace == std::string::npos || text[brace] != '{') continue;  // a do-while's closing while (..);
        const size_t close = matching(text, brace);
        if (close != std::string::npos) out.emplace_back(brace, close);
    }
    return out;
}

std::string trimmed(const std::string& s) {
    const size_t first = s.find_first_not_of(" \t\n"), last = s.find_last_not_of(" \t\n");
    return first == std::string::npos ? std::string() : s.substr(first, last - first + 1);
}

// `text` with each match of `pattern` replaced by what `replace` returns for it; a match it
// returns nothing for is kept as it is. Every rewrite below is one of these.
std::string replace_each(const std::string& text, const std::regex& pattern,
                         const std::function<std::optional<std::string>(const std::smatch&)>& replace) {
    std::string out;
    size_t last = 0;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), pattern); it != std::sregex_iterator(); ++it) {
        std::optional<std::string> replacement = replace(*it);
        if (!replacement) continue;
        out.append(text, last, static_cast<size_t>(it->position()) - last);
        out += *replacement;
        last = static_cast<size_t>(it->position() + it->length());
    }
    out.append(text, last, std::string::npos);
    return out;
}

}  // namespace

std::string with_godot3_syntax(const std::string& text) {
    return with_float_literals_exact(with_negated_subtrahends_added(with_unsigned_literals_spelled(with_loop_initialisers(
        with_loop_increments(with_loop_steps_in_body(with_loop_declarations_single(with_array_copies_elementwise(with_constant_arrays_local(text)))))))));
}

std::string with_float_literals_exact(const std::string& text) {
    // Godot 3 hands a float constant to the driver printed with six significant digits (%g): 0.9999999
    // reaches it as 1.0 (scanline-classic's `alpha > 1.0 - EPS` then never holds and its bezel's
    // green key shows), 0.083333336 as 0.0833333. A literal those digits do not keep goes as the
    // bits of its float, which an integer carries whole. Not in a uniform's default (the inspector's
    // value, which reaches the shader as a parameter, not as text) or a constant's initialiser,
    // which Godot 3 wants literal.
    auto exact = [](const std::string& token, const std::string& suffix) {
        if (!suffix.empty()) return token + suffix;
        const float value = std::strtof(token.c_str(), nullptr);
        const float printed = std::strtof(fmt::format("{:g}", static_cast<double>(value)).c_str(), nullptr);
        if (std::bit_cast<uint32_t>(printed) == std::bit_cast<uint32_t>(value) || !std::isfinite(value)) return token;
        return fmt::format("uintBitsToFloat(uint({}))", std::bit_cast<int32_t>(value));
    };
    std::string out;
    out.reserve(text.size() + text.size() / 8);
    for (size_t at = 0; at < text.size();) {
        size_t end = text.find('\n', at);
        end = end == std::string::npos ? text.size() : end + 1;
        const std::string line = text.substr(at, end - at);
        const size_t first = line.find_first_not_of(" \t");
        const bool declared = first != std::string::npos && (line.compare(first, 8, "uniform ") == 0 || line.compare(first, 6, "const ") == 0);
        out += declared ? line : crtforge::detail::rewrite_float_literals(line, exact);
        at = end;
    }
    return out;
}

std::string with_array_copies_elementwise(const std::string& text) {
    static const std::regex declared(R"(\b\w+ (\w+)\[(\d+)\](?= =|;))");
    std::map<std::string, std::string> lengths;  // array name -> its length
    for (auto it = std::sregex_iterator(text.begin(), text.end(), declared); it != std::sregex_iterator(); ++it)
        lengths[(*it)[1].str()] = (*it)[2].str();
    if (lengths.empty()) return text;
    // `a = b;`, or a declaration initialised from another array, `float a[6] = b;` (nis's scaler:
    // "Invalid data type for array"), which is declared first and then copied.
    static const std::regex copy(R"((^|\n)([ \t]*)(\w+ (\w+)\[\d+\]|(\w+)) = (\w+);(?=\n))");
    const std::string copied = replace_each(text, copy, [&](const std::smatch& m) -> std::optional<std::string> {
        const bool declaration = m[4].matched;
        auto to = lengths.find(m[declaration ? 4 : 5].str()), from = lengths.find(m[6].str());
        if (to == lengths.end() || from == lengths.end() || to->second != from->second) return std::nullopt;
        const std::string indent = m[1].str() + m[2].str();
        return (declaration ? indent + m[3].str() + ";" : std::string()) + indent + "for (int crt_element = 0; crt_element < " +
               to->second + "; crt_element++) { " + to->first + "[crt_element] = " + from->first + "[crt_element]; }";
    });
    // `a = float[](x, y, ...);` (crt-guest-advanced-pal's PalPass3 picks one of two weight tables:
    // "Expected '[' or '.'"): an assignment element by element, of the constructor's arguments.
    static const std::regex constructed(R"((^|\n)([ \t]*)(\w+) = \w+\[\d*\]\((.*)\);(?=\n))");
    return replace_each(copied, constructed, [&](const std::smatch& m) -> std::optional<std::string> {
        auto to = lengths.find(m[3].str());
        const std::vector<std::string> elements = split_top_level(m[4].str(), ',');
        if (to == lengths.end() || std::to_string(elements.size()) != to->second) return std::nullopt;
        std::string out;
        for (size_t i = 0; i < elements.size(); ++i)
            out += (i ? "\n" + m[2].str() : m[1].str() + m[2].str()) + to->first + "[" + std::to_string(i) + "] = " + trimmed(elements[i]) + ";";
        return out;
    });
}

std::string with_constant_arrays_local(const std::string& text) {
    static const std::regex constant(R"(^const (\w+ (\w+)\[\d+\] = .*;)$)");
    struct Constant {
        std::string declaration, name;
    };
    std::vector<Constant> constants;
    std::string rest;  // the text without them
    size_t at = 0;
    while (at < text.size()) {
        size_t end = text.find('\n', at);
        end = end == std::string::npos ? text.size() : end + 1;
        const std::string line = text.substr(at, end - at - (text[end - 1] == '\n' ? 1 : 0));
        std::smatch m;
        if (std::regex_match(line, m, constant)) constants.push_back({m[1].str(), m[2].str()});
        else rest.append(text, at, end - at);
        at = end;
    }
    if (constants.empty()) return text;
    // SPIRV-Cross prints a function as its signature at the start of a line, then "{" and "}"
    // alone on lines of their own.
    std::string out;
    size_t last = 0;
    for (size_t open = rest.find("\n{\n"); open != std::string::npos; open = rest.find("\n{\n", open + 1)) {
        if (rest[open - 1] != ')') continue;  // a struct's braces, not a function's
        const size_t close = rest.find("\n}\n", open);
        if (close == std::string::npos) break;
        const std::string body = rest.substr(open, close - open);
        std::string locals;
        for (const Constant& c : constants)
            if (std::regex_search(body, std::regex("\\b" + c.name + "\\b"))) locals += "    " + c.declaration + "\n";
        out.append(rest, last, open + 3 - last);
        out += locals;
        last = open + 3;
    }
    out.append(rest, last, std::string::npos);
    return out;
}

std::string with_loop_steps_in_body(const std::string& text) {
    std::string out = text;
    for (size_t at = out.find("for ("); at != std::string::npos; at = out.find("for (", at + 1)) {
        const size_t open = at + 4, close = matching(out, open);
        if (close == std::string::npos) throw spirv_cross::CompilerError("an unbalanced for loop");
        const std::vector<std::string> parts = split_top_level(out.substr(open + 1, close - open - 1), ';');
        if (parts.size() != 3) continue;
        const std::vector<std::string> steps = split_top_level(parts[2], ',');
        if (steps.size() < 2) continue;
        const size_t brace = out.find_first_not_of(" \t\n", close + 1);
        if (brace == std::string::npos || out[brace] != '{') throw spirv_cross::CompilerError("a for loop with a comma list of steps and no braces");
        const size_t end = matching(out, brace);
        if (end == std::string::npos) throw spirv_cross::CompilerError("an unbalanced for loop body");
        std::string inline_steps;  // the steps as statements, on one line
        for (const std::string& step : steps) inline_steps += trimmed(step) + "; ";
        // The body's closing brace sits on a line of its own, indented as the loop.
        const size_t line = out.rfind('\n', end) + 1;
        out.insert(line, out.substr(line, end - line) + "    " + trimmed(inline_steps) + "\n");
        // Each `continue` of this loop (not of a loop inside it) takes the steps first.
        const std::vector<std::pair<size_t, size_t>> inner = loop_bodies(out, brace + 1, line);
        for (size_t c = line; c > brace;) {
            const size_t found = out.rfind("continue;", c - 1);
            if (found == std::string::npos || found <= brace) break;
            c = found;
            const bool nested = std::any_of(inner.begin(), inner.end(), [&](const auto& r) { return found > r.first && found < r.second; });
            if (!nested) out.replace(found, 9, "{ " + inline_steps + "continue; }");
        }
        out.replace(open + 1, close - open - 1, parts[0] + ";" + parts[1] + "; ");
    }
    return out;
}

std::string with_unsigned_literals_spelled(const std::string& text) {
    // Godot 3's parser reads 4u as the int 4 ("Invalid arguments to operator '%' :uint and int"):
    // uint(4) is the same constant in a form it types right.
    return crtforge::detail::rewrite_words(text, [](std::string_view word) -> std::optional<std::string> {
        if (word.size() < 2 || (word.back() != 'u' && word.back() != 'U')) return std::nullopt;
        const std::string_view number = word.substr(0, word.size() - 1);
        const bool hex = number.size() > 2 && number[0] == '0' && (number[1] == 'x' || number[1] == 'X') &&
                         number.find_first_not_of("0123456789abcdefABCDEF", 2) == std::string_view::npos;
        const bool decimal = number.find_first_not_of("0123456789") == std::string_view::npos;
        if ((!hex && !decimal) || (hex && number.size() > 10)) return std::nullopt;  // 32 bits at most
        if (!hex) return "uint(" + std::string(number) + ")";
        // Nor does it read hexadecimal ("Invalid numeric constant"; SPIRV-Cross spells an infinite
        // float constant uintBitsToFloat(0xff800000u)): the int of the same bits, which uint() keeps.
        const auto bits = static_cast<uint32_t>(std::stoul(std::string(number.substr(2)), nullptr, 16));
        return "uint(" + std::to_string(static_cast<int32_t>(bits)) + ")";
    });
}

std::string with_negated_subtrahends_added(const std::string& text) {
    // Godot 3 drops the parentheses of a negated operand and the spaces around an operator. x - (-y)
    // is x + y exactly in IEEE arithmetic (subtraction is the addition of the negation) and in
    // wrapping integers. Only a whole operand is taken: a name (with its members) or a number,
    // whose exponent may carry a sign.
    static const std::regex negated(R"( - (?:\(-(\d[\d.]*[eE][-+]?\d+|[\w.]+)\)|-(\d[\d.]*[eE][-+]?\d+|[\w.]+)\b))");
    return replace_each(text, negated, [](const std::smatch& m) -> std::optional<std::string> {
        return " + " + (m[1].matched ? m[1].str() : m[2].str());
    });
}

std::string with_loop_increments(const std::string& text) {
    // Godot 3's parser wants an expression after a for loop's second ';' ("Expected expression,
    // found: QUESTION"), which SPIRV-Cross leaves out when the loop steps inside its body. An
    // increment of zero changes nothing: `x += 0` on the loop's own variable, or on a variable
    // declared for the purpose when the loop declares none.
    // SPIRV-Cross writes `for (;;)` for a loop it cannot put in for's three parts (one whose exit
    // test is not at its head). Godot 3.2.3 refuses that in some places ("Expected expression" at
    // atari-ntsc's cell-list loop, nested in an if) and takes it in others; with all three parts,
    // `true` the condition, it takes it everywhere.
    static const std::regex loop(R"(for \(([^;]*); ?([^;]*); ?\))");
    static const std::regex declared(R"(^(int|uint|float) (\w+))");
    int spare = 0;
    return replace_each(text, loop, [&](const std::smatch& m) -> std::optional<std::string> {
        std::string init = m[1].str(), step;
        std::smatch var;
        if (std::regex_search(init, var, declared)) {
            step = var[2].str() + (var[1] == "float" ? " += 0.0" : var[1] == "uint" ? " += 0u" : " += 0");
        } else if (init.empty()) {
            const std::string name = "crtforge_loop" + std::to_string(spare++);
            init = "int " + name + " = 0";
            step = name + " += 0";
        } else {
            throw spirv_cross::CompilerError("a for loop with no increment and an initialiser Godot 3 cannot extend: " + init);
        }
        const std::string condition = m[2].str().empty() ? std::string("true") : m[2].str();
        return "for (" + init + "; " + condition + "; " + step + ")";
    });
}

std::string with_loop_initialisers(const std::string& text) {
    // Godot 3.2.3 refuses a for loop with no initialiser ("Expected expression, found: PERIOD":
    // nis's scaler, whose counter SPIRV-Cross declares before the loop); a declaration of an int
    // nothing reads takes its place. Runs after with_loop_increments, which gave `for (;;)` one.
    static constexpr std::string_view kHead = "for (;";
    std::string out;
    size_t last = 0;
    int spare = 0;
    for (size_t at = text.find(kHead); at != std::string::npos; at = text.find(kHead, at + kHead.size())) {
        out.append(text, last, at - last);
        out += "for (int crtforge_init" + std::to_string(spare++) + " = 0;";
        last = at + kHead.size();
    }
    out.append(text, last, std::string::npos);
    return out;
}

std::string with_loop_declarations_single(const std::string& text) {
    // Godot 3 takes `for (float a = x, b = y; ...)` but prints it to GLSL as `float a=xfloat b=y`
    // (crt-beans-rgb's Scanlines: "unexpected NEW_IDENTIFIER"). The loop keeps its first variable;
    // the others are declared on the lines before it (SPIRV-Cross names a function's locals apart,
    // so they take no other name's place).
    static const std::regex head(R"((^|\n)([ \t]*)for \((\w+) ([^;]*);)");
    return replace_each(text, head, [](const std::smatch& m) -> std::optional<std::string> {
        const std::vector<std::string> declarators = split_top_level(m[4].str(), ',');
        if (declarators.size() < 2) return std::nullopt;
        const std::string indent = m[1].str() + m[2].str(), type = m[3].str();
        std::string out;
        for (size_t i = 1; i < declarators.size(); ++i) out += indent + type + " " + trimmed(declarators[i]) + ";";
        return out + indent + "for (" + type + " " + trimmed(declarators[0]) + ";";
    });
}

}  // namespace crtforge::godot::godot3
