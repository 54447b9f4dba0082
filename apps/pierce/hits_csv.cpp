#include "hits_csv.h"

#include <charconv>
#include <string>

namespace pierce::cli {

namespace {

template <typename T>
void append(std::string& s, T value) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  s.append(buf, r.ptr);
}

}  // namespace

bool write_hits_csv(std::FILE* out, std::size_t ray_count, const std::function<std::span<const Hit>(std::size_t)>& hits_of,
                    const std::function<bool()>& keep_going) {
  constexpr std::size_t kChunk = 1 << 20;
  std::string buf = "ray,t,geom,prim,u,v,enter\n";
  buf.reserve(kChunk + 256);
  for (std::size_t r = 0; r < ray_count; ++r) {
    for (const Hit& h : hits_of(r)) {
      append(buf, r);
      buf += ',';
      append(buf, h.t);  // shortest round-trip form
      buf += ',';
      append(buf, h.geom);
      buf += ',';
      append(buf, h.prim);
      buf += ',';
      append(buf, h.u + 0.f);  // + 0 turns -0 into 0
      buf += ',';
      append(buf, h.v + 0.f);
      buf += h.enter ? ",1\n" : ",0\n";
    }
    if (buf.size() >= kChunk) {
      if (!keep_going()) return false;
      std::fwrite(buf.data(), 1, buf.size(), out);
      buf.clear();
    }
  }
  if (!keep_going()) return false;
  std::fwrite(buf.data(), 1, buf.size(), out);
  return true;
}

}  // namespace pierce::cli
