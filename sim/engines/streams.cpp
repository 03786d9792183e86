// The stream forms of engines/streams.h: in memory, read ahead and write behind in threads.
#include "engines/streams.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

namespace tex {

size_t VectorSource::read(Request* out, size_t max) {
  const size_t n = std::min(max, n_ - next_);
  std::copy_n(requests_ + next_, n, out);
  next_ += n;
  return n;
}

std::shared_mutex& fork_gate() {
  static std::shared_mutex gate;
  return gate;
}

struct ReadAheadSource::Impl {
  struct Chunk {
    std::vector<Request> requests;
    std::exception_ptr error;  // the source threw here (after the requests before it)
  };
  RequestSource& inner;
  size_t chunk, depth;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<Chunk> ready;
  bool done = false, stop = false, started = false;
  double busy = 0;
  Chunk current;
  size_t at = 0;
  std::thread worker;

  Impl(RequestSource& source, size_t chunk_size, size_t max_chunks) : inner(source), chunk(chunk_size), depth(max_chunks) {
    worker = std::thread([this] { run(); });
    // Returns once the worker runs: a thread starting up may hold an allocator lock, and the
    // SystemC engine forks next (such a lock stays held in the child).
    std::unique_lock lock(mutex);
    changed.wait(lock, [this] { return started; });
  }
  void run() {
    {
      std::lock_guard lock(mutex);
      started = true;
    }
    changed.notify_all();
    for (;;) {
      std::shared_lock gate(fork_gate());  // (released while it waits)
      Chunk c;
      c.requests.resize(chunk);
      const auto t0 = std::chrono::steady_clock::now();
      size_t n = 0;
      try {
        n = inner.read(c.requests.data(), chunk);
      } catch (...) {
        c.error = std::current_exception();
      }
      c.requests.resize(n);
      const bool last = n == 0 || c.error;
      std::unique_lock lock(mutex);
      busy += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (n || c.error) ready.push_back(std::move(c));
      done = last;
      changed.notify_all();
      gate.unlock();
      // At the end, the thread waits for its owner's stop (fork_gate: it ends no sooner).
      changed.wait(lock, [this, last] { return stop || (!last && ready.size() < depth); });
      if (stop) return;
    }
  }
};

ReadAheadSource::ReadAheadSource(RequestSource& inner, size_t chunk, size_t depth)
    : impl_(std::make_unique<Impl>(inner, chunk, depth)) {}

ReadAheadSource::~ReadAheadSource() {
  {
    std::lock_guard lock(impl_->mutex);
    impl_->stop = true;
  }
  impl_->changed.notify_all();
  impl_->worker.join();
}

size_t ReadAheadSource::read(Request* out, size_t max) {
  Impl& d = *impl_;
  if (d.at == d.current.requests.size()) {
    if (d.current.error) std::rethrow_exception(std::exchange(d.current.error, nullptr));
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_lock lock(d.mutex);
    d.changed.wait(lock, [&] { return !d.ready.empty() || d.done; });
    busy_seconds_ = d.busy;
    wait_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (d.ready.empty()) return 0;
    d.current = std::move(d.ready.front());
    d.ready.pop_front();
    d.at = 0;
    d.changed.notify_all();
    lock.unlock();
    if (d.current.requests.empty() && d.current.error) std::rethrow_exception(std::exchange(d.current.error, nullptr));
  }
  const size_t n = std::min(max, d.current.requests.size() - d.at);
  std::copy_n(d.current.requests.data() + d.at, n, out);
  d.at += n;
  return n;
}

struct WriteBehindSink::Impl {
  TexelSink& inner;
  size_t chunk, depth;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::vector<Texel>> queue, spare;  // full chunks, in order; emptied ones for reuse
  std::vector<Texel> current;
  bool writing = false, stop = false, started = false;
  std::exception_ptr error;
  double busy = 0;
  std::thread worker;

  Impl(TexelSink& sink, size_t chunk_size, size_t max_chunks) : inner(sink), chunk(chunk_size), depth(max_chunks) {
    current.reserve(chunk);
    worker = std::thread([this] { run(); });
    // Returns once the worker waits: a thread starting up may hold an allocator lock, and the
    // SystemC engine forks next (such a lock stays held in the child).
    std::unique_lock lock(mutex);
    changed.wait(lock, [this] { return started; });
  }
  void run() {
    std::unique_lock lock(mutex);
    started = true;
    changed.notify_all();
    for (;;) {
      changed.wait(lock, [this] { return stop || !queue.empty(); });
      if (queue.empty()) return;  // (stop)
      std::vector<Texel> c = std::move(queue.front());
      queue.pop_front();
      writing = true;
      const bool failed = error != nullptr;
      lock.unlock();
      std::shared_lock gate(fork_gate());  // (released before it waits again)
      const auto t0 = std::chrono::steady_clock::now();
      std::exception_ptr e;
      if (!failed) try {
          inner.write(c.data(), c.size());
        } catch (...) {
          e = std::current_exception();
        }
      const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      c.clear();
      lock.lock();
      busy += dt;
      if (e && !error) error = e;
      spare.push_back(std::move(c));
      writing = false;
      changed.notify_all();
      gate.unlock();
    }
  }
  // Hands the current chunk to the thread (waits while `depth` chunks are queued).
  void hand_over() {
    std::unique_lock lock(mutex);
    changed.wait(lock, [this] { return queue.size() < depth || error; });
    if (error) std::rethrow_exception(error);
    queue.push_back(std::move(current));
    if (!spare.empty()) {
      current = std::move(spare.front());
      spare.pop_front();
    } else {
      current = {};
      current.reserve(chunk);
    }
    changed.notify_all();
  }
};

WriteBehindSink::WriteBehindSink(TexelSink& inner, size_t chunk, size_t depth)
    : impl_(std::make_unique<Impl>(inner, chunk, depth)) {}

WriteBehindSink::~WriteBehindSink() {
  {
    std::lock_guard lock(impl_->mutex);
    impl_->stop = true;
    impl_->queue.clear();
  }
  impl_->changed.notify_all();
  impl_->worker.join();
}

void WriteBehindSink::write(const Texel* texels, size_t n) {
  Impl& d = *impl_;
  while (n) {
    const size_t m = std::min(n, d.chunk - d.current.size());
    d.current.insert(d.current.end(), texels, texels + m);
    texels += m;
    n -= m;
    if (d.current.size() == d.chunk) d.hand_over();
  }
}

void WriteBehindSink::finish() {
  Impl& d = *impl_;
  if (!d.current.empty()) d.hand_over();
  std::unique_lock lock(d.mutex);
  d.changed.wait(lock, [&] { return (d.queue.empty() && !d.writing) || d.error; });
  if (d.error) std::rethrow_exception(d.error);
}

double WriteBehindSink::busy_seconds() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->busy;
}

void RequestQueue::refill() {
  at_ = size_ = 0;
  if (!ended_) size_ = source_.read(buffer_.data(), buffer_.size());
  ended_ = size_ == 0;
}

}  // namespace tex
