#include "engine/report/deformed_series.hpp"

#include <cstdio>
#include <filesystem>

#include "engine/report/output_files.hpp"
#include "fem/io/vtu_writer.hpp"

namespace softarm::engine {

std::string write_deformed_series(const std::string& directory, const fem::Mesh& mesh,
                                  const std::vector<Eigen::VectorXd>& positions, const std::vector<double>& times) {
  if (positions.empty()) return "";
  // An earlier run's frames beyond this run's count would lie about it: removed (only softarm's own names).
  std::error_code ignored;
  for (std::size_t i = positions.size();; ++i) {
    char stale[48];
    std::snprintf(stale, sizeof stale, "/frames/deformed_%03zu.vtu", i);
    if (!std::filesystem::remove(directory + stale, ignored)) break;
  }
  std::ofstream pvd = open_output_file(directory, "deformed.pvd");
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (std::size_t i = 0; i < positions.size() && i < times.size(); ++i) {
    char name[48];
    std::snprintf(name, sizeof name, "frames/deformed_%03zu.vtu", i);
    Eigen::MatrixXd x(mesh.num_nodes(), mesh.dim);
    for (int n = 0; n < mesh.num_nodes(); ++n) x.row(n) = positions[i].segment(mesh.dim * n, mesh.dim).transpose();
    fem::write_vtu(directory + "/" + name, mesh, x, {}, {});
    pvd << "    <DataSet timestep=\"" << times[i] << "\" part=\"0\" file=\"" << name << "\"/>\n";
  }
  pvd << "  </Collection>\n</VTKFile>\n";
  return ", " + directory + "/deformed.pvd";
}

}  // namespace softarm::engine
