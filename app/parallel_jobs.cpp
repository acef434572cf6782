#include "app/parallel_jobs.hpp"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace msislab::app {

void run_parallel(std::size_t count, int workers, const std::function<void(std::size_t)>& job,
                  const std::function<void()>& tick, std::chrono::milliseconds tick_period) {
  std::mutex mutex;
  std::condition_variable all_done;
  std::size_t next = 0;
  std::size_t running_threads = 0;
  std::exception_ptr error;

  auto worker = [&] {
    while (true) {
      std::size_t index = 0;
      {
        const std::lock_guard<std::mutex> lock(mutex);
        if (next >= count || error) break;
        index = next++;
      }
      try {
        job(index);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
      }
    }
    const std::lock_guard<std::mutex> lock(mutex);
    --running_threads;
    all_done.notify_all();
  };

  const std::size_t threads = std::min(count, static_cast<std::size_t>(std::max(1, workers)));
  std::vector<std::thread> pool;
  running_threads = threads;
  for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(worker);
  {
    std::unique_lock<std::mutex> lock(mutex);
    while (running_threads > 0) {
      all_done.wait_for(lock, tick_period, [&] { return running_threads == 0; });
      if (running_threads > 0 && tick) {
        lock.unlock();
        tick();
        lock.lock();
      }
    }
  }
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace msislab::app
