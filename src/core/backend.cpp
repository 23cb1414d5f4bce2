#include "core/backend.hpp"

#include <stdexcept>

namespace lidar_sgm {
namespace {

// The facade asks readsDeviceMemory() first: reaching these is a bug in the core.
[[noreturn]] void throwHostOnly(Backend backend) {
  throw std::logic_error("backend " + toString(backend) + " reads host memory only");
}

}  // namespace

void MatcherBackend::copyToHost(const DeviceFrame&, bool, DeviceFrameCopy&) { throwHostOnly(backend()); }

void MatcherBackend::copyToDevice(ImageView<const std::int16_t>, ImageView<std::int16_t>) {
  throwHostOnly(backend());
}

void MatcherBackend::runOnDevice(const FramePlan&, const FrameInputs&, ImageView<std::int16_t>, MemorySpace,
                                 FrameResults&) {
  throwHostOnly(backend());
}

}  // namespace lidar_sgm
