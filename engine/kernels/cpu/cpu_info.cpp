// SPDX-License-Identifier: MIT
// Linux topology from /sys/devices/system/cpu/cpuN/topology, restricted to the affinity mask
// (Windows: the processor-core records of GetLogicalProcessorInformationEx, all groups).
#include "kernels/cpu/cpu_info.h"

#ifdef _WIN32
#include <algorithm>
#include <thread>
#include <vector>

#include "core/windows_text.h"

namespace silk {

int PhysicalCoreCount() {
  const int logical = std::max(1u, std::thread::hardware_concurrency());
  DWORD len = 0;
  GetLogicalProcessorInformationEx(RelationProcessorCore, nullptr, &len);
  std::vector<char> buf(len);
  auto* info = reinterpret_cast<SYSTEM_LOGICAL_PROCESSOR_INFORMATION_EX*>(buf.data());
  if (len == 0 || !GetLogicalProcessorInformationEx(RelationProcessorCore, info, &len)) return logical;
  int cores = 0;
  for (DWORD off = 0; off < len;) {
    auto* rec = reinterpret_cast<SYSTEM_LOGICAL_PROCESSOR_INFORMATION_EX*>(buf.data() + off);
    if (rec->Size == 0) break;
    if (rec->Relationship == RelationProcessorCore) ++cores;
    off += rec->Size;
  }
  return cores > 0 ? std::min(cores, logical) : logical;
}

}  // namespace silk
#else
#include <sched.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <utility>

namespace silk {

namespace {

bool ReadInt(const std::string& path, int* out) {
  std::ifstream f(path);
  return static_cast<bool>(f >> *out);
}

}  // namespace

int PhysicalCoreCount() {
  const int logical = std::max(1u, std::thread::hardware_concurrency());
  cpu_set_t mask;
  CPU_ZERO(&mask);
  const bool have_mask = sched_getaffinity(0, sizeof(mask), &mask) == 0;
  std::set<std::pair<int, int> > cores;
  int allowed = 0;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
    if (have_mask && !CPU_ISSET(cpu, &mask)) continue;
    if (!have_mask && cpu >= logical) break;
    ++allowed;
    const std::string base = "/sys/devices/system/cpu/cpu" + std::to_string(cpu) + "/topology/";
    int package = 0, core = 0;
    if (!ReadInt(base + "physical_package_id", &package) || !ReadInt(base + "core_id", &core))
      return std::max(1, allowed > 0 && have_mask ? CPU_COUNT(&mask) : logical);
    cores.insert({package, core});
  }
  return cores.empty() ? logical : static_cast<int>(cores.size());
}

}  // namespace silk
#endif  // _WIN32
