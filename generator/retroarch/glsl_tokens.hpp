// A GLSL token stream that keeps every character: identifiers, numbers and punctuation, and the
// whitespace and comments between them ("space"), so a text rewritten token by token prints back
// exactly as it was except where it was changed. Preprocessor lines are tokenised like code: a
// rename reaches macro bodies too.
#pragma once

#include <string>
#include <vector>

namespace crtforge::retroarch {

struct GlslToken {
    enum class Kind { Identifier, Number, Punct, Space } kind = Kind::Space;
    std::string text;
};

std::vector<GlslToken> tokenize_glsl(const std::string& text);
std::string join_tokens(const std::vector<GlslToken>& tokens);

// The index of the next token after `i` that is not space (tokens.size() if none).
size_t next_significant(const std::vector<GlslToken>& tokens, size_t i);
// The index of the previous token before `i` that is not space (-1 if none).
long previous_significant(const std::vector<GlslToken>& tokens, size_t i);

}  // namespace crtforge::retroarch
