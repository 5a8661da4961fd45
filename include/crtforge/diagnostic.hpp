// Diagnostics and the Result<T> error channel used by every crtforge API.
// Errors are values, never exceptions: each carries the source location (file, line, column) and
// the field it is about, and prints as one line.
#pragma once

#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace crtforge {

// Input: the user's spec, preset, image or arguments are wrong (CLI exit code 2).
// Validation: crtforge's own output failed a check — spirv-val, a consumer compiler, a golden
// comparison (CLI exit code 1).
enum class ErrorKind { Input, Validation };

struct Diagnostic {
    std::string file;     // path as the user gave it (or a <generated:...> marker); may be empty
    int line = 0;         // 1-based; 0 = unknown
    int column = 0;       // 1-based; 0 = unknown
    std::string field;    // dotted path of the offending field, e.g. "stages.scanlines.scanlineIntensity"
    std::string message;  // what is wrong, and where useful, what would be right
    ErrorKind kind = ErrorKind::Input;

    // "file:line:col: error: field 'x': message" — always a single line. Appends only: GCC 12
    // misreports `"literal" + std::string` inlined here as an overlapping memcpy (-Wrestrict,
    // GCC bug 105329) in every file that includes this header.
    std::string str() const { return labelled("error"); }
    // The same line as a warning: "file:line:col: warning: field 'x': message" (what a loader accepts
    // but reports: a migrated key, a value RetroArch ignores).
    std::string warning() const { return labelled("warning"); }

private:
    std::string labelled(const char* label) const {
        std::string out;
        if (!file.empty()) {
            out += file;
            if (line > 0) out.append(1, ':').append(std::to_string(line));
            if (line > 0 && column > 0) out.append(1, ':').append(std::to_string(column));
            out += ": ";
        }
        out.append(label).append(": ");
        if (!field.empty()) out.append("field '").append(field).append("': ");
        for (char c : message) out += (c == '\n' || c == '\r') ? ' ' : c;  // keep it one line
        return out;
    }
};

inline Diagnostic make_error(std::string message, std::string file = {}, int line = 0,
                             std::string field = {}, int column = 0) {
    return Diagnostic{std::move(file), line, column, std::move(field), std::move(message), ErrorKind::Input};
}

inline Diagnostic make_validation_error(std::string message, std::string file = {}, int line = 0) {
    return Diagnostic{std::move(file), line, 0, {}, std::move(message), ErrorKind::Validation};
}

// A value or a diagnostic. Check ok() before value(); discarding one is a compile-time warning.
template <typename T>
class [[nodiscard]] Result {
public:
    Result(T value) : data_(std::move(value)) {}
    Result(Diagnostic error) : data_(std::move(error)) {}

    bool ok() const { return std::holds_alternative<T>(data_); }
    explicit operator bool() const { return ok(); }
    T& value() & { return std::get<T>(data_); }
    const T& value() const& { return std::get<T>(data_); }
    T&& value() && { return std::get<T>(std::move(data_)); }
    const Diagnostic& error() const { return std::get<Diagnostic>(data_); }

private:
    std::variant<T, Diagnostic> data_;
};

// "a, b, c": lists of names in messages.
inline std::string join_list(const std::vector<std::string>& items, const char* separator = ", ") {
    std::string out;
    for (const auto& item : items) out += (out.empty() ? "" : separator) + item;
    return out;
}

// Result<void> stand-in.
struct Ok {};
using Status = Result<Ok>;

}  // namespace crtforge
