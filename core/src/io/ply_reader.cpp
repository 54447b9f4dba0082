// PLY: `format ascii | binary_little_endian | binary_big_endian 1.0`, element `vertex` with scalar
// properties x, y, z (any numeric type), element `face` with a list property `vertex_indices` (or
// `vertex_index`). Other properties and elements are read past, so files with normals, colours,
// edges or materials load too.
#include <cstdint>

#include "io_util.h"
#include "readers.h"

namespace pierce::io {

namespace {

enum class PlyType : std::uint8_t { i8, u8, i16, u16, i32, u32, f32, f64 };

bool parse_type(std::string_view s, PlyType& t) {
  struct Name { std::string_view name; PlyType type; };
  static constexpr Name kNames[] = {
      {"char", PlyType::i8},    {"int8", PlyType::i8},     {"uchar", PlyType::u8},   {"uint8", PlyType::u8},
      {"short", PlyType::i16},  {"int16", PlyType::i16},   {"ushort", PlyType::u16}, {"uint16", PlyType::u16},
      {"int", PlyType::i32},    {"int32", PlyType::i32},   {"uint", PlyType::u32},   {"uint32", PlyType::u32},
      {"float", PlyType::f32},  {"float32", PlyType::f32}, {"double", PlyType::f64}, {"float64", PlyType::f64}};
  for (const Name& n : kNames)
    if (n.name == s) {
      t = n.type;
      return true;
    }
  return false;
}

std::size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::i8: case PlyType::u8: return 1;
    case PlyType::i16: case PlyType::u16: return 2;
    case PlyType::i32: case PlyType::u32: case PlyType::f32: return 4;
    case PlyType::f64: return 8;
  }
  return 1;
}

bool is_integer(PlyType t) { return t != PlyType::f32 && t != PlyType::f64; }

struct Property {
  std::string name;
  PlyType type = PlyType::f32;  // item type for lists
  bool list = false;
  PlyType count_type = PlyType::u8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> props;
};

enum class Format { ascii, little, big };

// Where the current element instance is, for messages.
struct Context {
  const std::string* element = nullptr;
  std::uint64_t index = 0;
  std::string describe() const { return element ? *element + " " + std::to_string(index) : std::string("data"); }
};

class AsciiSource {
 public:
  AsciiSource(const std::string& path, std::string_view body, std::size_t header_lines)
      : path_(path), ts_(body), line_base_(header_lines) {}
  Context ctx;

  [[noreturn]] void fail(const std::string& what) const {
    fail_at_line(path_, ts_.line() + line_base_, ctx.describe() + ": " + what);
  }
  std::string_view token() {
    std::string_view tok;
    if (!ts_.next(tok)) fail("unexpected end of file");
    return tok;
  }
  double scalar(PlyType t) {
    const std::string_view tok = token();
    if (is_integer(t)) {
      std::int64_t v;
      if (!parse_int(tok, v)) fail("bad integer " + quoted(tok));
      return double(v);
    }
    double v;
    if (!parse_double(tok, v)) fail("bad number " + quoted(tok));
    return v;
  }
  std::int64_t integer(PlyType t) {
    (void)t;
    const std::string_view tok = token();
    std::int64_t v;
    if (!parse_int(tok, v)) fail("bad integer " + quoted(tok));
    return v;
  }
  void skip(PlyType) { token(); }

 private:
  const std::string& path_;
  TokenStream ts_;
  std::size_t line_base_;
};

class BinarySource {
 public:
  BinarySource(const std::string& path, std::string_view data, std::size_t offset, bool big)
      : path_(path), data_(data), pos_(offset), big_(big) {}
  Context ctx;

  void mark() { start_ = pos_; }  // start of the current element instance
  [[noreturn]] void fail(const std::string& what) const {
    io::fail(path_, ctx.describe() + " (byte offset " + std::to_string(start_) + "): " + what);
  }
  double scalar(PlyType t) {
    const char* p = take(type_size(t));
    switch (t) {
      case PlyType::i8: return double(load_scalar<std::int8_t>(p, big_));
      case PlyType::u8: return double(load_scalar<std::uint8_t>(p, big_));
      case PlyType::i16: return double(load_scalar<std::int16_t>(p, big_));
      case PlyType::u16: return double(load_scalar<std::uint16_t>(p, big_));
      case PlyType::i32: return double(load_scalar<std::int32_t>(p, big_));
      case PlyType::u32: return double(load_scalar<std::uint32_t>(p, big_));
      case PlyType::f32: return double(load_scalar<float>(p, big_));
      case PlyType::f64: return load_scalar<double>(p, big_);
    }
    return 0.0;
  }
  std::int64_t integer(PlyType t) { return std::int64_t(scalar(t)); }  // integer types only: exact
  void skip(PlyType t) { take(type_size(t)); }

