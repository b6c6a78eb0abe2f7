// core/host_memory.h: the process's resident memory (host RSS), read from /proc/self/statm: a
// long run reports it at its start and end to show it does not grow.
#pragma once

#include <cstdint>
#include <cstdio>
#include <unistd.h>

namespace wisp {

// Bytes resident now; 0 where /proc is not there.
inline uint64_t hostResidentBytes()
{
    unsigned long long pages = 0, resident = 0;
    FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f)
        return 0;
    int read = std::fscanf(f, "%llu %llu", &pages, &resident);
    std::fclose(f);
    return read == 2 ? uint64_t(resident) * uint64_t(sysconf(_SC_PAGESIZE)) : 0;
}

} // namespace wisp
