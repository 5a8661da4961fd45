#include "runtime/vulkan/vulkan_pipeline.hpp"

#include <array>
#include <vector>

#include "runtime/vulkan/vulkan_check.hpp"

namespace crtforge::vulkan {
namespace {

Result<UniqueShaderModule> create_shader_module(VkDevice device, const std::vector<uint32_t>& spirv) {
    VkShaderModuleCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    info.codeSize = spirv.size() * sizeof(uint32_t);
    info.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    if (VkResult r = vkCreateShaderModule(device, &info, nullptr, &module); r != VK_SUCCESS) {
        return vk_error("vkCreateShaderModule", r);
    }
    return UniqueShaderModule(device, module);
}

Result<UniqueRenderPass> create_render_pass(VkDevice device, VkFormat format) {
    VkAttachmentDescription color{};
    color.format = format;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // defined contents even where a shader discards
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    color.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;  // ready for vkCmdCopyImageToBuffer

    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;

    // The implicit dependency out of the subpass only reaches BOTTOM_OF_PIPE with no access, which
    // does not order the colour writes before the readback copy; this one does.
    VkSubpassDependency to_copy{};
    to_copy.srcSubpass = 0;
    to_copy.dstSubpass = VK_SUBPASS_EXTERNAL;
    to_copy.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    to_copy.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    to_copy.dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    to_copy.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;

    VkRenderPassCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    info.attachmentCount = 1;
    info.pAttachments = &color;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 1;
    info.pDependencies = &to_copy;
    VkRenderPass pass = VK_NULL_HANDLE;
    if (VkResult r = vkCreateRenderPass(device, &info, nullptr, &pass); r != VK_SUCCESS) {
        return vk_error("vkCreateRenderPass", r);
    }
    return UniqueRenderPass(device, pass);
}

Result<UniqueDescriptorSetLayout> create_set_layout(VkDevice device, const std::vector<VkDescriptorSetLayoutBinding>& bindings) {
    VkDescriptorSetLayoutCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    info.bindingCount = static_cast<uint32_t>(bindings.size());
    info.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    if (VkResult r = vkCreateDescriptorSetLayout(device, &info, nullptr, &layout); r != VK_SUCCESS) {
        return vk_error("vkCreateDescriptorSetLayout", r);
    }
    return UniqueDescriptorSetLayout(device, layout);
}

// The job's set plus empty layouts for the set numbers below it: Vulkan 1.0 pipeline layouts
// cannot have holes.
Status create_layouts(VkDevice device, const RenderJob& job, GraphicsPass& pass) {
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    if (!job.uniform_data.empty()) {
        bindings.push_back({job.uniform_binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, stages, nullptr});
    }
    bindings.push_back({job.texture_binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stages, nullptr});
    for (const TextureInput& texture : job.textures) {
        bindings.push_back({texture.binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stages, nullptr});
    }
    auto set_layout = create_set_layout(device, bindings);
    if (!set_layout) return set_layout.error();
    pass.set_layout = std::move(set_layout).value();

    std::vector<VkDescriptorSetLayout> sets;
    if (job.descriptor_set > 0) {
        auto empty = create_set_layout(device, {});
        if (!empty) return empty.error();
        pass.empty_set_layout = std::move(empty).value();
        sets.assign(job.descriptor_set, pass.empty_set_layout.get());
    }
    sets.push_back(pass.set_layout.get());

    VkPipelineLayoutCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    info.setLayoutCount = static_cast<uint32_t>(sets.size());
    info.pSetLayouts = sets.data();
    VkPipelineLayout layout = VK_NULL_HANDLE;
    if (VkResult r = vkCreatePipelineLayout(device, &info, nullptr, &layout); r != VK_SUCCESS) {
        return vk_error("vkCreatePipelineLayout", r);
    }
    pass.pipeline_layout = UniquePipelineLayout(device, layout);
    return Ok{};
}

Result<UniquePipeline> create_pipeline(VkDevice device, const RenderJob& job, const GraphicsPass& pass) {
    auto vertex = create_shader_module(device, job.vertex_spirv);
    if (!vertex) return vertex.error();
    auto fragment = create_shader_module(device, job.fragment_spirv);
    if (!fragment) return fragment.error();

    std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
    stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vertex.value().get();
    stages[0].pName = "main";
    stages[1] = stages[0];
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fragment.value().get();

    // No vertex buffers: the vertex shader derives the full-screen triangle from gl_VertexIndex.
    VkPipelineVertexInputStateCreateInfo vertex_input{};
    vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;

    VkPipelineInputAssemblyStateCreateInfo assembly{};
    assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;

    // Standard Vulkan viewport: NDC y = -1 lands on its top row (framebuffer rows count down from
    // the top), so a shader that maps NDC y = -1 to v = 0 reproduces the input the right way up.
    // The job's viewport is in the same top-down pixels; the scissor keeps the draw inside it.
    const Viewport area = job.viewport.full() ? Viewport{0, 0, job.width, job.height} : job.viewport;
    VkViewport viewport{static_cast<float>(area.x), static_cast<float>(area.y), static_cast<float>(area.width),
                        static_cast<float>(area.height), 0.0f, 1.0f};
    if (job.clip_y_up) {  // D3D's clip space: NDC y = +1 on the top row (maintenance1's negative height)
        viewport.y = static_cast<float>(area.y + area.height);
        viewport.height = -static_cast<float>(area.height);
    }
    VkRect2D scissor{{area.x, area.y}, {static_cast<uint32_t>(area.width), static_cast<uint32_t>(area.height)}};
    VkPipelineViewportStateCreateInfo viewport_state{};
    viewport_state.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    viewport_state.viewportCount = 1;
    viewport_state.pViewports = &viewport;
    viewport_state.scissorCount = 1;
    viewport_state.pScissors = &scissor;

    VkPipelineRasterizationStateCreateInfo raster{};
    raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;  // the winding of the full-screen triangle does not matter
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;

    VkPipelineMultisampleStateCreateInfo multisample{};
    multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;

    VkPipelineColorBlendAttachmentState blend_attachment{};
    blend_attachment.blendEnable = VK_FALSE;  // the shader's output is the result, alpha included
    blend_attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                      VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    VkPipelineColorBlendStateCreateInfo blend{};
    blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    blend.attachmentCount = 1;
    blend.pAttachments = &blend_attachment;

    VkGraphicsPipelineCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    info.stageCount = static_cast<uint32_t>(stages.size());
    info.pStages = stages.data();
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport_state;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pColorBlendState = &blend;
    info.layout = pass.pipeline_layout.get();
    info.renderPass = pass.render_pass.get();
    info.subpass = 0;
    VkPipeline pipeline = VK_NULL_HANDLE;
    if (VkResult r = vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline); r != VK_SUCCESS) {
        return vk_error("vkCreateGraphicsPipelines", r);
    }
    return UniquePipeline(device, pipeline);
    // The shader modules are released here; a built pipeline no longer needs them.
}

}  // namespace