 private:
  const char* take(std::size_t n) {
    if (pos_ + n > data_.size())
      fail("unexpected end of file: truncated binary data (" + std::to_string(data_.size()) + " bytes)");
    const char* p = data_.data() + pos_;
    pos_ += n;
    return p;
  }
  const std::string& path_;
  std::string_view data_;
  std::size_t pos_, start_ = 0;
  bool big_;
};

struct Header {
  Format format = Format::ascii;
  std::vector<Element> elements;
  std::size_t lines = 0;        // header lines, for ASCII line numbers
  std::size_t body_offset = 0;  // first byte after end_header
};

Header read_header(const std::string& path, std::string_view data) {
  Header h;
  LineCursor lines(data);
  std::string_view line;
  if (!lines.next(line) || trim(line) != "ply") fail_at_line(path, 1, "not a PLY file (first line must be 'ply')");
  bool have_format = false;
  for (;;) {
    if (!lines.next(line)) fail_at_line(path, lines.line(), "unexpected end of file in header (no 'end_header')");
    const std::size_t ln = lines.line();
    Tokens tokens(line);
    std::string_view kw, a, b, c, d;
    if (!tokens.next(kw)) continue;
    if (kw == "end_header") break;
    if (kw == "comment" || kw == "obj_info") continue;
    if (kw == "format") {
      if (!tokens.next(a) || !tokens.next(b)) fail_at_line(path, ln, "incomplete format line");
      if (a == "ascii") h.format = Format::ascii;
      else if (a == "binary_little_endian") h.format = Format::little;
      else if (a == "binary_big_endian") h.format = Format::big;
      else fail_at_line(path, ln, "unknown PLY format " + quoted(a));
      if (b != "1.0" && b != "1") fail_at_line(path, ln, "unsupported PLY version " + quoted(b));
      have_format = true;
    } else if (kw == "element") {
      std::int64_t n;
      if (!tokens.next(a) || !tokens.next(b)) fail_at_line(path, ln, "incomplete element line");
      if (!parse_int(b, n) || n < 0) fail_at_line(path, ln, "bad element count " + quoted(b));
      // Every instance takes at least one byte: larger counts are corrupt, not a reason to allocate.
      if (std::uint64_t(n) > data.size())
        fail_at_line(path, ln, "element count " + std::to_string(n) + " exceeds what the file can hold");
      h.elements.push_back({std::string(a), std::uint64_t(n), {}});
    } else if (kw == "property") {
      if (h.elements.empty()) fail_at_line(path, ln, "property before any element");
      Property p;
      if (!tokens.next(a)) fail_at_line(path, ln, "incomplete property line");
      if (a == "list") {
        if (!tokens.next(b) || !tokens.next(c) || !tokens.next(d)) fail_at_line(path, ln, "incomplete list property");
        if (!parse_type(b, p.count_type)) fail_at_line(path, ln, "unknown type " + quoted(b));
        if (!is_integer(p.count_type)) fail_at_line(path, ln, "list count type must be an integer type");
        if (!parse_type(c, p.type)) fail_at_line(path, ln, "unknown type " + quoted(c));
        p.list = true;
        p.name = std::string(d);
      } else {
        if (!tokens.next(b)) fail_at_line(path, ln, "incomplete property line");
        if (!parse_type(a, p.type)) fail_at_line(path, ln, "unknown type " + quoted(a));
        p.name = std::string(b);
      }
      h.elements.back().props.push_back(std::move(p));
    } else {
      fail_at_line(path, ln, "unknown header line " + quoted(kw));
    }
  }
  if (!have_format) fail(path, "PLY header has no 'format' line");
  h.lines = lines.line();
  h.body_offset = lines.offset();
  return h;
}

// Property positions inside the vertex and face elements.
struct Layout {
  int vertex = -1, face = -1;  // element indices
  int xyz[3] = {-1, -1, -1};
  int indices = -1;
};

