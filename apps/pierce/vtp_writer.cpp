#include "vtp_writer.h"

#include <bit>
#include <cstring>
#include <stdexcept>

#include "base64.h"
#include "markup_text.h"

namespace pierce::cli {

namespace {

static_assert(std::endian::native == std::endian::little, "the VTP writer declares little-endian data");

template <typename T> const char* vtk_type();
template <> const char* vtk_type<double>() { return "Float64"; }
template <> const char* vtk_type<std::int32_t>() { return "Int32"; }
template <> const char* vtk_type<std::uint32_t>() { return "UInt32"; }
template <> const char* vtk_type<std::uint8_t>() { return "UInt8"; }
template <> const char* vtk_type<std::int64_t>() { return "Int64"; }

// Arrays are written inline, base64-encoded: the UInt64 byte count and the data in one stream,
// as VTK writes them. (Appended data, raw or encoded, trips the expat-based parser of Debian's
// VTK 9.2 / ParaView 5.11 at random positions; inline data is plain XML text.)
class Writer {
 public:
  explicit Writer(std::FILE* f) : f_(f) {}

  template <typename T>
  void array(const std::string& name, const std::vector<T>& v, int components = 1) {
    std::fprintf(f_, "        <DataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%d\" format=\"binary\">\n          ",
                 vtk_type<T>(), name.c_str(), components);
    const std::uint64_t bytes = v.size() * sizeof(T);
    std::vector<unsigned char> block(sizeof bytes + bytes);
    std::memcpy(block.data(), &bytes, sizeof bytes);
    if (bytes) std::memcpy(block.data() + sizeof bytes, v.data(), bytes);
    const std::string text = base64(block.data(), block.size());
    std::fwrite(text.data(), 1, text.size(), f_);
    std::fputs("\n        </DataArray>\n", f_);
  }

  bool finish() {
    std::fputs("</VTKFile>\n", f_);
    return !std::ferror(f_);
  }

 private:
  std::FILE* f_;
};

std::size_t size_of(const DataArray& a) {
  return std::visit([](const auto& v) { return v.size(); }, a);
}

}  // namespace

bool write_vtp(std::FILE* out, const PolyData& d) {
  for (const auto& [name, a] : d.point_data)
    if (size_of(a) != d.points.size()) throw std::invalid_argument("VTP point array " + name + " has the wrong length");
  for (const auto& [name, a] : d.cell_data)
    if (size_of(a) != d.triangles.size()) throw std::invalid_argument("VTP cell array " + name + " has the wrong length");

  // Flattened copies kept alive until the appended block is written.
  std::vector<double> coords;
  coords.reserve(d.points.size() * 3);
  for (const Vec3d& p : d.points) coords.insert(coords.end(), {p.x, p.y, p.z});
  std::vector<std::int64_t> connectivity, offsets;
  connectivity.reserve(d.triangles.size() * 3);
  for (const Tri& t : d.triangles) {
    for (auto v : t) connectivity.push_back(std::int64_t(v));
    offsets.push_back(std::int64_t(connectivity.size()));
  }

  std::fputs("<?xml version=\"1.0\"?>\n"
             "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
             "  <PolyData>\n",
             out);
  std::fprintf(out,
               "    <Piece NumberOfPoints=\"%zu\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
               "NumberOfPolys=\"%zu\">\n",
               d.points.size(), d.triangles.size());
  Writer w(out);
  auto arrays = [&](const char* tag, const std::vector<std::pair<std::string, DataArray>>& list) {
    if (list.empty()) return;
    std::fprintf(out, "      <%s Scalars=\"%s\">\n", tag, markup_escaped(list.front().first).c_str());
    for (const auto& [name, a] : list) std::visit([&, &n = name](const auto& v) { w.array(markup_escaped(n), v); }, a);
    std::fprintf(out, "      </%s>\n", tag);
  };
  arrays("PointData", d.point_data);
  arrays("CellData", d.cell_data);
  std::fputs("      <Points>\n", out);
  w.array("Points", coords, 3);
  std::fputs("      </Points>\n      <Polys>\n", out);
  w.array("connectivity", connectivity);
  w.array("offsets", offsets);
  std::fputs("      </Polys>\n    </Piece>\n  </PolyData>\n", out);
  return w.finish();
}

}  // namespace pierce::cli
