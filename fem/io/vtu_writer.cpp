#include "fem/io/vtu_writer.hpp"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <unistd.h>

namespace softarm::fem {
namespace {

constexpr int vtk_quad = 9, vtk_hexahedron = 12, vtk_quadratic_hexahedron = 25, vtk_biquadratic_quad = 28,
              vtk_triquadratic_hexahedron = 29;

int vtk_cell_type(const Mesh& mesh) {
  if (mesh.dim == 2 && mesh.nodes_per_element == 4) return vtk_quad;
  if (mesh.dim == 2 && mesh.nodes_per_element == 9) return vtk_biquadratic_quad;  // corners, mid-edges, centre
  if (mesh.dim == 3 && mesh.nodes_per_element == 8) return vtk_hexahedron;
  if (mesh.dim == 3 && mesh.nodes_per_element == 20) return vtk_quadratic_hexahedron;  // Hex27's first 20 nodes
  if (mesh.dim == 3 && mesh.nodes_per_element == 27) return vtk_triquadratic_hexahedron;  // fem/elements/hexahedron.hpp order
  throw std::invalid_argument("write_vtu: unsupported element (dim " + std::to_string(mesh.dim) + ", " +
                              std::to_string(mesh.nodes_per_element) + " nodes)");
}

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
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

/// Appends the shortest decimal text that reads back as exactly `x`.
void append_number(std::string& out, double x) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, result.ptr);
}
void append_number(std::string& out, long long x) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, result.ptr);
}

class VtuText {
 public:
  void open_array(const std::string& type, const std::string& name, int components) {
    text_ += "        <DataArray type=\"" + type + "\"";
    if (!name.empty()) text_ += " Name=\"" + xml_escaped(name) + "\"";
    text_ += " NumberOfComponents=\"" + std::to_string(components) + "\" format=\"ascii\">\n";
  }
  void close_array() { text_ += "        </DataArray>\n"; }
  /// One tuple of `components` numbers per line.
  template <class Number>
  void tuples(const std::vector<Number>& values, int components) {
    for (std::size_t i = 0; i < values.size(); ++i) {
      text_ += i % static_cast<std::size_t>(components) == 0 ? "          " : " ";
      append_number(text_, values[i]);
      if ((i + 1) % static_cast<std::size_t>(components) == 0) text_ += '\n';
    }
  }
  void line(const std::string& s) { text_ += s + '\n'; }
  /// The document's head, up to the piece of `points` points and `cells` cells.
  void open_piece(std::size_t points, std::size_t cells) {
    line("<?xml version=\"1.0\"?>");
    line("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">");
    line("  <UnstructuredGrid>");
    line("    <Piece NumberOfPoints=\"" + std::to_string(points) + "\" NumberOfCells=\"" + std::to_string(cells) + "\">");
  }
  /// The points (3 per point) and the cells: connectivity (`per_row` a line), end offsets, VTK types.
  void points_and_cells(const std::vector<double>& xyz, const std::vector<long long>& connectivity, int per_row,
                        const std::vector<long long>& offsets, const std::vector<long long>& types) {
    line("      <Points>");
    open_array("Float64", "", 3);
    tuples(xyz, 3);
    close_array();
    line("      </Points>");
    line("      <Cells>");
    open_array("Int64", "connectivity", 1);
    tuples(connectivity, per_row);
    close_array();
    open_array("Int64", "offsets", 1);
    tuples(offsets, 1);
    close_array();
    open_array("UInt8", "types", 1);
    tuples(types, 1);
    close_array();
    line("      </Cells>");
  }
  /// Closes the piece and the document; its whole text.
  const std::string& close_piece() {
    line("    </Piece>");
    line("  </UnstructuredGrid>");
    line("</VTKFile>");
    return text_;
  }

 private:
  std::string text_;
};

/// Points or point vectors of a dim-2 or dim-3 matrix, in 3D (x = r, y = 0, z = z for dim 2).
std::vector<double> as_3d(const Eigen::MatrixXd& m) {
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(m.rows()) * 3);
  for (Eigen::Index n = 0; n < m.rows(); ++n) {
    if (m.cols() == 2) out.insert(out.end(), {m(n, 0), 0.0, m(n, 1)});
    else out.insert(out.end(), {m(n, 0), m(n, 1), m(n, 2)});
  }
  return out;
}

