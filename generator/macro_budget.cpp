#include "generator/macro_budget.hpp"
#include "generator/template_lint.hpp"

#include <cctype>
#include <map>
#include <set>
#include <vector>

#include <fmt/format.h>

namespace crtforge::detail {

namespace {

struct Place {
    std::string file;
    int line = 0;
};

struct Macro {
    bool function_like = false;
    std::vector<std::string> params;  // in order; "..." binds __VA_ARGS__
    std::vector<std::string> body;    // its tokens
    Place at;
};

bool identifier_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

std::vector<std::string> tokens_of(const std::string& text) {
    std::vector<std::string> out;
    for (size_t i = 0; i < text.size();) {
        const char c = text[i];
        if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
        } else if (identifier_start(c) || std::isdigit(static_cast<unsigned char>(c))) {
            size_t end = i + 1;
            while (end < text.size() && (identifier_char(text[end]) || text[end] == '.')) ++end;
            out.push_back(text.substr(i, end - i));
            i = end;
        } else {
            out.push_back(std::string(1, c));
            ++i;
        }
    }
    return out;
}

// Estimates how many tokens a token sequence becomes once every macro in it is expanded, as the
// preprocessor would: an object-like macro by its body, a function-like one by its body with each
// parameter standing for its argument's own expansion (so F(F(F(x))) with `F(a) a a` counts 8).
// Sums stop growing just past the limit, which also bounds the work.
class Budget {
public:
    using Tokens = std::vector<std::string>;
    using Env = std::map<std::string, double>;

    double expanded(const Tokens& t, size_t begin, size_t end, const Env* env) {
        double total = 0.0;
        for (size_t i = begin; i < end && total <= kMaxMacroTokens; ++i) {
            const std::string& token = t[i];
            if (env) {
                if (auto bound = env->find(token); bound != env->end()) {
                    total += bound->second;
                    continue;
                }
            }
            auto macro = macros.find(token);
            if (macro == macros.end() || active_.count(token)) {  // a macro is not expanded inside itself
                total += 1.0;
                continue;
            }
            const Macro& m = macro->second;
            if (!m.function_like) {
                total += object_size(token, m);
                continue;
            }
            if (i + 1 >= end || t[i + 1] != "(") {  // a function-like name without a call stays itself
                total += 1.0;
                continue;
            }
            // The arguments: top-level commas split them, up to the matching parenthesis.
            std::vector<double> args;
            size_t arg_begin = i + 2, k = i + 2;
            int depth = 0;
            for (; k < end; ++k) {
                if (t[k] == "(") ++depth;
                else if (t[k] == ")" && depth-- == 0) break;
                else if (t[k] == "," && depth == 0) {
                    args.push_back(expanded(t, arg_begin, k, env));
                    arg_begin = k + 1;
                }
            }
            if (k > arg_begin || !args.empty()) args.push_back(expanded(t, arg_begin, std::min(k, end), env));
            Env bound;
            for (size_t p = 0; p < m.params.size(); ++p) {
                if (m.params[p] == "...") {
                    double rest = 0.0;
                    for (size_t a = p; a < args.size(); ++a) rest += args[a];
                    bound["__VA_ARGS__"] = rest;
                } else {
                    bound[m.params[p]] = p < args.size() ? args[p] : 0.0;
                }
            }
            active_.insert(token);
            total += expanded(m.body, 0, m.body.size(), &bound);
            active_.erase(token);
            i = k;  // past the call's closing parenthesis
        }
        return total;
    }

    double object_size(const std::string& name, const Macro& m) {
        if (auto known = sizes_.find(name); known != sizes_.end()) return known->second;
        active_.insert(name);
        const double size = expanded(m.body, 0, m.body.size(), nullptr);
        active_.erase(name);
        return sizes_[name] = size;
    }

    std::map<std::string, Macro> macros;

private:
    std::set<std::string> active_;
    std::map<std::string, double> sizes_;  // object-like macros (their size depends on nothing else)
};

}  // namespace