Result<GraphicsPass> create_graphics_pass(const VulkanContext& context, const RenderJob& job, VkFormat color_format) {
    const VkDevice device = context.device();
    GraphicsPass pass;
    auto render_pass = create_render_pass(device, color_format);
    if (!render_pass) return render_pass.error();
    pass.render_pass = std::move(render_pass).value();

    if (auto layouts = create_layouts(device, job, pass); !layouts) return layouts.error();

    auto pipeline = create_pipeline(device, job, pass);
    if (!pipeline) return pipeline.error();
    pass.pipeline = std::move(pipeline).value();
    return pass;
}

namespace {

// Everything of the job and format that create_graphics_pass reads, as bytes.
std::string graphics_pass_key(const RenderJob& job, VkFormat color_format) {
    std::string key;
    auto put = [&](const void* data, size_t size) { key.append(static_cast<const char*>(data), size); };
    auto put_int = [&](int64_t value) { put(&value, sizeof value); };
    put_int(color_format);
    put_int(job.uniform_data.empty() ? -1 : static_cast<int64_t>(job.uniform_binding));
    put_int(job.texture_binding);
    put_int(job.descriptor_set);
    put_int(static_cast<int64_t>(job.textures.size()));
    for (const TextureInput& texture : job.textures) put_int(texture.binding);
    const Viewport area = job.viewport.full() ? Viewport{0, 0, job.width, job.height} : job.viewport;
    for (int v : {area.x, area.y, area.width, area.height}) put_int(v);
    put_int(job.clip_y_up);
    put_int(static_cast<int64_t>(job.vertex_spirv.size()));
    put(job.vertex_spirv.data(), job.vertex_spirv.size() * sizeof(uint32_t));
    put(job.fragment_spirv.data(), job.fragment_spirv.size() * sizeof(uint32_t));
    return key;
}

}  // namespace

