// How a process that renders large images should hold its memory (see process_memory.cpp).
#pragma once

namespace crtforge {

// Keeps memory freed by large buffers in the process for reuse instead of handing it back to the
// system at each free. A 4K RGBA32F image is 130 MB; glibc maps every buffer above 32 MB afresh
// and unmaps it on free, so each image (ours, and lavapipe's textures and staging buffers) costs
// 32,000 page faults at first touch. On a virtual machine those dominated a 4K benchmark: sys time
// 60 s of a 175 s run, and a 12-pass reference render 3x slower than its arithmetic. Call once,
// first thing in main(); a no-op where the C library is not glibc. The price: the process's
// resident size stays at its peak until it exits.
void keep_freed_memory();

}  // namespace crtforge
