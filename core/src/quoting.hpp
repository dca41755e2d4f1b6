// How a message shows text that came from outside (a JSON key or string, a
// CSV field, an environment variable): control bytes as \xNN, since a NUL
// would end the message (what() is a C string) and others garble a
// terminal; and at most kMaxQuotedChars bytes of it, so that a 5 MB key is
// not echoed whole. Every message of the core shows such text through these.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace prism {

inline constexpr size_t kMaxQuotedChars = 60;

namespace detail {
// The first kMaxQuotedChars bytes of `text`, escaped; `cut` says whether that is not all of it.
inline std::string escaped_head(std::string_view text, bool& cut) {
  cut = text.size() > kMaxQuotedChars;
  std::string out;
  for (unsigned char c : text.substr(0, kMaxQuotedChars)) {
    if (c >= 0x20 && c != 0x7f) {
      out += char(c);
      continue;
    }
    char escaped[8];
    std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
    out += escaped;
  }
  return out;
}
}  // namespace detail

// The text escaped; when cut, "…" and the whole length follow: abc… (5242880 bytes).
inline std::string printable(std::string_view text) {
  bool cut = false;
  std::string head = detail::escaped_head(text, cut);
  return cut ? head + "… (" + std::to_string(text.size()) + " bytes)" : head;
}

// 'text', escaped; when cut: 'abc…' (5242880 bytes).
inline std::string quote(std::string_view text) {
  bool cut = false;
  std::string head = detail::escaped_head(text, cut);
  return cut ? "'" + head + "…' (" + std::to_string(text.size()) + " bytes)" : "'" + head + "'";
}

}  // namespace prism
