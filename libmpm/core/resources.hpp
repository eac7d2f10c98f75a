// What the machine has for a run: available memory and the free disk of the output folder, read
// before anything is allocated or written, so a scene that cannot fit is refused with the figures
// instead of dying with std::bad_alloc, or filling the disk, hours later (scene/budget.hpp).
#pragma once
#include <filesystem>
#include <string>

namespace cleave {

// Memory a new allocation can get, in bytes: /proc/meminfo's MemAvailable (else the free pages
// from sysconf), capped by the cgroup's memory.max less memory.current when the process runs in a
// limited cgroup (a container).
double available_memory_bytes();

// Memory this process holds now (resident), in bytes: added to the available memory, it is what a
// run built in this process had before it was built.
double resident_bytes();

// Free disk (for an unprivileged user) of the file system holding `dir`, or of its nearest existing
// parent when `dir` does not exist yet, in bytes; +inf when it cannot be read.
double free_disk_bytes(const std::filesystem::path& dir);

// "2.4 GB", "310 MB", "12 kB" (powers of 1000, as df -H and file managers print).
std::string format_bytes(double bytes);

// `cleave run --force`: run even when the estimates say the run will not fit. Process-wide: the
// CLI sets it once, before any scene is built.
void set_resource_checks_forced(bool forced);
bool resource_checks_forced();

}  // namespace cleave
