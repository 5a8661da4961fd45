// Where crtforge finds what it ships besides code: the data directory (templates/, golden/,
// tools/godot3-runner, tools/wgsl-runner) and the image I/O module. No absolute path is compiled
// in, so a crtforge installed with `cmake --install` can be moved, and a build tree works as is.
//
// Layout, the same for an installed prefix and for a build tree (which links its share/crtforge
// entries to the source tree):
//   <prefix>/share/crtforge/{templates, golden, tools}
//   <prefix>/lib/crtforge/libcrtforge_imageio.so
//
// The prefix is, first found:
//   1. the one a program passed to set_install_prefix() — a find_package(crtforge) consumer gets it
//      as the CMake variable crtforge_PREFIX and the compile definition CRTFORGE_INSTALL_PREFIX;
//   2. $CRTFORGE_PREFIX;
//   3. the directory of the running executable, or its parent (bin/ of an installed crtforge,
//      tests/ of a build tree), whichever holds share/crtforge/templates.
// Single resources keep their own overrides: $CRTFORGE_TEMPLATES, $CRTFORGE_GOLDEN,
// $CRTFORGE_IMAGEIO_MODULE.
#pragma once

#include <string>

namespace crtforge {

// The running program's path (/proc/self/exe), or "" when it cannot be read: where the prefix is
// looked for, and what `crtforge corpus` starts as its workers.
std::string running_executable();
// Call before any other crtforge call that loads data (not thread-safe against concurrent lookups).
void set_install_prefix(const std::string& prefix);

// The prefix found by the rules above; "" when none holds share/crtforge/templates.
const std::string& install_prefix();

// <prefix>/share/crtforge, or "" when no prefix was found.
std::string data_dir();

// A path under data_dir() ("templates", "golden", "tools/wgsl-runner"); relative to the working
// directory when no prefix was found, so the error that follows names something sensible.
std::string data_path(const std::string& relative);

// <prefix>/lib/crtforge/<file>.
std::string module_path(const std::string& file);

}  // namespace crtforge
