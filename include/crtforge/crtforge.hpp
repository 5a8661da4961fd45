// Umbrella header for programs that embed the crtforge generator.
#pragma once

#include "crtforge/assembler.hpp"
#include "crtforge/cache.hpp"
#include "crtforge/diagnostic.hpp"
#include "crtforge/exporter.hpp"
#include "crtforge/files.hpp"
#include "crtforge/paths.hpp"
#include "crtforge/preset.hpp"
#include "crtforge/quality_tiers.hpp"
#include "crtforge/reflection.hpp"
#include "crtforge/spec.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "crtforge/targets.hpp"
#include "crtforge/template_library.hpp"
#include "crtforge/value.hpp"
#include "crtforge/variant.hpp"
#include "crtforge/version.hpp"
