// The Vulkan RenderEngine: check the job, create its objects, run the one command buffer, read
// the target back. The instance and device (VulkanContext) live as long as the engine; everything
// else lives for one render() call.
#include <cstring>
#include <exception>
#include <optional>
#include <vector>

#include <fmt/core.h>

#include "crtforge/runtime/render_engine.hpp"
#include "runtime/vulkan/job_validation.hpp"
#include "runtime/common/pixel_conversion.hpp"
#include "runtime/vulkan/vulkan_commands.hpp"
#include "runtime/vulkan/vulkan_context.hpp"
#include "runtime/vulkan/vulkan_pipeline.hpp"
#include "runtime/vulkan/vulkan_resources.hpp"

namespace crtforge {
namespace vulkan {
namespace {

// The buffers and images of one job, in creation order (destroyed in reverse).
struct JobResources {
    std::vector<SampledTexture> textures;  // [0] the input, then job.textures in order
    std::optional<HostBuffer> uniforms;    // absent when the job has no uniform data
    DeviceImage target;
    HostBuffer readback;
};

Result<JobResources> create_job_resources(const VulkanContext& context, const RenderJob& job, const JobPlan& plan) {
    JobResources out;

    out.textures.reserve(job.textures.size() + 1);
    for (size_t i = 0; i <= job.textures.size(); ++i) {
        const TexturePlan& format = plan.textures[i];
        auto texture = i == 0 ? create_sampled_texture(context, job.input, format.format, format.texels, job.filter,
                                                       job.wrap, job.texture_binding)
                              : create_sampled_texture(context, job.textures[i - 1].image, format.format, format.texels,
                                                       job.textures[i - 1].filter, job.textures[i - 1].wrap,
                                                       job.textures[i - 1].binding);
        if (!texture) return texture.error();
        out.textures.push_back(std::move(texture).value());
    }

    if (!job.uniform_data.empty()) {
        auto uniforms = create_host_buffer(context, job.uniform_data.size(), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
        if (!uniforms) return uniforms.error();
        out.uniforms = std::move(uniforms).value();
        std::memcpy(out.uniforms->mapped, job.uniform_data.data(), job.uniform_data.size());
        if (auto s = flush(context, *out.uniforms); !s) return s.error();
    }

    const auto width = static_cast<uint32_t>(job.width), height = static_cast<uint32_t>(job.height);
    auto target = create_device_image(context, plan.output_format, width, height,
                                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    if (!target) return target.error();
    out.target = std::move(target).value();

    const VkDeviceSize readback_bytes = VkDeviceSize{width} * height * texel_bytes(job.format);
    auto readback = create_host_buffer(context, readback_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    if (!readback) return readback.error();
    out.readback = std::move(readback).value();
    return out;
}

class VulkanEngine final : public RenderEngine {
public:
    explicit VulkanEngine(std::unique_ptr<VulkanContext> context) : context_(std::move(context)) {}

    const DeviceInfo& device() const override { return context_->info(); }

    Result<Image> render(const RenderJob& job) override {
        try {
            context_->take_validation_messages();  // start each job with a clean slate
            auto plan = check_job(*context_, job);
            if (!plan) return plan.error();
            auto image = run(job, plan.value());
            // Checked after run() returns, so messages about destroying the job's objects count too.
            // They take precedence over a failed call's bare VkResult: they say what was wrong.
            if (auto messages = context_->take_validation_messages(); !messages.empty()) {
                return validation_failure("while rendering", messages);
            }
            return image;
        } catch (const std::exception& e) {  // bad_alloc on a huge job: errors are values here
            return make_error(fmt::format("render failed: {}", e.what()));
        }
    }

private:
    Result<Image> run(const RenderJob& job, const JobPlan& plan) {
        const VulkanContext& context = *context_;
        auto resources = create_job_resources(context, job, plan);
        if (!resources) return resources.error();
        const JobResources& r = resources.value();

        auto pass = create_graphics_pass(context, job, plan.output_format);
        if (!pass) return pass.error();
        auto framebuffer = create_framebuffer(context, pass.value().render_pass.get(), r.target);
        if (!framebuffer) return framebuffer.error();
        auto descriptors =
            create_descriptor_set(context, pass.value(), job, r.uniforms ? &*r.uniforms : nullptr, r.textures);
        if (!descriptors) return descriptors.error();

        const PassCommands commands{r.textures,
                                    pass.value(),
                                    framebuffer.value().get(),
                                    descriptors.value().set,
                                    job.descriptor_set,
                                    r.target,
                                    r.readback,
                                    job.clear_color};
        if (auto s = submit_and_wait(context, [&](VkCommandBuffer cb) { record_pass(cb, commands); }); !s) {
            return s.error();
        }
        if (auto s = invalidate(context, r.readback); !s) return s.error();
        return read_texels(r.readback.mapped, job.width, job.height, job.format);
    }

    std::unique_ptr<VulkanContext> context_;
};

}  // namespace
}  // namespace vulkan

Result<std::unique_ptr<RenderEngine>> create_vulkan_engine(const EngineOptions& options) {
    try {
        auto context = vulkan::VulkanContext::create(options);
        if (!context) return context.error();
        return std::unique_ptr<RenderEngine>(std::make_unique<vulkan::VulkanEngine>(std::move(context).value()));
    } catch (const std::exception& e) {
        return make_error(fmt::format("creating the Vulkan engine failed: {}", e.what()));
    }
}

}  // namespace crtforge
