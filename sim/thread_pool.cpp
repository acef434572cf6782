#include "sim/thread_pool.hpp"

#include <oneapi/tbb/global_control.h>

#include <new>

namespace msislab::sim {

struct ThreadPoolScope::Handle {
  oneapi::tbb::task_scheduler_handle tbb{oneapi::tbb::attach{}};
};

ThreadPoolScope::ThreadPoolScope() : handle_(std::make_unique<Handle>()) {}

ThreadPoolScope::~ThreadPoolScope() = default;

bool ThreadPoolScope::finish() { return oneapi::tbb::finalize(handle_->tbb, std::nothrow); }

}  // namespace msislab::sim
