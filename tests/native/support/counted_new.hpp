#pragma once
// Counts the heap allocations of a test program: include this in exactly one translation
// unit of the program (it replaces the global operator new and delete) and compare
// g_allocations before and after the code that must not allocate.
#include <atomic>
#include <cstdlib>
#include <new>

// atomic: a test may allocate from two threads
inline std::atomic<long> g_allocations{0};

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
