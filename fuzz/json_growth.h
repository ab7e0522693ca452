#pragma once
// A structure-aware mutation for the JSON fuzzers (glTF, graphs, timelines):
// the byte mutations of libFuzzer rarely turn a small file into one that
// makes a loader work hard, which is what issue 37's inputs do. Half the
// time this grows the document instead: an array's element copied many
// times (with its strings made distinct, so names do not clash), an object
// nested inside itself one level deeper, or a number scaled up; the other
// half, and whenever the input is not JSON, it leaves the bytes to
// LLVMFuzzerMutate. A fuzzer opts in by defining LLVMFuzzerCustomMutator with
// FUZZ_GROW_JSON_MUTATOR.
#include <cstddef>
#include <cstdint>

namespace fuzz {

size_t mutateGrowingJson(uint8_t* data, size_t size, size_t maxSize, unsigned seed);

}  // namespace fuzz

#define FUZZ_GROW_JSON_MUTATOR                                                                       \
  extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t maxSize, unsigned seed) { \
    return ::fuzz::mutateGrowingJson(data, size, maxSize, seed);                                    \
  }
