#pragma once
// What the 3CA's cells (tca_cell.hpp, tca_end_cell.hpp) share: the scale of their
// faces' penalties and the supports that hold a face's in-plane rigid motion.
#include <vector>

#include "fem/assembly/energy_problem.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

/// A plane face's penalty per node: this many times the stiffest silicone's initial shear
/// modulus times 1 mm (plane_face_form.hpp).
constexpr double kPlanePenaltyRatio = 1e4;

/// The initial shear modulus of the stiffest part but the rings (the penalties' scale).
double stiffest_silicone_shear_modulus(const Mesh& mesh, const std::vector<Material>& materials);

/// Holds the in-plane rigid motion of a face whose normal motion is held otherwise: the node of
/// `face` nearest the axis holds x (and y in a full model; in a half model it is taken on the
/// symmetry plane, whose nodes hold y already); in a full model the face's node farthest from the
/// axis holds its tangential direction too (rotation about z). The supports carry no force at
/// equilibrium.
void hold_in_plane_rigid_motion(const Mesh& mesh, const std::vector<int>& face, bool half, DirichletConstraints& bc);

}  // namespace softarm::fem
