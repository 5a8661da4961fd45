# Compile time. A clean build on CI's 2 cores was half of the test command's time: every
# translation unit parses about 90k lines of the C++20 standard library and then generates code
# again for the same instantiations of std::string, fmt, nlohmann::json and CLI11.
# crtforge_compile_fast(TARGET [HEADER...]) gives TARGET
#  - a precompiled header: the standard headers most files include, plus the HEADERs (third-party
#    headers the target uses);
#  - a unity build (CRTFORGE_UNITY, on by default): its sources compiled 8 to a translation unit,
#    so those instantiations are generated once per batch instead of once per file.
# A source opts out with SKIP_PRECOMPILE_HEADERS / SKIP_UNITY_BUILD_INCLUSION (and says why).
option(CRTFORGE_UNITY "Compile each library's sources in batches (unity build)" ON)

set(CRTFORGE_STD_PRECOMPILED
  <algorithm> <array> <cmath> <cstdint> <cstring> <filesystem> <fstream> <functional> <map>
  <memory> <mutex> <optional> <regex> <set> <sstream> <string> <string_view> <utility> <vector>)

function(crtforge_compile_fast target)
  target_precompile_headers(${target} PRIVATE ${CRTFORGE_STD_PRECOMPILED} ${ARGN})
  if(CRTFORGE_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
    # A batch is a main file that includes .cpp files, so GCC takes a class defined in one of them
    # with a member of that file's anonymous namespace (a pimpl's State) for a header's class.
    target_compile_options(${target} PRIVATE -Wno-subobject-linkage)
  endif()
endfunction()
