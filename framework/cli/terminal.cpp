#include "terminal.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <streambuf>

namespace radchain::cli {

namespace {

// Passes bytes to `next`, writing C0 controls (but \n and \t), DEL and the C1 controls (UTF-8 C2 80 to C2 9F) as
// visible escapes. Keeps a lone C2 until the next byte says whether it starts a C1 control.
class EscapingBuffer final : public std::streambuf {
 public:
  explicit EscapingBuffer(std::streambuf* next) : next_(next) {}

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return sync() == 0 ? traits_type::not_eof(c) : c;
    const auto byte = static_cast<unsigned char>(traits_type::to_char_type(c));
    if (pending_c2_) {
      pending_c2_ = false;
      if (byte >= 0x80 && byte <= 0x9F) return put_escape("\\u00", byte) ? c : traits_type::eof();
      if (next_->sputc(static_cast<char>(0xC2)) == traits_type::eof()) return traits_type::eof();
    }
    if (byte == 0xC2) {
      pending_c2_ = true;
      return c;
    }
    if ((byte < 0x20 && byte != '\n' && byte != '\t') || byte == 0x7F) return put_escape("\\x", byte) ? c : traits_type::eof();
    return next_->sputc(static_cast<char>(byte)) == traits_type::eof() ? traits_type::eof() : c;
  }
  int sync() override {
    if (pending_c2_) {
      pending_c2_ = false;
      if (next_->sputc(static_cast<char>(0xC2)) == traits_type::eof()) return -1;
    }
    return next_->pubsync();
  }

 private:
  bool put_escape(const char* prefix, unsigned char byte) {
    static constexpr char hex[] = "0123456789abcdef";
    const char text[] = {hex[byte >> 4], hex[byte & 15]};
    for (const char* p = prefix; *p; ++p)
      if (next_->sputc(*p) == traits_type::eof()) return false;
    return next_->sputn(text, 2) == 2;
  }
  std::streambuf* next_;
  bool pending_c2_ = false;
};

}  // namespace

void escape_control_characters_on_terminals() {
  // Never destroyed: the standard streams are flushed after every static object's destructor has run, and a
  // destroyed buffer there is a crash at exit. (Reachable through the streams: no leak to report.)
  if (::isatty(STDOUT_FILENO)) std::cout.rdbuf(new EscapingBuffer(std::cout.rdbuf()));
  if (::isatty(STDERR_FILENO)) std::cerr.rdbuf(new EscapingBuffer(std::cerr.rdbuf()));
}

}  // namespace radchain::cli
