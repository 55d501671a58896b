#include "fem/scenes/cell_supports.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fem/forms/mean_displacement_form.hpp"

namespace softarm::fem {

double stiffest_silicone_shear_modulus(const Mesh& mesh, const std::vector<Material>& materials) {
  double mu = 0;
  for (std::size_t p = 0; p < materials.size(); ++p)
    if (mesh.part_names[p] != "rings") mu = std::max(mu, materials[p].law->initial_shear_modulus());
  return mu;
}

InPlaneHold hold_in_plane_rigid_motion(const Mesh& mesh, const std::vector<int>& face, bool half, double mu,
                                       DirichletConstraints& bc) {
  std::vector<char> on_symmetry(mesh.num_nodes(), 0);
  if (const auto it = mesh.node_sets.find("symmetry"); it != mesh.node_sets.end())
    for (int n : it->second) on_symmetry[n] = 1;
  InPlaneHold hold;
  int far = -1;
  double best = std::numeric_limits<double>::infinity(), farthest = -1;
  for (int n : face) {
    const double r = mesh.X.row(n).head<2>().norm();
    if ((!half || on_symmetry[n]) && r < best) best = r, hold.centre = n;
    if (r > farthest) farthest = r, far = n;
  }
  const double penalty = mu * 1.0 * static_cast<double>(face.size());  // N/mm
  for (int direction = 0; direction < (half ? 1 : 2); ++direction) {
    std::vector<int> dofs;
    std::vector<double> reference;
    for (int n : face) dofs.push_back(3 * n + direction), reference.push_back(mesh.X(n, direction));
    hold.forms.push_back(std::make_shared<MeanDisplacementForm>(std::move(dofs), std::move(reference), penalty));
  }
  if (!half) {
    const bool along_x = std::abs(mesh.X(far, 0)) < std::abs(mesh.X(far, 1));
    bc.fix(3 * far + (along_x ? 0 : 1));
  }
  return hold;
}

}  // namespace softarm::fem