Layout find_layout(const std::string& path, const Header& h) {
  Layout L;
  for (std::size_t e = 0; e < h.elements.size(); ++e) {
    const Element& el = h.elements[e];
    if (el.name == "vertex" && L.vertex < 0) {
      L.vertex = int(e);
      for (std::size_t p = 0; p < el.props.size(); ++p)
        for (int a = 0; a < 3; ++a)
          if (el.props[p].name == std::string(1, char('x' + a)) && !el.props[p].list) L.xyz[a] = int(p);
      for (int a = 0; a < 3; ++a)
        if (L.xyz[a] < 0) fail(path, std::string("PLY element 'vertex' has no scalar property '") + char('x' + a) + "'");
    } else if (el.name == "face" && L.face < 0) {
      L.face = int(e);
      for (std::size_t p = 0; p < el.props.size(); ++p)
        if (el.props[p].list && (el.props[p].name == "vertex_indices" || el.props[p].name == "vertex_index"))
          L.indices = int(p);
      if (L.indices < 0) fail(path, "PLY element 'face' has no list property 'vertex_indices'");
      if (!is_integer(el.props[std::size_t(L.indices)].type)) fail(path, "PLY face indices must have an integer type");
    }
  }
  if (L.vertex < 0) fail(path, "PLY file has no 'vertex' element");
  if (L.face < 0) fail(path, "PLY file has no 'face' element");
  return L;
}

template <typename Source>
void read_body(Source& src, const Header& h, const Layout& L, LoadedMesh& m) {
  const std::uint64_t nv = h.elements[std::size_t(L.vertex)].count;
  if (nv >= std::numeric_limits<std::uint32_t>::max()) src.fail("too many vertices");
  std::vector<std::int64_t> poly;
  for (std::size_t e = 0; e < h.elements.size(); ++e) {
    const Element& el = h.elements[e];
    src.ctx.element = &el.name;
    const bool is_vertex = int(e) == L.vertex, is_face = int(e) == L.face;
    if (is_vertex) reserve_huge(m.vertices, std::size_t(el.count));
    if (is_face) reserve_huge(m.triangles, std::size_t(el.count));
    for (std::uint64_t i = 0; i < el.count; ++i) {
      src.ctx.index = i;
      if constexpr (requires { src.mark(); }) src.mark();
      double xyz[3] = {0, 0, 0};
      for (std::size_t p = 0; p < el.props.size(); ++p) {
        const Property& prop = el.props[p];
        if (prop.list) {
          const std::int64_t k = src.integer(prop.count_type);
          if (k < 0) src.fail("negative list length " + std::to_string(k));
          if (is_face && int(p) == L.indices) {
            if (k < 3) src.fail("face with " + std::to_string(k) + " vertices (needs at least 3)");
            poly.clear();
            for (std::int64_t j = 0; j < k; ++j) {
              const std::int64_t idx = src.integer(prop.type);
              if (idx < 0 || std::uint64_t(idx) >= nv)
                src.fail("vertex index " + std::to_string(idx) + " out of range (the file has " + std::to_string(nv) +
                         " vertices)");
              poly.push_back(idx);
            }
            append_fan(poly.data(), poly.size(), m.triangles);
          } else {
            for (std::int64_t j = 0; j < k; ++j) src.skip(prop.type);
          }
        } else if (is_vertex && (int(p) == L.xyz[0] || int(p) == L.xyz[1] || int(p) == L.xyz[2])) {
          const int a = int(p) == L.xyz[0] ? 0 : (int(p) == L.xyz[1] ? 1 : 2);
          xyz[a] = src.scalar(prop.type);
          if (const char* problem = coordinate_problem(xyz[a])) src.fail(problem);
        } else {
          src.skip(prop.type);
        }
      }
      if (is_vertex) m.vertices.push_back({xyz[0], xyz[1], xyz[2]});
    }
  }
}

}  // namespace

std::vector<LoadedMesh> read_ply(const std::string& path, std::string_view data) {
  const Header h = read_header(path, data);
  const Layout L = find_layout(path, h);
  LoadedMesh m;
  m.name = file_stem(path);
  if (h.format == Format::ascii) {
    AsciiSource src(path, data.substr(h.body_offset), h.lines);
    read_body(src, h, L, m);
  } else {
    BinarySource src(path, data, h.body_offset, h.format == Format::big);
    read_body(src, h, L, m);
  }
  return only_mesh(std::move(m));
}

}  // namespace pierce::io
