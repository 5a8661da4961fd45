#include "runtime/vulkan/job_validation.hpp"

#include "runtime/common/job_checks.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "runtime/vulkan/spirv_inspect.hpp"

namespace crtforge::vulkan {
namespace {

using detail::job_error;
using detail::output_format_name;

// The smallest of the limits an image of this size has to satisfy along one axis.
uint32_t max_extent(const VkPhysicalDeviceLimits& limits, bool horizontal) {
    uint32_t limit = limits.maxImageDimension2D;
    limit = std::min(limit, horizontal ? limits.maxFramebufferWidth : limits.maxFramebufferHeight);
    limit = std::min(limit, limits.maxViewportDimensions[horizontal ? 0 : 1]);
    return limit;
}

Status check_size(const VulkanContext& context, const RenderJob& job) {
    const auto& limits = context.limits();
    auto clamp_int = [](uint32_t v) { return static_cast<int>(std::min<uint32_t>(v, 1u << 30)); };
    detail::JobLimits job_limits{clamp_int(max_extent(limits, true)), clamp_int(max_extent(limits, false)),
                                 clamp_int(limits.maxImageDimension2D), context.info().name,
                                 "the device's maxImageDimension2D", &context};
    if (auto s = detail::check_job_extent(job.width, job.height, *job.input, job_limits); !s.ok()) return s;
    if (auto s = detail::check_texture_images(job.textures, job_limits); !s.ok()) return s;
    if (auto s = detail::check_viewport(job.viewport, job.width, job.height); !s.ok()) return s;
    return detail::check_clear_color(job.clear_color);
}

Status check_bindings(const VulkanContext& context, const RenderJob& job) {
    const auto& limits = context.limits();
    if (job.descriptor_set >= limits.maxBoundDescriptorSets) {
        return job_error(fmt::format("descriptor set {} is beyond the device's maxBoundDescriptorSets of {}",
                                     job.descriptor_set, limits.maxBoundDescriptorSets),
                         "descriptor_set");
    }
    if (!job.uniform_data.empty() && job.uniform_binding == job.texture_binding) {
        return job_error(fmt::format("uniform buffer and texture cannot share binding {}", job.uniform_binding),
                         "uniform_binding");
    }
    std::vector<detail::BindingUse> uses{{job.texture_binding, "texture_binding"}};
    if (!job.uniform_data.empty()) uses.push_back({job.uniform_binding, "uniform_binding"});
    for (size_t i = 0; i < job.textures.size(); ++i) {
        uses.push_back({job.textures[i].binding, detail::texture_field(i, "binding")});
    }
    if (auto s = detail::check_distinct_bindings(uses); !s.ok()) return s;
    const uint64_t samplers = job.textures.size() + 1;
    const uint32_t sampler_limit =
        std::min({limits.maxPerStageDescriptorSamplers, limits.maxPerStageDescriptorSampledImages,
                  limits.maxDescriptorSetSamplers, limits.maxDescriptorSetSampledImages});
    if (samplers > sampler_limit) {
        return job_error(fmt::format("the job binds {} textures, over the device's limit of {} per stage and set",
                                     samplers, sampler_limit),
                         "textures");
    }
    if (job.uniform_data.size() > limits.maxUniformBufferRange) {
        return job_error(fmt::format("uniform data is {} bytes, over the device's maxUniformBufferRange of {}",
                                     job.uniform_data.size(), limits.maxUniformBufferRange),
                         "uniform_data");
    }
    return Ok{};
}

bool provides_texture(const RenderJob& job, uint32_t binding) {
    if (binding == job.texture_binding) return true;
    return std::any_of(job.textures.begin(), job.textures.end(),
                       [binding](const TextureInput& t) { return t.binding == binding; });
}

// "1" or "1, 3, 4": the input's binding, then the extra textures'.
std::string texture_bindings(const RenderJob& job) {
    std::string out = std::to_string(job.texture_binding);
    for (const TextureInput& t : job.textures) out += ", " + std::to_string(t.binding);
    return out;
}

// Every descriptor the module declares must be one the job provides, of the matching kind.
Status check_resources(const SpirvInterface& module, const char* what, const RenderJob& job) {
    for (const SpirvResource& r : module.resources) {
        const std::string label = fmt::format("{} '{}' (set {}, binding {})", resource_kind_name(r.kind), r.name,
                                              r.set, r.binding);
        if (r.set != job.descriptor_set) {
            return job_error(fmt::format("{} uses {}, but the job binds its resources in set {}", what, label,
                                         job.descriptor_set),
                             "descriptor_set");
        }
        if (r.array_size != 1) {
            return job_error(fmt::format("{} declares {} as an array of descriptors; the engine binds single ones",
                                         what, label),
                             "descriptor_set");
        }
        if (r.kind == SpirvResourceKind::CombinedImageSampler && provides_texture(job, r.binding)) continue;
        if (r.binding == job.uniform_binding && r.kind == SpirvResourceKind::UniformBuffer) {
            if (job.uniform_data.empty()) {
                return job_error(fmt::format("{} declares {} but the job has no uniform data", what, label),
                                 "uniform_data");
            }
            if (r.block_bytes > job.uniform_data.size()) {
                return job_error(fmt::format("{} reads {} bytes of {} but the job's uniform data has only {}", what,
                                             r.block_bytes, label, job.uniform_data.size()),
                                 "uniform_data");
            }
            continue;
        }
        return job_error(fmt::format("{} uses {}, which the job does not provide (it binds a uniform buffer at {} "
                                     "and combined image samplers at {})",
                                     what, label, job.uniform_binding, texture_bindings(job)),
                         r.binding == job.uniform_binding ? "uniform_binding" : "texture_binding");
    }
    return Ok{};
}

Status check_module(const std::vector<uint32_t>& spirv, ExecutionModel model, const RenderJob& job) {
    const bool vertex = model == ExecutionModel::Vertex;
    const char* what = vertex ? "vertex shader" : "fragment shader";
    const char* field = vertex ? "vertex_spirv" : "fragment_spirv";

    auto inspected = inspect_spirv(spirv, what);
    if (!inspected) return make_error(inspected.error().message, {}, 0, fmt::format("job.{}", field));
    const SpirvInterface& module = inspected.value();

    if (!has_entry_point(module, model, "main")) {
        std::string found;
        for (const auto& e : module.entry_points) found += (found.empty() ? "'" : ", '") + e.name + "'";
        return job_error(fmt::format("{} has no {} entry point named 'main' (entry points: {})", what,
                                     vertex ? "Vertex" : "Fragment", found.empty() ? "none" : found),
                         field);
    }
    if (module.push_constants) {
        return job_error(fmt::format("{} uses push constants; the engine passes parameters in a uniform block", what),
                         field);
    }
    if (vertex && module.user_inputs) {
        return job_error("vertex shader reads vertex attributes; the engine binds no vertex buffers "
                         "(derive positions from gl_VertexIndex)",
                         field);
    }
    return check_resources(module, what, job);
}

// The one format choice for the input and every extra texture: full float where the device can
// sample (and filter) it; half float, which every Vulkan device can filter, otherwise. A mip
// chain is made by linear blits: it needs blits and linear filtering whatever the pass's filter.
// `field` names the filter that could not be met.
// An 8-bit picture with a mip chain keeps its chain in 8 bits, as RetroArch's (RenderJob::unorm8).
Result<TexturePlan> pick_texture_format(const VulkanContext& context, SamplerFilter filter, bool mipmap, bool unorm8,
                                        const std::string& field) {
    VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    if (filter == SamplerFilter::Linear || mipmap) needed |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    if (mipmap) needed |= VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT;
    if (mipmap && unorm8 && (context.optimal_tiling_features(VK_FORMAT_R8G8B8A8_UNORM) & needed) == needed) {
        return TexturePlan{VK_FORMAT_R8G8B8A8_UNORM, TextureTexels::Rgba8Unorm};
    }
    if ((context.optimal_tiling_features(VK_FORMAT_R32G32B32A32_SFLOAT) & needed) == needed) {
        return TexturePlan{VK_FORMAT_R32G32B32A32_SFLOAT, TextureTexels::Rgba32Float};
    }
    if ((context.optimal_tiling_features(VK_FORMAT_R16G16B16A16_SFLOAT) & needed) == needed) {
        return TexturePlan{VK_FORMAT_R16G16B16A16_SFLOAT, TextureTexels::Rgba16Float};
    }
    return job_error(fmt::format("device '{}' cannot sample an RGBA32F or RGBA16F texture with this filter{}",
                                 context.info().name, mipmap ? " and make its mip chain (linear blits)" : ""),
                     field);
}

}  // namespace

VkFormat output_vk_format(OutputFormat format) {
    switch (format) {
        case OutputFormat::Rgba8Unorm: return VK_FORMAT_R8G8B8A8_UNORM;
        case OutputFormat::Rgba8Srgb: return VK_FORMAT_R8G8B8A8_SRGB;
        case OutputFormat::Rgba16Float: return VK_FORMAT_R16G16B16A16_SFLOAT;
        case OutputFormat::Rgba32Float: return VK_FORMAT_R32G32B32A32_SFLOAT;
        case OutputFormat::Rgb10A2Unorm: return VK_FORMAT_A2B10G10R10_UNORM_PACK32;
        case OutputFormat::R16Float: return VK_FORMAT_R16_SFLOAT;
        case OutputFormat::Rg16Float: return VK_FORMAT_R16G16_SFLOAT;
    }
    return VK_FORMAT_UNDEFINED;
}

Result<JobPlan> check_job(const VulkanContext& context, const RenderJob& job) {
    if (auto s = check_size(context, job); !s) return s.error();
    if (auto s = check_bindings(context, job); !s) return s.error();
    if (auto s = check_module(job.vertex_spirv, ExecutionModel::Vertex, job); !s) return s.error();
    if (auto s = check_module(job.fragment_spirv, ExecutionModel::Fragment, job); !s) return s.error();

    JobPlan plan;
    plan.output_format = output_vk_format(job.format);
    const VkFormatFeatureFlags target_needs = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT;
    if (plan.output_format == VK_FORMAT_UNDEFINED ||
        (context.optimal_tiling_features(plan.output_format) & target_needs) != target_needs) {
        return job_error(fmt::format("device '{}' cannot render to {}", context.info().name,
                                     output_format_name(job.format)),
                         "format");
    }
    auto input = pick_texture_format(context, job.filter, job.mipmap, job.unorm8, "filter");
    if (!input) return input.error();
    plan.textures.push_back(input.value());
    for (size_t i = 0; i < job.textures.size(); ++i) {
        auto texture = pick_texture_format(context, job.textures[i].filter, job.textures[i].mipmap, job.textures[i].unorm8,
                                           detail::texture_field(i, "filter"));
        if (!texture) return texture.error();
        plan.textures.push_back(texture.value());
    }
    return plan;
}

}  // namespace crtforge::vulkan
