#include "libmpm/core/resources.hpp"

#include <sys/resource.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace cleave {
namespace {

std::atomic<bool> g_forced{false};

// The first number of a one-line file (cgroup's memory.max: "max" or a byte count); -1 if none.
double number_in(const char* file) {
  std::ifstream in(file);
  double v = -1;
  if (in >> v) return v;
  return -1;
}

}  // namespace

double available_memory_bytes() {
  double avail = -1;
  std::ifstream meminfo("/proc/meminfo");
  for (std::string line; std::getline(meminfo, line);) {
    if (line.rfind("MemAvailable:", 0) != 0) continue;
    std::istringstream s(line.substr(13));
    double kb = 0;
    if (s >> kb) avail = kb * 1024.0;
    break;
  }
  if (avail < 0) {
    const long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    avail = pages > 0 && page > 0 ? double(pages) * double(page) : std::numeric_limits<double>::infinity();
  }
  // cgroup v2: a container's limit is often far below the host's MemAvailable.
  const double max = number_in("/sys/fs/cgroup/memory.max"), used = number_in("/sys/fs/cgroup/memory.current");
  if (max > 0 && used >= 0) avail = std::min(avail, std::max(0.0, max - used));
  // ulimit -v: the address space left below the limit.
  rlimit as{};
  if (::getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
    std::ifstream statm("/proc/self/statm");
    double pages = 0;
    statm >> pages;
    avail = std::min(avail, std::max(0.0, double(as.rlim_cur) - pages * double(sysconf(_SC_PAGESIZE))));
  }
  return avail;
}

double free_disk_bytes(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::path p = std::filesystem::absolute(dir, ec);
  if (ec) p = dir;
  while (!p.empty() && !std::filesystem::exists(p, ec) && p != p.parent_path()) p = p.parent_path();
  struct statvfs st {};
  if (p.empty() || ::statvfs(p.c_str(), &st) != 0) return std::numeric_limits<double>::infinity();
  return double(st.f_bavail) * double(st.f_frsize);
}

double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  double size = 0, resident = 0;
  statm >> size >> resident;
  return resident * double(sysconf(_SC_PAGESIZE));
}

std::string format_bytes(double b) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (b >= 999.5 && u < 5) b /= 1000, ++u;
  char buf[32];
  std::snprintf(buf, sizeof buf, b < 9.95 && u > 0 ? "%.1f %s" : "%.0f %s", b, units[u]);
  return buf;
}

void set_resource_checks_forced(bool forced) { g_forced = forced; }
bool resource_checks_forced() { return g_forced; }

}  // namespace cleave