Status check_macro_expansion(const std::string& source, const std::string& name) {
    const std::string text = without_comments(source);
    Budget budget;
    struct CodeLine {
        Place at;
        std::vector<std::string> tokens;
    };
    std::vector<CodeLine> code;
    Place next{name, 1};
    for (size_t begin = 0; begin < text.size();) {
        // One logical line: physical ones joined where a line ends in a backslash.
        std::string line;
        const Place at = next;
        size_t end = begin;
        for (;;) {
            end = text.find('\n', begin);
            const size_t stop = end == std::string::npos ? text.size() : end;
            ++next.line;
            if (stop > begin && text[stop - 1] == '\\') {
                line.append(text, begin, stop - begin - 1);
                begin = stop + 1;
                if (end == std::string::npos) break;
                continue;
            }
            line.append(text, begin, stop - begin);
            begin = end == std::string::npos ? text.size() : end + 1;
            break;
        }
        size_t i = line.find_first_not_of(" \t");
        if (i == std::string::npos) continue;
        if (line[i] != '#') {
            code.push_back({at, tokens_of(line)});
            continue;
        }
        i = line.find_first_not_of(" \t", i + 1);
        if (i == std::string::npos) continue;
        size_t word_end = i;
        while (word_end < line.size() && identifier_char(line[word_end])) ++word_end;
        const std::string directive = line.substr(i, word_end - i);
        if (directive == "line") {
            // `#line N` or `#line N "file"`: the next line is line N (of that file).
            const std::vector<std::string> words = tokens_of(line.substr(word_end));
            if (!words.empty() && std::isdigit(static_cast<unsigned char>(words[0][0]))) next.line = std::atoi(words[0].c_str());
            const size_t quote = line.find('"', word_end);
            const size_t close = quote == std::string::npos ? quote : line.find('"', quote + 1);
            if (close != std::string::npos) next.file = line.substr(quote + 1, close - quote - 1);
        } else if (directive == "define") {
            size_t n = line.find_first_not_of(" \t", word_end);
            if (n == std::string::npos || !identifier_start(line[n])) continue;
            size_t n_end = n;
            while (n_end < line.size() && identifier_char(line[n_end])) ++n_end;
            Macro macro;
            macro.at = at;
            size_t body = n_end;
            if (n_end < line.size() && line[n_end] == '(') {  // function-like: `(` right after the name
                const size_t close = line.find(')', n_end);
                if (close == std::string::npos) continue;
                macro.function_like = true;
                std::string params = line.substr(n_end + 1, close - n_end - 1);
                if (const size_t dots = params.find("..."); dots != std::string::npos) params.replace(dots, 3, " VARIADIC_ ");
                for (const std::string& p : tokens_of(params))
                    if (p != ",") macro.params.push_back(p == "VARIADIC_" ? "..." : p);
                body = close + 1;
            }
            macro.body = tokens_of(line.substr(body));
            budget.macros[line.substr(n, n_end - n)] = std::move(macro);
        } else if (directive == "undef") {
            const std::vector<std::string> words = tokens_of(line.substr(word_end));
            if (!words.empty()) budget.macros.erase(words[0]);
        }
    }
    // The first object-like macro, in source order, too large by itself.
    const std::pair<std::string, const Macro*> none{"", nullptr};
    std::pair<std::string, const Macro*> worst = none;
    for (const auto& [macro, definition] : budget.macros)
        if (!definition.function_like && budget.object_size(macro, definition) > kMaxMacroTokens &&
            (!worst.second || definition.at.line < worst.second->at.line))
            worst = {macro, &definition};
    if (worst.second)
        return make_error(fmt::format("macro '{}' expands to more than {:.0f} tokens (macros within macros): refused "
                                      "before the preprocessor runs", worst.first, kMaxMacroTokens),
                          worst.second->at.file, worst.second->at.line);
    // The code, line by line (a call's arguments may run over several lines).
    Budget::Tokens all;
    std::vector<size_t> line_of;
    for (size_t l = 0; l < code.size(); ++l)
        for (const std::string& t : code[l].tokens) {
            all.push_back(t);
            line_of.push_back(l);
        }
    double total = 0.0;
    for (size_t begin = 0; begin < all.size();) {
        size_t end = begin + 1;
        while (end < all.size() && line_of[end] == line_of[begin]) ++end;
        // A call left open at the line's end takes the lines up to its closing parenthesis.
        int depth = 0;
        for (size_t k = begin; k < end || (depth > 0 && k < all.size()); ++k) {
            if (all[k] == "(") ++depth;
            if (all[k] == ")") --depth;
            end = std::max(end, k + 1);
        }
        if ((total += budget.expanded(all, begin, end, nullptr)) > kMaxMacroTokens)
            return make_error(fmt::format("the shader expands to more than {:.0f} tokens by here (macros within macros): "
                                          "refused before the preprocessor runs", kMaxMacroTokens),
                              code[line_of[begin]].at.file, code[line_of[begin]].at.line);
        begin = end;
    }
    return Ok{};
}

}  // namespace crtforge::detail
