// The worker threads behind Embree's BVH builds and the renderer (TBB). A process that forks
// without exec, as `msislab montecarlo` does for its runs, must not hold any: a child cannot use a
// thread pool inherited from its parent (oneTBB's known limitations), so scene work done before the
// fork runs inside a ThreadPoolScope that ends the workers afterwards.
#pragma once

#include <memory>

namespace msislab::sim {

class ThreadPoolScope {
 public:
  ThreadPoolScope();
  ~ThreadPoolScope();
  ThreadPoolScope(const ThreadPoolScope&) = delete;
  ThreadPoolScope& operator=(const ThreadPoolScope&) = delete;

  /// Waits until the pool's workers have ended (every Scene built meanwhile must be gone); false
  /// when another user of the pool is still alive, in which case the workers stay.
  bool finish();

 private:
  struct Handle;
  std::unique_ptr<Handle> handle_;
};

}  // namespace msislab::sim
