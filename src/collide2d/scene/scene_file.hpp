// A scene file read twice: once whole as text (kept in the run file), once
// as a stream parsed ball by ball, every byte hashed on the way, so that the
// scene parsed is shown to be the text kept.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <streambuf>
#include <string>

#include "collide2d/scene/scene.hpp"

namespace collide2d {

// A 64-bit hash of a text, eight bytes a step: h <- mix((h ^ word) * p),
// each step a bijection of h, so one changed word always changes the hash.
// Fed in pieces, it equals the hash of the whole when every piece but the
// last is a multiple of eight bytes long.
inline void hash_text(std::uint64_t& h, const char* bytes, std::size_t n) {
  constexpr std::uint64_t prime = 0x100000001b3ULL;
  std::size_t k = 0;
  for (; k + 8 <= n; k += 8) {
    std::uint64_t word;
    std::memcpy(&word, bytes + k, 8);
    h = (h ^ word) * prime;
    h ^= h >> 29;
  }
  for (; k < n; ++k) h = (h ^ static_cast<unsigned char>(bytes[k])) * prime;
}

inline constexpr std::uint64_t kTextHashStart = 0xcbf29ce484222325ULL;

struct TextDigest {
  std::uint64_t hash = kTextHashStart;
  std::uint64_t size = 0;
  bool operator==(const TextDigest&) const = default;
};

inline TextDigest digest_of(const std::string& text) {
  TextDigest d;
  hash_text(d.hash, text.data(), text.size());
  d.size = text.size();
  return d;
}

// The stream buffer of a file that digests what it hands out. Each refill
// reads a whole buffer (short only at the end of the file), as hash_text
// needs for its pieces.
class HashedFileBuf : public std::streambuf {
 public:
  explicit HashedFileBuf(const std::string& path) { file_.open(path, std::ios::in | std::ios::binary); }
  bool is_open() const { return file_.is_open(); }
  const TextDigest& digest() const { return digest_; }

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    std::streamsize n = 0;
    while (n < static_cast<std::streamsize>(buffer_.size())) {
      const std::streamsize got = file_.sgetn(buffer_.data() + n, static_cast<std::streamsize>(buffer_.size()) - n);
      if (got <= 0) break;
      n += got;
    }
    if (n == 0) return traits_type::eof();
    hash_text(digest_.hash, buffer_.data(), static_cast<std::size_t>(n));
    digest_.size += static_cast<std::uint64_t>(n);
    setg(buffer_.data(), buffer_.data(), buffer_.data() + n);
    return traits_type::to_int_type(buffer_[0]);
  }

 private:
  std::filebuf file_;
  std::array<char, 1 << 16> buffer_{};
  TextDigest digest_;
};

// Parses the scene file at `path` as a stream and checks that its bytes are
// the ones digested before as `written` (a file changed between the two
// reads is refused with SceneError "changed while it was read; run again").
// expected_balls only sizes the ball list (count_ball_positions of the text).
Scene scene_from_file_as_written(const std::string& path, std::size_t expected_balls, const TextDigest& written);

}  // namespace collide2d
