#ifndef vimlop_TaskPool_h
#define vimlop_TaskPool_h

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace vimlop
{

/**
 * @brief A small fixed pool of worker threads running indexed tasks.
 *
 * run(n, task) calls task(i) for i in [0, n) on the pool and the calling
 * thread, and returns when all are done. Work is split into tasks by the
 * caller, never by the number of threads, and results are combined by task
 * index, so VIMLOP's results do not depend on the thread count.
 */
class TaskPool
{
public:
  /// @param threads total threads including the caller; 0 means the hardware concurrency.
  explicit TaskPool(int threads = 0);
  ~TaskPool();
  TaskPool(const TaskPool&) = delete;
  TaskPool& operator=(const TaskPool&) = delete;

  int threadCount() const { return static_cast<int>(this->Workers.size()) + 1; }

  /// @brief Runs task(0) ... task(n - 1); the first exception thrown is rethrown
  /// here. One run at a time: run() must not be called concurrently.
  void run(int n, const std::function<void(int)>& task);

  /**
   * @brief Calls body(begin, end) over [0, n) in chunks of `chunk` items
   * (the partition depends on n and chunk only).
   */
  template <typename Body>
  void forChunks(int n, int chunk, Body&& body)
  {
    const int tasks = (n + chunk - 1) / chunk;
    this->run(tasks, [&](int t) { body(t * chunk, std::min(n, (t + 1) * chunk)); });
  }

private:
  void workerLoop();
  void drain();

  std::vector<std::thread> Workers;
  std::mutex Mutex;
  std::condition_variable Wake;
  std::condition_variable Done;
  const std::function<void(int)>* Task = nullptr;
  int Next = 0;
  int Count = 0;
  int Pending = 0;
  unsigned long Generation = 0;
  bool Stop = false;
  std::exception_ptr Failure;
};

} // namespace vimlop

#endif
