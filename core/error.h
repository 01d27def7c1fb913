// SPDX-License-Identifier: MIT
// Error types by who is at fault: bad input, unwritable output, and bugs (INKLINE_CHECK).
#pragma once

#include <cstddef>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace inkline {

// Input that cannot be drawn: a broken file, a bad scene key, an impossible camera.
// what() is one line naming the file or key first, e.g. "scene.json: key 'image.width': ...".
class InputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// An output that cannot be written: unwritable folder, full disk.
class OutputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Memory or address space the run needs and cannot have, with what it was for. A std::bad_alloc,
// so it is handled as any other allocation failure (exit 5).
class OutOfMemory : public std::bad_alloc {
  public:
    explicit OutOfMemory(std::string what) : what_(std::move(what)) {}
    const char* what() const noexcept override { return what_.c_str(); }

  private:
    std::string what_;
};

// A broken internal invariant: a bug in inkline, never the user's fault.
class InternalError : public std::logic_error {
  public:
    using std::logic_error::logic_error;
};

// Largest number of characters of a user value (a key, an option value, a file name) an error
// message quotes: messages stay one short line however long the value.
inline constexpr size_t kMaxQuotedChars = 60;

// A user value as an error message quotes it: control characters shown as '?', and a value
// longer than max_chars cut to its start and end around "...", at UTF-8 character boundaries.
std::string quote_value(std::string_view value, size_t max_chars = kMaxQuotedChars);

namespace detail {
[[noreturn]] void check_failed(const char* file, int line, const std::string& message);

template <typename A, typename B>
[[noreturn]] void check_eq_failed(const char* file, int line, const char* a_text,
                                  const char* b_text, const A& a, const B& b) {
    std::ostringstream out;
    out << a_text << " == " << b_text << " failed: " << a << " vs " << b;
    check_failed(file, line, out.str());
}
}  // namespace detail

}  // namespace inkline

#define INKLINE_CHECK(cond)                                                       \
    do {                                                                          \
        if (!(cond)) ::inkline::detail::check_failed(__FILE__, __LINE__, #cond);  \
    } while (false)

#define INKLINE_CHECK_EQ(a, b)                                                          \
    do {                                                                                \
        const auto& inkline_a_ = (a);                                                   \
        const auto& inkline_b_ = (b);                                                   \
        if (!(inkline_a_ == inkline_b_))                                                \
            ::inkline::detail::check_eq_failed(__FILE__, __LINE__, #a, #b, inkline_a_, \
                                               inkline_b_);                             \
    } while (false)
