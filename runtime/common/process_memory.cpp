// glibc's malloc tuned for a process that allocates and frees many images of 100 MB and more.
#include "crtforge/runtime/process_memory.hpp"

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace crtforge {

void keep_freed_memory() {
#if defined(__GLIBC__)
    // No buffer gets a mapping of its own (the threshold cannot be raised above 32 MB, so the
    // count of such mappings is set to zero: large buffers come from the heap, which glibc still
    // extends by mmap where brk fails), and the heap's free top is never returned to the system.
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, -1);
#endif
}

}  // namespace crtforge