void check_fields(const std::vector<NamedField>& fields, std::size_t count, const char* where,
                  std::set<std::string>& names) {
  for (const auto& f : fields) {
    if (f.name.empty() || f.components < 1)
      throw std::invalid_argument(std::string("write_vtu: ") + where + " field needs a name and >= 1 component");
    if (!names.insert(f.name).second)
      throw std::invalid_argument("write_vtu: field name '" + f.name + "' is used twice or reserved");
    if (f.values.size() != count * static_cast<std::size_t>(f.components))
      throw std::invalid_argument("write_vtu: " + std::string(where) + " field '" + f.name + "' has " +
                                  std::to_string(f.values.size()) + " values, expected " +
                                  std::to_string(count * static_cast<std::size_t>(f.components)));
  }
}

std::string vtu_document(const Mesh& mesh, const Eigen::MatrixXd& x, const std::vector<NamedField>& point_fields,
                         const std::vector<NamedField>& cell_fields) {
  const int cell_type = vtk_cell_type(mesh);
  const auto num_nodes = static_cast<std::size_t>(mesh.num_nodes());
  const auto num_cells = static_cast<std::size_t>(mesh.num_elements());
  if (x.rows() != mesh.X.rows() || x.cols() != mesh.X.cols() || mesh.X.cols() != mesh.dim)
    throw std::invalid_argument("write_vtu: current positions are " + std::to_string(x.rows()) + " x " +
                                std::to_string(x.cols()) + ", the mesh has " + std::to_string(num_nodes) + " x " +
                                std::to_string(mesh.dim));
  if (mesh.part.size() != num_cells) throw std::invalid_argument("write_vtu: mesh.part has the wrong size");
  std::set<std::string> names{"displacement"};
  check_fields(point_fields, num_nodes, "point", names);
  names = {"part"};
  check_fields(cell_fields, num_cells, "cell", names);

  VtuText out;
  out.open_piece(num_nodes, num_cells);

  auto write_fields = [&out](const std::vector<NamedField>& fields) {
    for (const auto& f : fields) {
      out.open_array("Float64", f.name, f.components);
      out.tuples(f.values, f.components);
      out.close_array();
    }
  };
  out.line("      <PointData Vectors=\"displacement\">");
  out.open_array("Float64", "displacement", 3);
  out.tuples(as_3d(x - mesh.X), 3);
  out.close_array();
  write_fields(point_fields);
  out.line("      </PointData>");

  out.line("      <CellData Scalars=\"part\">");
  out.open_array("Int32", "part", 1);
  out.tuples(std::vector<long long>(mesh.part.begin(), mesh.part.end()), 1);
  out.close_array();
  write_fields(cell_fields);
  out.line("      </CellData>");

  const int npe = mesh.nodes_per_element;
  std::vector<long long> offsets, types(num_cells, cell_type);
  for (std::size_t e = 1; e <= num_cells; ++e) offsets.push_back(static_cast<long long>(e) * npe);
  out.points_and_cells(as_3d(x), std::vector<long long>(mesh.connectivity.begin(), mesh.connectivity.end()), npe,
                       offsets, types);
  return out.close_piece();
}

