// Device memory kept for reuse. A corpus sweep renders thousands of passes whose images and
// buffers come in a few sizes; freeing each job's memory and allocating the next job's made the
// driver (lavapipe's memory is the process's) map fresh pages for every job, and the kernel's page
// faults and zeroing were about a third of a large preset's render. A block goes back to the pool
// when its image or buffer is done, and a request of the same memory type and size takes it again:
// binding a new object at offset 0 of memory of exactly its required size and type is what a new
// allocation would give. Bounded in bytes, the least recently returned freed first. Not
// thread-safe: each VulkanContext has its own, used by the one thread that renders on it.
#pragma once

#include <list>

#include <vulkan/vulkan.h>

#include "crtforge/diagnostic.hpp"

namespace crtforge::vulkan {

class MemoryPool;

// One block of device memory, owned until it goes back to its pool (move-only). A host-visible
// block is mapped once, on first use, and stays mapped while the pool keeps it.
class PooledMemory {
public:
    PooledMemory() = default;
    ~PooledMemory() { reset(); }
    PooledMemory(PooledMemory&& other) noexcept;
    PooledMemory& operator=(PooledMemory&& other) noexcept;
    PooledMemory(const PooledMemory&) = delete;
    PooledMemory& operator=(const PooledMemory&) = delete;

    VkDeviceMemory get() const { return memory_; }
    explicit operator bool() const { return memory_ != VK_NULL_HANDLE; }
    // The whole block mapped (host-visible memory only).
    Result<void*> map();
    void reset();

private:
    friend class MemoryPool;
    MemoryPool* pool_ = nullptr;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    uint32_t type_ = 0;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

class MemoryPool {
public:
    MemoryPool(VkDevice device, VkDeviceSize budget_bytes) : device_(device), budget_(budget_bytes) {}
    ~MemoryPool() { clear(); }
    MemoryPool(const MemoryPool&) = delete;
    MemoryPool& operator=(const MemoryPool&) = delete;

    // `size` bytes of memory type `type`: a kept block of that type and size, else a new one.
    Result<PooledMemory> take(uint32_t type, VkDeviceSize size);
    // Frees every kept block (before the device goes).
    void clear();
    // The bytes of the blocks kept for reuse.
    VkDeviceSize kept_bytes() const { return bytes_; }

private:
    friend class PooledMemory;
    struct Block {
        uint32_t type;
        VkDeviceSize size;
        VkDeviceMemory memory;
        void* mapped;
    };
    void give(const Block& block);

    VkDevice device_;
    const VkDeviceSize budget_;
    VkDeviceSize bytes_ = 0;
    std::list<Block> kept_;  // most recently returned first
};

}  // namespace crtforge::vulkan
