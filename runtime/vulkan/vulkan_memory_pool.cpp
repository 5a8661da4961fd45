#include "runtime/vulkan/vulkan_memory_pool.hpp"

#include <utility>

#include <fmt/core.h>

#include "runtime/vulkan/vulkan_check.hpp"

namespace crtforge::vulkan {

PooledMemory::PooledMemory(PooledMemory&& other) noexcept
    : pool_(other.pool_), memory_(std::exchange(other.memory_, VK_NULL_HANDLE)), type_(other.type_), size_(other.size_),
      mapped_(std::exchange(other.mapped_, nullptr)) {}

PooledMemory& PooledMemory::operator=(PooledMemory&& other) noexcept {
    if (this != &other) {
        reset();
        pool_ = other.pool_;
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        type_ = other.type_;
        size_ = other.size_;
        mapped_ = std::exchange(other.mapped_, nullptr);
    }
    return *this;
}

Result<void*> PooledMemory::map() {
    if (!mapped_) {
        if (VkResult r = vkMapMemory(pool_->device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_); r != VK_SUCCESS) {
            mapped_ = nullptr;
            return vk_error("vkMapMemory", r);
        }
    }
    return mapped_;
}

void PooledMemory::reset() {
    if (memory_ == VK_NULL_HANDLE) return;
    pool_->give({type_, size_, memory_, mapped_});
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
}

Result<PooledMemory> MemoryPool::take(uint32_t type, VkDeviceSize size) {
    PooledMemory out;
    out.pool_ = this;
    out.type_ = type;
    out.size_ = size;
    for (auto it = kept_.begin(); it != kept_.end(); ++it) {
        if (it->type != type || it->size != size) continue;
        out.memory_ = it->memory;
        out.mapped_ = it->mapped;
        bytes_ -= it->size;
        kept_.erase(it);
        return out;
    }
    VkMemoryAllocateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    info.allocationSize = size;
    info.memoryTypeIndex = type;
    if (VkResult r = vkAllocateMemory(device_, &info, nullptr, &out.memory_); r != VK_SUCCESS) {
        out.memory_ = VK_NULL_HANDLE;
        return make_error(fmt::format("cannot allocate {} bytes: vkAllocateMemory failed: {}", size, vk_result_name(r)));
    }
    return out;
}

void MemoryPool::give(const Block& block) {
    if (block.size > budget_ / 4) {  // a block near the budget would push out everything else
        vkFreeMemory(device_, block.memory, nullptr);
        return;
    }
    kept_.push_front(block);
    bytes_ += block.size;
    while (bytes_ > budget_) {
        bytes_ -= kept_.back().size;
        vkFreeMemory(device_, kept_.back().memory, nullptr);  // freeing also unmaps
        kept_.pop_back();
    }
}

void MemoryPool::clear() {
    for (const Block& block : kept_) vkFreeMemory(device_, block.memory, nullptr);
    kept_.clear();
    bytes_ = 0;
}

}  // namespace crtforge::vulkan
