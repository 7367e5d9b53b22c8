// VTK XML UnstructuredGrid (.vtu) writer: Float64 points, tets as cell type
// 10, and an Int32 cell array "label". Binary output is inline base64 with a
// UInt64 byte-count header, which VTK, ParaView and meshio read.

#include "tet_formats_internal.h"

#include <mr/io/output_file.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

namespace mr::plugins::tet {
namespace {

// Streams bytes as base64 text, 3 input bytes to 4 characters.
class Base64Writer {
 public:
  explicit Base64Writer(io::OutputFile& out) : out_(out) {}

  void put(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      carry_[carried_++] = bytes[i];
      if (carried_ == 3) emit(3);
    }
  }
  void finish() {
    if (carried_ > 0) emit(carried_);
  }

 private:
  void emit(int count) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (int i = count; i < 3; ++i) carry_[i] = 0;
    const std::uint32_t v = (std::uint32_t(carry_[0]) << 16) | (std::uint32_t(carry_[1]) << 8) | carry_[2];
    char quad[4] = {kAlphabet[(v >> 18) & 63], kAlphabet[(v >> 12) & 63], kAlphabet[(v >> 6) & 63],
                    kAlphabet[v & 63]};
    if (count < 3) quad[3] = '=';
    if (count < 2) quad[2] = '=';
    out_.write_raw(quad, 4);
    carried_ = 0;
  }

  io::OutputFile& out_;
  unsigned char carry_[3] = {};
  int carried_ = 0;
};

template <class T>
const char* vtk_type_name() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
  if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
  if constexpr (std::is_same_v<T, std::uint8_t>) return "UInt8";
}

// Writes one DataArray whose `count` values are value(0) .. value(count - 1).
template <class T, class ValueAt>
void write_array(io::OutputFile& out, bool binary, const char* name, int components, std::size_t count,
                 const ValueAt& value) {
  out << "        <DataArray type=\"" << vtk_type_name<T>() << "\" Name=\"" << name;
  out << "\" NumberOfComponents=\"" << components
      << (binary ? "\" format=\"binary\">\n" : "\" format=\"ascii\">\n");
  if (binary) {
    Base64Writer base64(out);
    const std::uint64_t byte_count = count * sizeof(T);
    base64.put(&byte_count, sizeof(byte_count));
    std::vector<T> chunk;
    chunk.reserve(std::min<std::size_t>(count, 1 << 16));
    for (std::size_t i = 0; i < count; i += chunk.size()) {
      chunk.clear();
      for (std::size_t j = i; j < count && chunk.size() < chunk.capacity(); ++j) chunk.push_back(value(j));
      base64.put(chunk.data(), chunk.size() * sizeof(T));
    }
    base64.finish();
  } else {
    for (std::size_t i = 0; i < count; ++i) {
      if constexpr (std::is_floating_point_v<T>) {
        out << value(i);
      } else {
        out << static_cast<std::int64_t>(value(i));
      }
      out << ((i + 1) % static_cast<std::size_t>(components) == 0 ? "\n" : " ");
    }
  }
  out << "\n        </DataArray>\n";
}

}  // namespace

void write_vtu(const TetMesh& mesh, const std::filesystem::path& path, const io::WriteOptions& options) {
  const bool binary = options.binary;
  const std::size_t points = mesh.positions.size(), cells = mesh.tets.size();
  io::OutputFile out(path);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"";
  out << (std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian");
  out << "\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"";
  out << static_cast<std::int64_t>(points) << "\" NumberOfCells=\"" << static_cast<std::int64_t>(cells);
  out << "\">\n      <Points>\n";
  write_array<double>(out, binary, "Points", 3, 3 * points,
                      [&](std::size_t i) { return mesh.positions[i / 3][static_cast<int>(i % 3)]; });
  out << "      </Points>\n      <Cells>\n";
  write_array<std::int64_t>(out, binary, "connectivity", 1, 4 * cells,
                            [&](std::size_t i) { return std::int64_t(mesh.tets[i / 4][i % 4]); });
  write_array<std::int64_t>(out, binary, "offsets", 1, cells,
                            [](std::size_t i) { return std::int64_t(4 * (i + 1)); });
  write_array<std::uint8_t>(out, binary, "types", 1, cells, [](std::size_t) { return std::uint8_t{10}; });
  out << "      </Cells>\n      <CellData Scalars=\"label\">\n";
  write_array<std::int32_t>(out, binary, "label", 1, cells,
                            [&](std::size_t i) { return mesh.has_tet_labels() ? mesh.tet_labels[i] : 0; });
  out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  out.close();
}

}  // namespace mr::plugins::tet
