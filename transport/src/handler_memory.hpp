// Memory for the operations Asio makes for each asynchronous call (a receive,
// a timer's wait, a posted task). Asio frees an operation before calling its
// handler and keeps one freed block per thread for the next operation; on a
// node's hot path a receive, a post and a timer's wait compete for that one
// block, and the loser allocates. Each of them gets blocks of its own here,
// so steady-state traffic allocates nothing. (Private to the transport.)
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/system/error_code.hpp>
#include <cstddef>
#include <functional>
#include <memory>
#include <new>
#include <vector>

namespace jaus::transport::detail {

// A few blocks of one size; a request that is larger, or made while every
// block is in use (not expected), goes to the heap: always correct.
class HandlerMemory {
 public:
  HandlerMemory(std::size_t blocks, std::size_t block_size)
      : block_size_(round_up(block_size)), storage_(new std::max_align_t[blocks * block_size_ / kAlign]) {
    free_.reserve(blocks);
    for (std::size_t i = 0; i < blocks; ++i) free_.push_back(block(i));
    end_ = block(blocks);
  }
  void* allocate(std::size_t size) {
    if (size > block_size_ || free_.empty()) return ::operator new(size);
    void* p = free_.back();
    free_.pop_back();
    return p;
  }
  void deallocate(void* p) {
    // std::less: a total order even for a pointer from the heap, where `<` on
    // pointers into different objects is unspecified.
    if (!std::less<void*>()(p, storage_.get()) && std::less<void*>()(p, end_))
      free_.push_back(p);  // within the reserved capacity: never allocates
    else
      ::operator delete(p);
  }

 private:
  static constexpr std::size_t kAlign = sizeof(std::max_align_t);
  static std::size_t round_up(std::size_t n) { return (n + kAlign - 1) / kAlign * kAlign; }
  void* block(std::size_t i) { return reinterpret_cast<unsigned char*>(storage_.get()) + i * block_size_; }

  std::size_t block_size_;
  std::unique_ptr<std::max_align_t[]> storage_;
  void* end_ = nullptr;
  std::vector<void*> free_;
};

// Shares the memory: an operation still queued when its owner is gone (the
// io_context runs or is destroyed later) frees its block into live memory.
template <class T>
struct HandlerAllocator {
  using value_type = T;
  explicit HandlerAllocator(std::shared_ptr<HandlerMemory> m) : memory(std::move(m)) {}
  template <class U>
  HandlerAllocator(const HandlerAllocator<U>& other) : memory(other.memory) {}  // NOLINT: rebinding
  T* allocate(std::size_t n) { return static_cast<T*>(memory->allocate(sizeof(T) * n)); }
  void deallocate(T* p, std::size_t) { memory->deallocate(p); }
  template <class U>
  bool operator==(const HandlerAllocator<U>& other) const {
    return memory == other.memory;
  }
  std::shared_ptr<HandlerMemory> memory;
};

// A handler whose operation Asio allocates from `memory`.
template <class Handler>
struct WithHandlerMemory {
  using allocator_type = HandlerAllocator<void>;
  allocator_type get_allocator() const noexcept { return allocator_type(memory); }
  template <class... Args>
  void operator()(Args&&... args) {
    handler(std::forward<Args>(args)...);
  }
  std::shared_ptr<HandlerMemory> memory;
  Handler handler;
};

template <class Handler>
WithHandlerMemory<std::decay_t<Handler>> with_memory(const std::shared_ptr<HandlerMemory>& memory, Handler&& h) {
  return {memory, std::forward<Handler>(h)};
}

}  // namespace jaus::transport::detail
