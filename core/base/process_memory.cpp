#include "core/base/process_memory.h"

#include <cstdlib>
#include <malloc.h>

namespace sp {

bool keepFreedMemory() {
    // A function-local static: the first caller decides, later ones (another engine, the server's main and
    // a plugin's module) see the same answer.
    static const bool kept = [] {
        if (std::getenv("MALLOC_TRIM_THRESHOLD_") || std::getenv("MALLOC_MMAP_THRESHOLD_"))
            return false;
        return mallopt(M_MMAP_THRESHOLD, 32 << 20) == 1 && mallopt(M_TRIM_THRESHOLD, 128 << 20) == 1;
    }();
    return kept;
}

} // namespace sp
