#include "targets/word_scan.hpp"

namespace crtforge::detail {

std::string rewrite_words(const std::string& text, const std::function<std::optional<std::string>(std::string_view word)>& rewrite) {
    std::string out;
    out.reserve(text.size());
    size_t last = 0;
    for (size_t at = 0; at < text.size();) {
        if (!is_identifier_char(text[at])) {
            ++at;
            continue;
        }
        size_t end = at;
        while (end < text.size() && is_identifier_char(text[end])) ++end;
        if (auto replaced = rewrite(std::string_view(text).substr(at, end - at))) {
            out.append(text, last, at - last);
            out += *replaced;
            last = end;
        }
        at = end;
    }
    out.append(text, last, std::string::npos);
    return out;
}

std::string replace_member_access(const std::string& text, const std::string& instance,
                                  const std::function<std::string(const std::string& member)>& replace) {
    const std::string access = instance + ".";
    std::string out;
    size_t last = 0;
    for (size_t at = text.find(access); at != std::string::npos; at = text.find(access, at + 1)) {
        if (at < last || (at > 0 && is_identifier_char(text[at - 1]))) continue;
        size_t end = at + access.size();
        while (end < text.size() && is_identifier_char(text[end])) ++end;
        if (end == at + access.size()) continue;  // no member name follows
        out.append(text, last, at - last);
        out += replace(text.substr(at + access.size(), end - at - access.size()));
        last = end;
    }
    out.append(text, last, std::string::npos);
    return out;
}

}  // namespace crtforge::detail
