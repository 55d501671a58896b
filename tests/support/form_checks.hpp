#pragma once
// The finite-difference checks shared by the axisymmetric (test_forms.cpp) and
// the 3D (test_solid3d.cpp) forms: the laws and volumetric treatments every
// elastic form runs through, and a chamber's pressure form checked on its own.
#include <catch2/catch.hpp>
#include <memory>
#include <string>
#include <vector>

#include "fem/forms/elastic_form.hpp"
#include "fem/forms/chamber_pressure_form.hpp"
#include "test_problems.hpp"

namespace softarm::test {

struct FormCase {
  const char* name;
  fem::Material material;
  fem::VolumetricTreatment treatment;
};

/// The thesis' Ogden silicone both ways, a nearly incompressible neo-Hookean and the
/// St Venant–Kirchhoff ABS, which has no volumetric split.
inline std::vector<FormCase> form_cases() {
  using fem::VolumetricTreatment;
  return {
      {"Ogden DS30, projected dilatation", dragon_skin_30_ogden(2.0 / 0.7029), VolumetricTreatment::projected_dilatation},
      {"Ogden DS30, pointwise", dragon_skin_30_ogden(2.0 / 0.7029), VolumetricTreatment::pointwise},
      {"neo-Hookean nearly incompressible", neo_hookean(1.0, 1000.0), VolumetricTreatment::projected_dilatation},
      {"St Venant-Kirchhoff (ABS)", abs_plastic(), VolumetricTreatment::projected_dilatation},
  };
}

/// A chamber's pressure form alone (so that its load stiffness is not hidden behind an
/// elastic one), at pressure p, on a mesh without constraints.
struct PressureOnly {
  fem::LoadState load;
  std::shared_ptr<fem::ChamberPressureForm> chamber;
  std::unique_ptr<fem::EnergyProblem> problem;
  PressureOnly(const fem::Mesh& mesh, double p) {
    load.chamber_pressure_MPa = {p};
    problem = std::make_unique<fem::EnergyProblem>(fem::flattened_positions(mesh), fem::DirichletConstraints{});
    chamber = std::make_shared<fem::ChamberPressureForm>(mesh, 0, load);
    problem->add_form(chamber);
    problem->finalize();
  }

  /// Gradient and Hessian against central differences (test_forms.cpp's 1e-6) at a
  /// random perturbation of the reference state, and the gradient equal to −p ∂V/∂x.
  void check_derivatives(double amplitude, const std::string& label) const {
    const fem::Vector x = perturbed(problem->reference_positions(), amplitude, 11);
    const auto err = finite_difference_errors(*problem, x, 1e-6);
    INFO(label << ": gradient error " << err.gradient << ", Hessian error " << err.hessian);
    CHECK(err.gradient < 1e-6);
    CHECK(err.hessian < 1e-6);
    const auto e = problem->evaluate(x, true, false);
    CHECK((e.gradient + load.chamber_pressure_MPa[0] * chamber->volume_gradient(x)).norm() < 1e-12 * e.gradient.norm());
  }
};

}  // namespace softarm::test
