// The fuzzer's bytes read as decisions, for the targets that generate structured input from them
// (fuzz_gltf's generator mode, fuzz_shader_includes): each call takes the next byte(s), and an
// exhausted input reads as zeros, so every input makes one well-defined structure and libFuzzer's
// byte mutations become structural ones (a count, a reference, an extreme value changes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>

namespace vplkit::fuzzing {

class fuzz_input {
 public:
  fuzz_input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  bool empty() const { return at_ >= size_; }
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  std::uint32_t word() {
    std::uint32_t value = 0;
    for (int k = 0; k < 4; ++k) value = value << 8 | byte();
    return value;
  }
  /// A number in [0, count) (0 when count is 0).
  std::uint32_t below(std::uint32_t count) { return count == 0 ? 0 : (count <= 256 ? byte() % count : word() % count); }
  bool flag() { return byte() & 1; }
  /// One of the given texts.
  const char* pick(std::initializer_list<const char*> choices) { return choices.begin()[below(static_cast<std::uint32_t>(choices.size()))]; }
  /// `count` bytes of the input (fewer where it ends).
  std::string take(std::size_t count) {
    std::string out;
    while (count-- > 0 && !empty()) out += static_cast<char>(byte());
    return out;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

}  // namespace vplkit::fuzzing
