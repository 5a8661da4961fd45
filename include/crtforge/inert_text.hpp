// Text from templates (a preset's doc, a param's doc and unit, a file path) that generated code
// carries must stay inert there: in a `//` comment, nothing may end the line early (a consumer that
// treats \r, \v, \f, U+0085, U+2028 or U+2029 as a line end would compile the rest as code), and
// a trailing backslash must not splice the next line into the comment. The loaders refuse such
// text already (toml_reader's unsafe_text); these functions are the emitters' own guarantee, the
// one place every target's generated text goes through.
#pragma once

#include <string>
#include <string_view>

namespace crtforge {

// One line safe inside a `//` comment of GLSL, HLSL, WGSL and Godot's shading language: every
// control character and Unicode line or paragraph separator becomes a space, and a backslash
// becomes '/' (no line splicing by a preprocessor).
std::string inert_comment(std::string_view text);

// Safe inside a double-quoted string of a `#line` directive or a Godot resource: as above, and
// '"' becomes '\''.
std::string inert_quoted(std::string_view text);

// Safe as HTML or XML text and attribute values: '&', '<', '>', '"' and '\'' as entities.
std::string html_escape(std::string_view text);

// Safe as XML 1.0 text and attribute values (junit.xml), which must be well-formed: html_escape,
// and every character XML 1.0 forbids even as a reference (C0 controls but tab, newline and
// carriage return; U+FFFE, U+FFFF) or a byte that is not UTF-8 becomes U+FFFD.
std::string xml_escape(std::string_view text);

}  // namespace crtforge
