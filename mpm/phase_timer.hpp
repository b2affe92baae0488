#pragma once
// Wall time per named phase of the time step. A phase appears in the table only if it ran, so
// physics a scene does not ask for does not appear.
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace hvi::mpm {

class PhaseTimer {
 public:
  struct Entry {
    std::string name;
    double seconds = 0.0;
    std::int64_t calls = 0;
  };

  class Scope {
   public:
    Scope(PhaseTimer& timer, std::size_t index)
        : timer_(timer), index_(index), start_(std::chrono::steady_clock::now()) {}
    ~Scope() {
      const auto end = std::chrono::steady_clock::now();
      timer_.entries_[index_].seconds += std::chrono::duration<double>(end - start_).count();
      timer_.entries_[index_].calls += 1;
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    PhaseTimer& timer_;
    std::size_t index_;
    std::chrono::steady_clock::time_point start_;
  };

  // Times the enclosing block under `name` (entries keep the order of first use).
  Scope scope(const std::string& name) { return Scope(*this, index_of(name)); }
  const std::vector<Entry>& entries() const { return entries_; }
  double total() const;
  // "phase  seconds  share  calls" lines.
  std::string table() const;
  void clear() { entries_.clear(); }

 private:
  std::size_t index_of(const std::string& name);
  std::vector<Entry> entries_;
};

}  // namespace hvi::mpm
