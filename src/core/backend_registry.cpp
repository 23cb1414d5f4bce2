// The public queries about backends (names, availability, Auto's choice) and their creation,
// all answered from the generated list of the backends built in.
#include "core/backend_registry.hpp"

#include <stdexcept>

namespace lidar_sgm {

std::string toString(Backend backend) {
  switch (backend) {
    case Backend::Auto: return "auto";
    case Backend::CpuRef: return "cpu_ref";
    case Backend::Cpu: return "cpu";
    case Backend::Cuda: return "cuda";
  }
  return "unknown";
}

Backend backendFromString(const std::string& name) {
  for (Backend b : {Backend::Auto, Backend::CpuRef, Backend::Cpu, Backend::Cuda}) {
    if (toString(b) == name) return b;
  }
  throw std::invalid_argument("unknown backend '" + name + "': must be auto, cpu_ref, cpu or cuda");
}

namespace {

// "" when `entry` can run on this machine.
std::string entryUnavailable(const detail::BackendEntry& entry) {
  return entry.unavailable == nullptr ? std::string() : entry.unavailable();
}

}  // namespace

std::string unavailableReason(Backend backend) {
  if (backend == Backend::Auto) return "";
  for (const detail::BackendEntry& entry : detail::builtinBackends()) {
    if (entry.backend == backend) return entryUnavailable(entry);
  }
  return "not built into this library" +
         std::string(backend == Backend::Cuda ? " (configure with the CUDA toolkit, LIDAR_SGM_WITH_CUDA=ON)"
                     : backend == Backend::Cpu ? " (configure with Highway, LIDAR_SGM_WITH_CPU_BACKEND=ON)"
                                               : "");
}

bool isAvailable(Backend backend) { return unavailableReason(backend).empty(); }

Backend resolve(Backend backend) {
  if (backend != Backend::Auto) return backend;
  for (const detail::BackendEntry& entry : detail::builtinBackends()) {
    if (entryUnavailable(entry).empty()) return entry.backend;
  }
  return Backend::CpuRef;  // always built, always runs
}

namespace detail {

std::unique_ptr<MatcherBackend> createBackend(Backend backend) {
  const Backend wanted = resolve(backend);
  std::string available;
  for (const BackendEntry& entry : builtinBackends()) {
    if (entry.backend == wanted) {
      const std::string why = entryUnavailable(entry);
      if (!why.empty()) throw std::runtime_error("backend " + toString(wanted) + " cannot run here: " + why);
      return entry.create();
    }
    available += toString(entry.backend) + ", ";
  }
  throw std::runtime_error("backend " + toString(backend) + " is not built into this library; available: " +
                           available + "auto");
}

}  // namespace detail
}  // namespace lidar_sgm
