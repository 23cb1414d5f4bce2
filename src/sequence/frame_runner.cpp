#include "lidar_sgm/sequence/frame_runner.hpp"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

namespace lidar_sgm {
namespace sequence {

std::size_t runFramesInOrder(std::size_t count, int jobs, const FrameWork& work, const FrameDone& done,
                             const StopAsked& stop) {
  if (jobs < 1) throw std::invalid_argument("runFramesInOrder: jobs must be >= 1");
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::optional<FrameRecord>> records(count);
  std::size_t next = 0;      // the next frame a worker takes
  int running = jobs;        // workers not yet finished
  bool failed = false;       // an exception escaped: no new frames
  std::exception_ptr error;

  auto worker = [&](int id) {
    for (;;) {
      std::size_t index = 0;
      {
        const std::lock_guard<std::mutex> lock(mutex);
        if (failed || next >= count || stop()) break;
        index = next++;
      }
      try {
        FrameRecord record = work(index, id);
        const std::lock_guard<std::mutex> lock(mutex);
        records[index] = std::move(record);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
      changed.notify_all();
    }
    {
      const std::lock_guard<std::mutex> lock(mutex);
      --running;
    }
    changed.notify_all();
  };

  std::vector<std::thread> workers;
  workers.reserve(static_cast<std::size_t>(jobs));
  for (int id = 0; id < jobs; ++id) workers.emplace_back(worker, id);

  std::size_t finished = 0;
  try {
    std::unique_lock<std::mutex> lock(mutex);
    while (finished < count) {
      // Workers only stop taking frames (stop, failure); every frame taken is recorded before its
      // worker ends, so when none runs the records present are exactly the frames finished.
      changed.wait(lock, [&] { return records[finished].has_value() || running == 0; });
      if (!records[finished]) break;  // never taken
      const FrameRecord record = std::move(*records[finished]);
      records[finished].reset();
      lock.unlock();
      done(finished, record);
      ++finished;
      lock.lock();
    }
  } catch (...) {
    const std::lock_guard<std::mutex> lock(mutex);
    if (!error) error = std::current_exception();
    failed = true;
  }
  for (std::thread& t : workers) t.join();
  if (error) std::rethrow_exception(error);
  return finished;
}

}  // namespace sequence
}  // namespace lidar_sgm