/// Polylines: one VTK_POLY_LINE cell per line, its points in order; `per_line` as cell data.
std::string polyline_document(const std::vector<std::vector<Eigen::Vector3d>>& lines, const NamedField& per_line) {
  if (per_line.components != 1 || per_line.values.size() != lines.size() || per_line.name.empty())
    throw std::invalid_argument("write_polyline_vtu: one named value per line expected, got " +
                                std::to_string(per_line.values.size()) + " for " + std::to_string(lines.size()) + " lines");
  std::vector<double> points;
  std::vector<long long> connectivity, offsets;
  for (const auto& line : lines) {
    for (const Eigen::Vector3d& p : line) {
      connectivity.push_back(static_cast<long long>(points.size() / 3));
      points.insert(points.end(), {p.x(), p.y(), p.z()});
    }
    offsets.push_back(static_cast<long long>(connectivity.size()));
  }
  constexpr int vtk_poly_line = 4;
  VtuText out;
  out.open_piece(points.size() / 3, lines.size());
  out.line("      <CellData Scalars=\"" + xml_escaped(per_line.name) + "\">");
  out.open_array("Float64", per_line.name, 1);
  out.tuples(per_line.values, 1);
  out.close_array();
  out.line("      </CellData>");
  out.points_and_cells(points, connectivity, 1, offsets, std::vector<long long>(lines.size(), vtk_poly_line));
  return out.close_piece();
}

/// Points: one VTK_VERTEX cell per point; `fields` as point data.
std::string point_cloud_document(const std::vector<Eigen::Vector3d>& cloud, const std::vector<NamedField>& fields) {
  for (const NamedField& f : fields)
    if (f.name.empty() || f.components < 1 || f.values.size() != cloud.size() * static_cast<std::size_t>(f.components))
      throw std::invalid_argument("write_point_cloud_vtu: field '" + f.name + "' needs a name and " +
                                  std::to_string(f.components) + " values per point");
  std::vector<double> points;
  std::vector<long long> connectivity, offsets;
  for (const Eigen::Vector3d& p : cloud) {
    connectivity.push_back(static_cast<long long>(points.size() / 3));
    points.insert(points.end(), {p.x(), p.y(), p.z()});
    offsets.push_back(static_cast<long long>(connectivity.size()));
  }
  constexpr int vtk_vertex = 1;
  VtuText out;
  out.open_piece(cloud.size(), cloud.size());
  out.line("      <PointData>");
  for (const NamedField& f : fields) {
    out.open_array("Float64", f.name, f.components);
    out.tuples(f.values, f.components);
    out.close_array();
  }
  out.line("      </PointData>");
  out.points_and_cells(points, connectivity, 1, offsets, std::vector<long long>(cloud.size(), vtk_vertex));
  return out.close_piece();
}

/// Writes `text` to `path` through a temporary file in the same folder and a rename, so that a
/// reader never sees half a file; missing parent folders are created.
void write_atomically(const std::string& path, const std::string& text, const char* who) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  std::error_code ignored;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ignored);
  // Same folder, so the rename is atomic; the pid keeps concurrent writers apart.
  const fs::path temporary = target.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << text;
    file.close();
    if (!file) {
      fs::remove(temporary, ignored);
      throw std::runtime_error(std::string(who) + ": cannot write '" + path + "'");
    }
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    fs::remove(temporary, ignored);
    throw std::runtime_error(std::string(who) + ": cannot move the output into '" + path + "': " + error.message());
  }
}

}  // namespace

void write_vtu(const std::string& path, const Mesh& mesh, const Eigen::MatrixXd& current_positions,
               const std::vector<NamedField>& point_fields, const std::vector<NamedField>& cell_fields) {
  write_atomically(path, vtu_document(mesh, current_positions, point_fields, cell_fields), "write_vtu");
}

void write_polyline_vtu(const std::string& path, const std::vector<std::vector<Eigen::Vector3d>>& lines,
                        const NamedField& per_line) {
  write_atomically(path, polyline_document(lines, per_line), "write_polyline_vtu");
}

void write_point_cloud_vtu(const std::string& path, const std::vector<Eigen::Vector3d>& points,
                           const std::vector<NamedField>& point_fields) {
  write_atomically(path, point_cloud_document(points, point_fields), "write_point_cloud_vtu");
}

}  // namespace softarm::fem
