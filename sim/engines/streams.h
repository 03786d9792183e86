// The request and texel streams every engine and workload shares: requests pulled a chunk at a
// time from a source (a query trace is never held whole in memory), texels pushed a chunk at a time
// into a sink, in request order; threads that read ahead and write behind; in-memory forms. Only
// model types: workloads/ include this, not engine.h.
#pragma once
#include <cstddef>
#include <memory>
#include <shared_mutex>
#include <vector>

#include "model/sampler.h"

namespace tex {

// Requests in order, pulled a chunk at a time as an engine takes them: a query trace is never
// held whole in memory.
class RequestSource {
 public:
  virtual ~RequestSource() = default;
  // Up to `max` next requests into `out`; 0 at the end. Throws tex::Error on bad input.
  virtual size_t read(Request* out, size_t max) = 0;
};

// The threads that work beside an engine (ReadAheadSource's, WriteBehindSink's) hold this shared
// while they work, and the SystemC engine holds it alone across fork(): no other thread is then
// inside an allocator, whose lock the child would inherit held forever (glibc's malloc takes its
// locks around fork itself; GCC 12's AddressSanitizer runtime does not). Such a thread also stays
// alive until its owner ends it, and its owner's constructor returns only once it runs: a thread
// that starts or ends allocates and frees too.
std::shared_mutex& fork_gate();

// Reads a source ahead in a thread of its own, a chunk at a time, while the caller works on the
// previous chunks: parsing overlaps sampling. The requests, and any error of the source (thrown by
// read() where the source threw it), come out in order. busy_seconds(): the thread's time in the
// source; wait_seconds(): the caller's time waiting for it.
class ReadAheadSource final : public RequestSource {
 public:
  explicit ReadAheadSource(RequestSource& inner, size_t chunk = 16384, size_t depth = 4);
  ~ReadAheadSource() override;
  size_t read(Request* out, size_t max) override;
  double busy_seconds() const { return busy_seconds_; }
  double wait_seconds() const { return wait_seconds_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double busy_seconds_ = 0, wait_seconds_ = 0;
};

// Texels in request order, delivered a chunk at a time.
class TexelSink {
 public:
  virtual ~TexelSink() = default;
  virtual void write(const Texel* texels, size_t n) = 0;
};

// Writes to a sink in a thread of its own, a chunk at a time, while the caller makes the next
// chunks: formatting overlaps sampling. finish() waits until every texel is written and throws the
// inner sink's error, if any (so does the first write() after it). busy_seconds(): the thread's
// time in the sink. Destroyed without finish() (an error path), it drops what is still queued.
class WriteBehindSink final : public TexelSink {
 public:
  explicit WriteBehindSink(TexelSink& inner, size_t chunk = 16384, size_t depth = 4);
  ~WriteBehindSink() override;
  void write(const Texel* texels, size_t n) override;
  void finish();
  double busy_seconds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// In-memory source and sink, and the chunked views engines use to take one request per clock.
class VectorSource final : public RequestSource {
 public:
  explicit VectorSource(const std::vector<Request>& r) : VectorSource(r.data(), r.size()) {}
  VectorSource(const Request* requests, size_t n) : requests_(requests), n_(n) {}
  size_t read(Request* out, size_t max) override;

 private:
  const Request* requests_;
  size_t n_, next_ = 0;
};

class VectorSink final : public TexelSink {
 public:
  void write(const Texel* t, size_t n) override { texels.insert(texels.end(), t, t + n); }
  std::vector<Texel> texels;
};

class RequestQueue {
 public:
  explicit RequestQueue(RequestSource& source, size_t chunk = 4096) : source_(source), buffer_(chunk) {}
  // The next request not yet popped, or nullptr at the end of the source.
  const Request* peek() {
    if (at_ == size_) refill();
    return at_ < size_ ? &buffer_[at_] : nullptr;
  }
  void pop() { ++at_; }

 private:
  void refill();
  RequestSource& source_;
  std::vector<Request> buffer_;
  size_t at_ = 0, size_ = 0;
  bool ended_ = false;
};

class TexelQueue {
 public:
  explicit TexelQueue(TexelSink& sink, size_t chunk = 4096) : sink_(sink) { buffer_.reserve(chunk); }
  void push(const Texel& t) {
    buffer_.push_back(t);
    if (buffer_.size() == buffer_.capacity()) flush();
  }
  void flush() {
    if (!buffer_.empty()) sink_.write(buffer_.data(), buffer_.size());
    buffer_.clear();
  }

 private:
  TexelSink& sink_;
  std::vector<Texel> buffer_;
};

}  // namespace tex
