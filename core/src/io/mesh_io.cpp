#include "pierce/io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "io_util.h"
#include "readers.h"

namespace pierce {

namespace io {

[[noreturn]] void fail_at_line(const std::string& path, std::size_t line, const std::string& what) {
  throw InputError(path + ":" + std::to_string(line) + ": " + what);
}

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw InputError(path + ": " + what); }

std::string quoted(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string s(token.substr(0, kMax));
  if (token.size() > kMax) s += "...";
  for (char& c : s)
    if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
  return "'" + s + "'";
}

void require_regular_file(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) fail(path, "cannot open file (no such file)");
  if (std::filesystem::is_directory(status)) fail(path, "is a directory, not a file");
  if (!std::filesystem::is_regular_file(status)) fail(path, "cannot read: not a regular file");
}

FileBytes read_file(const std::string& path) {
  require_regular_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open file (") + std::strerror(errno) + ")");
  FileBytes data;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) fail(path, "cannot read file");
  data.resize(std::size_t(size));
  in.seekg(0);
  in.read(data.data(), size);
  if (in.gcount() != size) fail(path, "read error");
  return data;
}

std::string file_stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

}  // namespace io

std::vector<LoadedMesh> load_mesh_file(const std::string& path) {
  io::require_regular_file(path);
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  using Reader = std::vector<LoadedMesh> (*)(const std::string&, std::string_view);
  Reader reader = nullptr;
  if (ext == ".stl") reader = io::read_stl;
  else if (ext == ".obj") reader = io::read_obj;
  else if (ext == ".off") reader = io::read_off;
  else if (ext == ".ply") reader = io::read_ply;
  else
    io::fail(path, "unknown model format " + (ext.empty() ? std::string("(no extension)") : io::quoted(ext)) +
                       " (expected .stl, .obj, .off or .ply)");
  const io::FileBytes bytes = io::read_file(path);
  const std::string_view data(bytes.data(), bytes.size());
  if (io::trim(data).empty()) io::fail(path, "file is empty");
  std::vector<LoadedMesh> meshes = reader(path, data);
  std::size_t faces = 0;
  for (const LoadedMesh& m : meshes) faces += m.triangles.size();
  if (faces == 0) io::fail(path, "no faces found");
  return meshes;
}

void add_model_files(Scene& scene, const std::vector<std::string>& paths) {
  for (const std::string& path : paths)
    for (LoadedMesh& m : load_mesh_file(path))
      scene.add_mesh(std::move(m.vertices), std::move(m.triangles), std::move(m.name), path);
}

}  // namespace pierce
