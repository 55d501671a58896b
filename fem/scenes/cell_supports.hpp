#pragma once
// What the 3CA's cells (tca_cell.hpp, tca_end_cell.hpp) share: the scale of their
// faces' penalties and the supports that hold a face's in-plane rigid motion.
#include <memory>
#include <vector>

#include "fem/assembly/energy_problem.hpp"
#include "fem/forms/form.hpp"
#include "fem/materials/material.hpp"
#include "fem/mesh/mesh.hpp"

namespace softarm::fem {

/// A plane face's penalty per node: this many times the stiffest silicone's initial shear
/// modulus times 1 mm (plane_face_form.hpp).
constexpr double kPlanePenaltyRatio = 1e4;

/// The initial shear modulus of the stiffest part but the rings (the penalties' scale).
double stiffest_silicone_shear_modulus(const Mesh& mesh, const std::vector<Material>& materials);

/// How a face's in-plane rigid motion is held (hold_in_plane_rigid_motion).
struct InPlaneHold {
  /// The face's node nearest the axis (in a half model, on the mirror plane): the point a cut face's
  /// plane is referenced to (PlaneFaceForm's reference node).
  int centre = -1;
  /// Forms to add to the problem: the face's mean in-plane displacement held.
  std::vector<std::shared_ptr<Form>> forms;
};

/// Holds the in-plane rigid motion of a face whose normal motion is held otherwise, where the
/// body's energy is invariant under in-plane translations: the translation by the face's mean
/// displacement along x (and y in a full model; a half model's mirror plane holds y) with the
/// penalty `mu`·(1 mm) per face node (mean_displacement_form.hpp: no force at equilibrium, and no
/// soft mode like a single held node's); in a full model the rotation about z by the face's node
/// farthest from the axis, held in its tangential direction in `bc`. `mu`: the silicone's shear
/// modulus, MPa.
InPlaneHold hold_in_plane_rigid_motion(const Mesh& mesh, const std::vector<int>& face, bool half, double mu,
                                       DirichletConstraints& bc);

}  // namespace softarm::fem
