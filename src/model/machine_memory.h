// The machine's physical memory, for the checks that refuse a grid before allocating it (the
// scene loader's, and the CPU solver's by its integrator's arrays, cpu/cpu_memory.h).
#pragma once

#include <unistd.h>

namespace cloth {

// Bytes of physical memory; 8 GB where the system does not say.
inline double physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && pageSize > 0 ? double(pages) * double(pageSize) : 8e9;
}

}  // namespace cloth