Result<std::shared_ptr<const GraphicsPass>> GraphicsPassCache::get(const VulkanContext& context, const RenderJob& job,
                                                                   VkFormat color_format) {
    std::string key = graphics_pass_key(job, color_format);
    const size_t hash = std::hash<std::string>{}(key);
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
        if (it->hash != hash || it->key != key) continue;
        entries_.splice(entries_.begin(), entries_, it);
        return entries_.front().pass;
    }
    auto pass = create_graphics_pass(context, job, color_format);
    if (!pass) return pass.error();
    auto shared = std::make_shared<const GraphicsPass>(std::move(pass).value());
    entries_.push_front({hash, std::move(key), shared});
    if (entries_.size() > capacity_) entries_.pop_back();
    return shared;
}

Result<UniqueFramebuffer> create_framebuffer(const VulkanContext& context, VkRenderPass render_pass,
                                             const DeviceImage& target) {
    VkImageView view = target.view.get();
    VkFramebufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    info.renderPass = render_pass;
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = target.extent.width;
    info.height = target.extent.height;
    info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    if (VkResult r = vkCreateFramebuffer(context.device(), &info, nullptr, &framebuffer); r != VK_SUCCESS) {
        return vk_error("vkCreateFramebuffer", r);
    }
    return UniqueFramebuffer(context.device(), framebuffer);
}

Result<DescriptorSet> create_descriptor_set(const VulkanContext& context, const GraphicsPass& pass,
                                            const RenderJob& job, const HostBuffer* uniforms,
                                            const std::vector<SampledTexture>& textures) {
    const VkDevice device = context.device();
    std::vector<VkDescriptorPoolSize> sizes{
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, static_cast<uint32_t>(textures.size())}};
    if (uniforms) sizes.push_back({VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1});

    VkDescriptorPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = static_cast<uint32_t>(sizes.size());
    pool_info.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    if (VkResult r = vkCreateDescriptorPool(device, &pool_info, nullptr, &pool); r != VK_SUCCESS) {
        return vk_error("vkCreateDescriptorPool", r);
    }
    DescriptorSet out;
    out.pool = UniqueDescriptorPool(device, pool);

    VkDescriptorSetLayout layout = pass.set_layout.get();
    VkDescriptorSetAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &layout;
    if (VkResult r = vkAllocateDescriptorSets(device, &alloc, &out.set); r != VK_SUCCESS) {
        return vk_error("vkAllocateDescriptorSets", r);
    }

    // Sized up front: the writes point into it.
    std::vector<VkDescriptorImageInfo> images;
    images.reserve(textures.size());
    std::vector<VkWriteDescriptorSet> writes;
    for (const SampledTexture& texture : textures) {
        images.push_back({texture.sampler.get(), texture.texels->image.view.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
        VkWriteDescriptorSet write{};
        write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        write.dstSet = out.set;
        write.dstBinding = texture.binding;
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        write.pImageInfo = &images.back();
        writes.push_back(write);
    }
    VkDescriptorBufferInfo buffer{};
    if (uniforms) {
        buffer = {uniforms->buffer.get(), 0, uniforms->size};
        VkWriteDescriptorSet write{};
        write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        write.dstSet = out.set;
        write.dstBinding = job.uniform_binding;
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        write.pBufferInfo = &buffer;
        writes.push_back(write);
    }
    vkUpdateDescriptorSets(device, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
    return out;
}

}  // namespace crtforge::vulkan
