#include "result_array.hpp"

#include <sys/mman.h>

#include <cstdlib>
#include <list>
#include <memory>
#include <mutex>
#include <new>

namespace py = pybind11;

namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

struct Block {
  void* data;
  std::size_t bytes;
};

// Released large blocks, most recent first. Never destroyed: arrays may be released during interpreter
// shutdown, after static destructors would have run.
struct Pool {
  std::mutex mutex;
  std::list<Block> free;
  std::size_t bytes = 0;
};
Pool& pool() {
  static Pool* p = new Pool;
  return *p;
}

Block take(std::size_t bytes) {
  if (bytes < kLargeResultBytes) {
    void* p = std::aligned_alloc(64, (bytes + 63) / 64 * 64);
    if (!p) throw std::bad_alloc();
    return {p, bytes};
  }
  {
    Pool& pool_ = pool();
    std::lock_guard<std::mutex> lock(pool_.mutex);
    for (auto it = pool_.free.begin(); it != pool_.free.end(); ++it)
      if (it->bytes == bytes) {
        const Block b = *it;
        pool_.bytes -= b.bytes;
        pool_.free.erase(it);
        return b;
      }
  }
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (!p) throw std::bad_alloc();
  madvise(p, rounded, MADV_HUGEPAGE);  // advice only: without huge pages the array works the same
  return {p, bytes};
}

void give_back(Block b) {
  if (b.bytes >= kLargeResultBytes && b.bytes <= kResultPoolBytes) {
    Pool& pool_ = pool();
    std::lock_guard<std::mutex> lock(pool_.mutex);
    pool_.free.push_front(b);
    pool_.bytes += b.bytes;
    while (pool_.bytes > kResultPoolBytes) {
      pool_.bytes -= pool_.free.back().bytes;
      std::free(pool_.free.back().data);
      pool_.free.pop_back();
    }
    return;
  }
  std::free(b.data);
}

}  // namespace

ComplexArray result_array(std::size_t n) {
  auto owner = std::make_unique<Block>(take(n * n * sizeof(std::complex<double>)));
  auto* data = static_cast<std::complex<double>*>(owner->data);
  py::capsule release(owner.get(), [](void* p) {
    const std::unique_ptr<Block> block(static_cast<Block*>(p));
    give_back(*block);
  });
  owner.release();  // the capsule owns it now
  return ComplexArray({n, n}, data, release);
}
