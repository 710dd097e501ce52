#include <vimlop/Core/TaskPool.h>

#include <algorithm>
#include <exception>
#include <utility>

namespace vimlop
{

TaskPool::TaskPool(int threads)
{
  if (threads <= 0)
  {
    threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  }
  for (int i = 1; i < threads; ++i)
  {
    this->Workers.emplace_back([this] { this->workerLoop(); });
  }
}

TaskPool::~TaskPool()
{
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Stop = true;
  }
  this->Wake.notify_all();
  for (std::thread& worker : this->Workers)
  {
    worker.join();
  }
}

void TaskPool::drain()
{
  // Claims and runs tasks of the current batch until none is left.
  std::unique_lock<std::mutex> lock(this->Mutex);
  while (this->Task && this->Next < this->Count)
  {
    const int index = this->Next++;
    const std::function<void(int)>* task = this->Task;
    lock.unlock();
    try
    {
      (*task)(index);
    }
    catch (...)
    {
      std::lock_guard<std::mutex> failureLock(this->Mutex);
      if (!this->Failure)
      {
        this->Failure = std::current_exception();
      }
    }
    lock.lock();
    if (--this->Pending == 0)
    {
      this->Done.notify_all();
    }
  }
}

void TaskPool::workerLoop()
{
  unsigned long seen = 0;
  for (;;)
  {
    {
      std::unique_lock<std::mutex> lock(this->Mutex);
      this->Wake.wait(lock, [&] { return this->Stop || this->Generation != seen; });
      if (this->Stop)
      {
        return;
      }
      seen = this->Generation;
    }
    this->drain();
  }
}

void TaskPool::run(int n, const std::function<void(int)>& task)
{
  if (n <= 0)
  {
    return;
  }
  if (this->Workers.empty() || n == 1)
  {
    for (int i = 0; i < n; ++i)
    {
      task(i);
    }
    return;
  }
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Task = &task;
    this->Next = 0;
    this->Count = n;
    this->Pending = n;
    this->Failure = nullptr;
    ++this->Generation;
  }
  this->Wake.notify_all();
  this->drain();
  std::unique_lock<std::mutex> lock(this->Mutex);
  this->Done.wait(lock, [&] { return this->Pending == 0; });
  this->Task = nullptr;
  if (this->Failure)
  {
    std::rethrow_exception(std::exchange(this->Failure, nullptr));
  }
}

} // namespace vimlop
