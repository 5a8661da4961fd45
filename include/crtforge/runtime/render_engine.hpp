// The render engine: runs one full-screen pass of a SPIR-V vertex + fragment pair over an input
// image and reads the result back as floats. The Vulkan implementation is the harness that proves
// every generated shader on a real driver (Mesa lavapipe by default, any Vulkan GPU by choice).
//
// Lifecycle (the GPU work sits behind this interface so callers can be tested with a stub):
//   1. create  — create_vulkan_engine() opens an instance and one device; it fails with a one-line
//                Diagnostic (missing driver, missing validation layer, no matching device).
//   2. render  — render(job) any number of times, one job at a time (not thread-safe: use one
//                engine per thread). The instance and device are reused; everything a job needs
//                (pipeline, images, buffers) is created for that call and destroyed before it
//                returns, so a failed job leaves the engine usable for the next one.
//   3. destroy — the destructor waits for the device and releases it.
// No exception escapes any of these calls; every failure is a Result error.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/image.hpp"

namespace crtforge {

// Format of the offscreen colour target the fragment shader writes.
enum class OutputFormat {
    Rgba8Unorm,   // bytes; read back as byte / 255 (values are clamped to [0, 1] by the hardware)
    Rgba8Srgb,    // bytes stored sRGB-encoded by the hardware; read back DECODED to linear, i.e.
                  // the value the shader wrote, quantised to the sRGB byte grid
    Rgba16Float,  // half floats; read back exactly (HDR values above 1.0 survive)
    Rgba32Float,  // floats; read back exactly
    Rgb10A2Unorm, // 10 bits a colour channel, 2 for alpha (packed in 32 bits); read back as n / 1023, n / 3
    R16Float,     // one half float; read back as (r, 0, 0, 1)
    Rg16Float,    // two half floats; read back as (r, g, 0, 1)
};

enum class SamplerFilter { Nearest, Linear };

// Texture addressing outside [0, 1], on both axes (Vulkan CLAMP_TO_EDGE / REPEAT /
// MIRRORED_REPEAT / CLAMP_TO_BORDER, GL the same, WebGPU clamp-to-edge / repeat / mirror-repeat).
// ClampToBorder reads transparent black outside the texture (RetroArch's default wrap); WebGPU has
// no border colour, so the Dawn engine refuses it.
enum class WrapMode { ClampToEdge, Repeat, MirroredRepeat, ClampToBorder };

// A texture a pass reads besides its main input (a previous pass's output, a lookup table, ...).
// Uploaded exactly as the main input is (RGBA32F, or RGBA16F where the device cannot filter
// RGBA32F with a Linear filter), with its own filter and wrap mode and, with `mipmap`, a mip chain
// (below).
struct TextureInput {
    std::string name;              // the sampler2D's name in the shader: the GL engine binds by name
    uint32_t binding = 0;          // the Vulkan descriptor binding of the combined image sampler (in
                                   // the job's descriptor_set), and the WGSL texture_2d<f32> binding
    uint32_t sampler_binding = 0;  // the WGSL sampler binding (Dawn only; ignored elsewhere)
    SharedImage image;             // empty = a 1x1 transparent-black texture
    SamplerFilter filter = SamplerFilter::Linear;
    WrapMode wrap = WrapMode::ClampToEdge;
    bool mipmap = false;
    SamplerFilter mip_filter = SamplerFilter::Linear;
    bool unorm8 = false;  // an 8-bit picture: its mip chain is made and kept in 8 bits (below)
};

// The rectangle of the target the full-screen triangle covers, in pixels with the origin at the
// TOP-left of the output and rows going down; outside it the target keeps the clear colour.
// Inside it, texture coordinate (0, 0) is the viewport's top-left and vTexCoord spans 0..1 over
// the viewport: exactly a viewport-sized render pasted at (x, y). 0x0 = the whole target.
struct Viewport {
    int x = 0, y = 0, width = 0, height = 0;
    bool full() const { return width == 0 && height == 0; }
};

// One full-screen pass. Conventions shared with the generator:
//  - the vertex shader draws a full-screen triangle from gl_VertexIndex (vkCmdDraw(3), no vertex
//    buffers) and the fragment shader writes location 0;
//  - texture coordinate (0, 0) is the top-left of `input` (of every texture), and output row 0 is
//    the top row;
//  - both modules use the entry point "main".
// What the shader sees: in `descriptor_set`, the uniform block at uniform_binding (when
// uniform_data is given), `input` as a combined image sampler at texture_binding and each of
// `textures` as one at its own binding; the target, cleared to clear_color, is drawn only inside
// `viewport` (gl_FragCoord stays in target pixels: derive coordinates from vTexCoord).
struct RenderJob {
    std::vector<uint32_t> vertex_spirv, fragment_spirv;
    // Uploaded as an RGBA32F sampled texture (RGBA16F where the device cannot sample/filter
    // RGBA32F), addressed by `wrap` (clamp-to-edge by default). An empty image binds a 1x1
    // transparent-black texture, for shaders that sample nothing. Shared as `textures` are: the
    // engine uploads a picture it has seen before (an earlier pass's input or texture) once.
    SharedImage input;
    SamplerFilter filter = SamplerFilter::Linear;
    WrapMode wrap = WrapMode::ClampToEdge;
    // A mip chain, as RetroArch's Vulkan driver builds one for `mipmap_input` and `NAME_mipmap`:
    // floor(log2(max(w, h))) + 1 levels, level i max(1, size >> i), each a linear blit of the level
    // above; sampled with the hardware's level of detail, the levels blended as `mip_filter` says
    // (Linear: the two nearest levels weighed; Nearest: the nearest level). Without it the texture
    // has one level. The same two fields on each TextureInput.
    bool mipmap = false;
    SamplerFilter mip_filter = SamplerFilter::Linear;
    // The picture holds 8-bit values (byte / 255: an rgba8 pass's output, a LUT decoded from a PNG).
    // With `mipmap` it is then uploaded as R8G8B8A8_UNORM, so each level of its chain is rounded to
    // 8 bits as RetroArch's chains of its R8G8B8A8_UNORM framebuffers and LUTs are (a float chain
    // keeps what RetroArch's rounds away: a shader reading a 2x1 level for the picture's average
    // brightness sees the difference). Without `mipmap` it changes nothing. The same on each
    // TextureInput.
    bool unorm8 = false;
    // More textures, each a combined image sampler at its own binding in descriptor_set (no two
    // resources of the job may share a binding).
    std::vector<TextureInput> textures;
    int width = 0, height = 0;  // output size in pixels
    Viewport viewport;          // where inside width x height the pass draws; default: everywhere
    // The vertex shader writes D3D's y-up clip space (HLSL): the viewport is flipped (negative
    // height, Vulkan 1.1) so the picture lands the right way up with FragCoord counted from the
    // top row, as D3D runs it.
    bool clip_y_up = false;
    std::array<float, 4> clear_color = {0, 0, 0, 0};  // linear RGBA the whole target starts as
    OutputFormat format = OutputFormat::Rgba8Unorm;
    // The output is only sampled by later jobs of this engine (a scene's intermediate pass): the
    // engine may keep it on its device and return an Image of its size whose `device` holds it,
    // with no texels, instead of reading it back and uploading it again for each reader. It does
    // so only where its readers then sample exactly the values a read-back would have given them
    // (the float formats, copied into full float); otherwise the texels come back as usual.
    bool keep_on_device = false;
    // The bytes of the std140 uniform block, as laid out by the shader. Empty = the shader has no
    // uniform block. It must cover every byte of the block the shader declares.
    std::vector<uint8_t> uniform_data;
    // Where the uniform block and the input's combined image sampler live. The shader may use no
    // other descriptors than these and `textures` (and no push constants or vertex attributes).
    uint32_t uniform_binding = 0, texture_binding = 1, descriptor_set = 0;
};

// The levels of a mipmapped width x height texture: floor(log2(max(width, height))) + 1 (the
// count RetroArch gives its mip chains); 1 for an empty one.
inline uint32_t mip_level_count(int width, int height) {
    uint32_t levels = 1;
    for (int size = width > height ? width : height; size > 1; size >>= 1) ++levels;
    return levels;
}

// One job of RenderEngine::time_draws(): timed `timings` times.
struct TimedJob {
    const RenderJob* job = nullptr;
    int timings = 1;
};

struct DeviceInfo {
    uint32_t index = 0;  // position in the Vulkan loader's enumeration; EngineOptions::device accepts it
    std::string name;    // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string type;    // "cpu", "integrated", "discrete", "virtual" or "other"
    std::string driver;  // driver name and version info, e.g. "llvmpipe (Mesa 22.3.6 (LLVM 15.0.6))"
};

class RenderEngine {
public:
    virtual ~RenderEngine() = default;
    // The device every render() runs on.
    virtual const DeviceInfo& device() const = 0;
    // Renders `job` and returns the output image (job.width x job.height, linear floats).
    // A bad job (zero or oversized output, malformed SPIR-V, no "main" entry point, a descriptor
    // the job does not provide, a too-short uniform buffer, two resources at one binding, a
    // malformed or oversized texture, a viewport outside the target, a non-finite clear colour)
    // returns an ErrorKind::Input error with field "job.<name>" before any GPU work.
    virtual Result<Image> render(const RenderJob& job) = 0;
    // Device times of jobs' draws (render pass with its clear, pipeline, descriptors, the
    // full-screen triangle), in nanoseconds per draw: each job is built and uploaded once, then
    // timed `timings` times, the jobs taking turns (round 1: each job once, in order; round 2 ...),
    // each timing `draws` draws recorded back to back between two timestamp queries after one
    // untimed draw. out[i] holds jobs[i]'s timings in order. An ErrorKind::Input error when the
    // device's queue has no timestamps.
    virtual Result<std::vector<std::vector<double>>> time_draws(const std::vector<TimedJob>& jobs, int draws) = 0;
};

struct EngineOptions {
    // "" = prefer Mesa lavapipe (llvmpipe), else the first device. A string of digits selects a
    // device by index (see list_vulkan_devices); anything else is a case-insensitive substring of
    // the device name.
    std::string device;
    // Enable VK_LAYER_KHRONOS_validation. Every warning or error it reports while a job runs turns
    // that render() into an error (the first message is quoted), so a clean render is a proof.
    bool validation = false;
};

Result<std::unique_ptr<RenderEngine>> create_vulkan_engine(const EngineOptions& options);

// Every Vulkan device the loader can see, in enumeration order.
Result<std::vector<DeviceInfo>> list_vulkan_devices();
// The name of the first device whose name holds `part` and not `besides` (the device already in
// use; "" for none), both case-insensitive; "" where none does.
Result<std::string> vulkan_device_named(const std::string& part, const std::string& besides = "");

}  // namespace crtforge
