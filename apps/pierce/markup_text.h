#pragma once
// Text inside XML or HTML markup (VTP attributes, the report's page): the characters that would
// end a tag, an attribute or an entity written as entities.
#include <string>
#include <string_view>

namespace pierce::cli {

inline std::string markup_escaped(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace pierce::cli
