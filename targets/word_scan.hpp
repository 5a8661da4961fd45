// Words of generated shader text — maximal runs of letters, digits and '_', what a regex's
// \b…\b sees — found by a plain scan. The emitters rewrite every pass's whole text several times;
// std::regex there cost a fifth of an export of a many-pass preset.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "crtforge/identifier_chars.hpp"

namespace crtforge::detail {

// `text` with each word for which `rewrite(word)` gives a value replaced by it.
std::string rewrite_words(const std::string& text, const std::function<std::optional<std::string>(std::string_view word)>& rewrite);

// `text` with each `instance.member` (instance a whole word) replaced by `replace(member)`.
std::string replace_member_access(const std::string& text, const std::string& instance,
                                  const std::function<std::string(const std::string& member)>& replace);

}  // namespace crtforge::detail
