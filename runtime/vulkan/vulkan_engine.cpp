// The Vulkan RenderEngine: check the job, create its objects, run the one command buffer, read
// the target back. The instance and device (VulkanContext) live as long as the engine, and so do
// the textures it has uploaded from shared images (TextureCache) and the passes it has built
// (GraphicsPassCache); everything else lives for one render() or time_draws() call.

#include <algorithm>
#include <cstring>
#include <exception>
#include <optional>
#include <vector>

#include <fmt/core.h>

#include "crtforge/runtime/render_engine.hpp"
#include "runtime/vulkan/job_validation.hpp"
#include "runtime/common/pixel_conversion.hpp"
#include "runtime/vulkan/vulkan_check.hpp"
#include "runtime/vulkan/vulkan_commands.hpp"
#include "runtime/vulkan/vulkan_context.hpp"
#include "runtime/vulkan/vulkan_pipeline.hpp"
#include "runtime/vulkan/vulkan_resources.hpp"
#include "runtime/vulkan/vulkan_texture_cache.hpp"

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

// Every texture, the input too, comes through `cache`. Without `read_back` (a target kept on the
// device) there is no read-back buffer.
Result<JobResources> create_job_resources(const VulkanContext& context, const RenderJob& job, const JobPlan& plan,
                                          TextureCache& cache, bool read_back) {
    JobResources out;

    out.textures.reserve(job.textures.size() + 1);
    for (size_t i = 0; i <= job.textures.size(); ++i) {
        const TexturePlan& format = plan.textures[i];
        const bool mipmap = i == 0 ? job.mipmap : job.textures[i - 1].mipmap;
        auto texels = cache.get(context, i == 0 ? job.input : job.textures[i - 1].image, format.format, format.texels, mipmap);
        if (!texels) return texels.error();
        const SamplerFilter filter = i == 0 ? job.filter : job.textures[i - 1].filter;
        const WrapMode wrap = i == 0 ? job.wrap : job.textures[i - 1].wrap;
        const uint32_t binding = i == 0 ? job.texture_binding : job.textures[i - 1].binding;
        const SamplerFilter mip_filter = i == 0 ? job.mip_filter : job.textures[i - 1].mip_filter;
        auto texture = create_sampled_texture(context, std::move(texels).value(), filter, wrap, mip_filter, binding);
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
    if (!read_back) return out;

    const VkDeviceSize readback_bytes = VkDeviceSize{width} * height * texel_bytes(job.format);
    auto readback = create_host_buffer(context, readback_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    if (!readback) return readback.error();
    out.readback = std::move(readback).value();
    return out;
}

class VulkanEngine final : public RenderEngine {
public:
    explicit VulkanEngine(std::shared_ptr<VulkanContext> context) : context_(std::move(context)) {}

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

    Result<std::vector<std::vector<double>>> time_draws(const std::vector<TimedJob>& jobs, int draws) override {
        try {
            if (draws < 1 || draws > 100000) return make_error(fmt::format("draws must be 1..100000; got {}", draws), {}, 0, "draws");
            context_->take_validation_messages();
            if (!has_timestamps()) return make_error("the device's graphics queue has no timestamps: it cannot time draws");
            auto ns = time_prepared(jobs, draws);
            if (auto messages = context_->take_validation_messages(); !messages.empty())
                return validation_failure("while timing", messages);
            return ns;
        } catch (const std::exception& e) {
            return make_error(fmt::format("timing failed: {}", e.what()));
        }
    }

private:
    // Everything one job's draws need, built once: a job timed many times compiles its pipeline and
    // uploads its textures once. Held by pointer: `commands` refers into the rest.
    struct PreparedJob {
        JobResources resources;
        std::shared_ptr<const GraphicsPass> pass;
        UniqueFramebuffer framebuffer;
        DescriptorSet descriptors;
        std::optional<PassCommands> commands;
    };

    Result<std::unique_ptr<PreparedJob>> prepare(const RenderJob& job, const JobPlan& plan, bool read_back = true) {
        const VulkanContext& context = *context_;
        auto resources = create_job_resources(context, job, plan, textures_, read_back);
        if (!resources) return resources.error();
        auto pass = passes_.get(context, job, plan.output_format);
        if (!pass) return pass.error();
        auto out = std::make_unique<PreparedJob>(PreparedJob{std::move(resources).value(), std::move(pass).value(), {}, {}, {}});
        auto framebuffer = create_framebuffer(context, out->pass->render_pass.get(), out->resources.target);
        if (!framebuffer) return framebuffer.error();
        out->framebuffer = std::move(framebuffer).value();
        const JobResources& r = out->resources;
        auto descriptors = create_descriptor_set(context, *out->pass, job, r.uniforms ? &*r.uniforms : nullptr, r.textures);
        if (!descriptors) return descriptors.error();
        out->descriptors = std::move(descriptors).value();
        out->commands.emplace(PassCommands{r.textures, *out->pass, out->framebuffer.get(), out->descriptors.set,
                                           job.descriptor_set, r.target, r.readback, job.clear_color});
        return out;
    }

    bool has_timestamps() const {
        uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(context_->physical_device(), &families, nullptr);
        std::vector<VkQueueFamilyProperties> properties(families);
        vkGetPhysicalDeviceQueueFamilyProperties(context_->physical_device(), &families, properties.data());
        return context_->queue_family() < families && properties[context_->queue_family()].timestampValidBits != 0;
    }

    // Every job built and uploaded once; then rounds: in each, every job with timings left is timed
    // once, in the given order (so a pass and its baseline alternate).
    Result<std::vector<std::vector<double>>> time_prepared(const std::vector<TimedJob>& jobs, int draws) {
        const VulkanContext& context = *context_;
        std::vector<std::unique_ptr<PreparedJob>> prepared;
        int rounds = 0;
        for (size_t i = 0; i < jobs.size(); ++i) {
            if (!jobs[i].job || jobs[i].timings < 1)
                return make_error(fmt::format("timed job {} has no job or no timings", i), {}, 0, "jobs");
            auto plan = check_job(context, *jobs[i].job);
            if (!plan) return plan.error();
            auto job = prepare(*jobs[i].job, plan.value());
            if (!job) return job.error();
            prepared.push_back(std::move(job).value());
            rounds = std::max(rounds, jobs[i].timings);
        }
        if (auto s = submit_and_wait(context, [&](VkCommandBuffer cb) { for (auto& p : prepared) record_uploads(cb, *p->commands); }); !s)
            return s.error();
        for (auto& p : prepared) mark_uploaded(p->resources);

        VkQueryPoolCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
        info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        info.queryCount = 2;
        VkQueryPool queries = VK_NULL_HANDLE;
        if (VkResult res = vkCreateQueryPool(context.device(), &info, nullptr, &queries); res != VK_SUCCESS)
            return vk_error("vkCreateQueryPool", res);
        struct PoolGuard {
            VkDevice device;
            VkQueryPool pool;
            ~PoolGuard() { vkDestroyQueryPool(device, pool, nullptr); }
        } guard{context.device(), queries};

        std::vector<std::vector<double>> out(jobs.size());
        for (int round = 0; round < rounds; ++round) {
            for (size_t i = 0; i < jobs.size(); ++i) {
                if (round >= jobs[i].timings) continue;
                auto record = [&](VkCommandBuffer cb) { record_timed_draws(cb, *prepared[i]->commands, queries, draws); };
                if (auto s = submit_and_wait(context, record); !s) return s.error();
                uint64_t stamps[2] = {0, 0};
                if (VkResult res = vkGetQueryPoolResults(context.device(), queries, 0, 2, sizeof stamps, stamps, sizeof(uint64_t),
                                                         VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
                    res != VK_SUCCESS)
                    return vk_error("vkGetQueryPoolResults", res);
                out[i].push_back(static_cast<double>(stamps[1] - stamps[0]) * context.limits().timestampPeriod / draws);
            }
        }
        return out;
    }

    // The render: uploads, the draw, the readback (or the target kept, RenderJob::keep_on_device).
    Result<Image> run(const RenderJob& job, const JobPlan& plan) {
        const bool keep = job.keep_on_device && can_keep_target(*context_, job.format);
        auto prepared = prepare(job, plan, !keep);
        if (!prepared) return prepared.error();
        const PassCommands& commands = *prepared.value()->commands;
        if (auto s = submit_and_wait(*context_, [&](VkCommandBuffer cb) { record_pass(cb, commands); }); !s) return s.error();
        mark_uploaded(prepared.value()->resources);
        if (keep) {
            auto kept = std::make_shared<KeptTarget>();
            kept->context = context_;
            kept->image = std::move(prepared.value()->resources.target);
            Image out;
            out.width = job.width;
            out.height = job.height;
            out.device = std::move(kept);
            return out;
        }
        const HostBuffer& readback = prepared.value()->resources.readback;
        if (auto s = invalidate(*context_, readback); !s) return s.error();
        return read_texels(readback.mapped, job.width, job.height, job.format);
    }

    static void mark_uploaded(JobResources& resources) {
        for (SampledTexture& texture : resources.textures) texture.texels->mark_uploaded();
    }

    std::shared_ptr<VulkanContext> context_;  // shared with the targets it keeps (KeptTarget)
    TextureCache textures_{VkDeviceSize{1} << 30};  // 1 GiB of uploaded textures
    GraphicsPassCache passes_{128};
};

}  // namespace
}  // namespace vulkan

Result<std::unique_ptr<RenderEngine>> create_vulkan_engine(const EngineOptions& options) {
    try {
        auto context = vulkan::VulkanContext::create(options);
        if (!context) return context.error();
        return std::unique_ptr<RenderEngine>(
            std::make_unique<vulkan::VulkanEngine>(std::shared_ptr<vulkan::VulkanContext>(std::move(context).value())));
    } catch (const std::exception& e) {
        return make_error(fmt::format("creating the Vulkan engine failed: {}", e.what()));
    }
}

}  // namespace crtforge
