#pragma once
// ParaView output: a mesh in its current configuration, with point and cell
// data, as a VTK XML unstructured grid (.vtu, ASCII).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

/// A field to write: `components` values per point (or per cell), point-major.
/// Axisymmetric vectors are best written with 3 components (x = r, y = 0, z = z),
/// the frame the points are written in, so that ParaView can draw them.
struct NamedField {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

/// Writes `mesh` at `current_positions` (same shape as mesh.X) to `path`.
/// Axisymmetric meshes (dim 2) are drawn in the x–z plane (x = r, y = 0, z = z)
/// as VTK_QUAD cells (collapsed quads stay quads); 3D meshes of 8-node
/// hexahedra (VTK node order) as VTK_HEXAHEDRON. Always adds point data
/// "displacement" (current − reference, 3 components) and cell data "part"
/// (the part index), so these two names are reserved. The file is written to a
/// temporary name in the same folder and renamed, so a reader never sees half a
/// file; missing parent folders are created. Throws std::invalid_argument for
/// inconsistent sizes or names and std::runtime_error when the file cannot be written.
void write_vtu(const std::string& path, const Mesh& mesh, const Eigen::MatrixXd& current_positions,
               const std::vector<NamedField>& point_fields, const std::vector<NamedField>& cell_fields);

/// Polylines, e.g. a rod's centreline at each output state, as VTK_POLY_LINE cells (line i's points
/// in order, mm), with `per_line` (one component, one value per line: "pressure_kPa") as cell data
/// for ParaView to colour or threshold the states by. Written as write_vtu writes; throws
/// std::invalid_argument when `per_line` does not give one value per line.
void write_polyline_vtu(const std::string& path, const std::vector<std::vector<Eigen::Vector3d>>& lines,
                        const NamedField& per_line);

/// A cloud of points (mm), each its own VTK_VERTEX cell so that ParaView draws it, with `point_fields`
/// (one tuple per point) as point data: a workspace's tips with their pressures. Written as write_vtu
/// writes; throws std::invalid_argument for a field of the wrong size or without a name.
void write_point_cloud_vtu(const std::string& path, const std::vector<Eigen::Vector3d>& points,
                           const std::vector<NamedField>& point_fields);

}  // namespace softarm::fem
