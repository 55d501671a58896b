#include "engine/material_command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "fem/core/input_error.hpp"
#include "fem/core/json_reader.hpp"
#include "fem/materials/drucker_stability.hpp"
#include "fem/materials/material.hpp"
#include "fem/materials/material_fit.hpp"

namespace softarm::engine {
namespace {

using nlohmann::json;

std::string number(double x, int precision = 4) {
  if (std::isnan(x)) return "-";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  std::ostringstream s;
  s << std::setprecision(precision) << x;
  return s.str();
}

// K0 in words: a law without a volumetric term (D_per_MPa [] or [0]) is incompressible, K0 = 2/D1
// unbounded; said so rather than printed as "inf" (issue 35).
std::string bulk_modulus_text(double K0) {
  return std::isinf(K0) ? std::string("incompressible (no volumetric term)") : "K0 = " + number(K0) + " MPa";
}

json finite_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

// ---------------------------------------------------------------- list

json material_summary(const fem::Material& m) {
  return {{"name", m.name},
          {"law", m.law->kind()},
          {"mu0_MPa", finite_or_null(m.law->initial_shear_modulus())},
          {"K0_MPa", finite_or_null(m.law->initial_bulk_modulus())},
          {"density_g_cm3", m.density_g_cm3},
          {"tensile_strength_MPa", finite_or_null(m.tensile_strength_MPa)},
          {"elongation_at_break_percent", finite_or_null(m.elongation_at_break * 100.0)},
          {"coefficients", fem::material_to_json(m)}};
}

void print_list(bool as_json) {
  std::vector<const fem::Material*> materials;
  for (const auto& name : fem::builtin_material_names()) materials.push_back(&fem::builtin_material(name, "material"));
  if (as_json) {
    json out = json::array();
    for (const auto* m : materials) out.push_back(material_summary(*m));
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::cout << std::left << std::setw(16) << "name" << std::setw(24) << "law" << std::right << std::setw(10)
            << "mu0 MPa" << std::setw(10) << "K0 MPa" << std::setw(10) << "g/cm3" << std::setw(13) << "strength MPa"
            << std::setw(14) << "elongation %" << "\n";
  for (const auto* m : materials) {
    std::cout << std::left << std::setw(16) << m->name << std::setw(24) << m->law->kind() << std::right
              << std::setw(10) << number(m->law->initial_shear_modulus()) << std::setw(10)
              << (std::isinf(m->law->initial_bulk_modulus()) ? "incompr." : number(m->law->initial_bulk_modulus()))
              << std::setw(10) << number(m->density_g_cm3)
              << std::setw(13) << number(m->tensile_strength_MPa) << std::setw(14)
              << number(m->elongation_at_break * 100.0) << "\n";
  }
}

// ---------------------------------------------------------------- check

/// A built-in name, or a JSON file holding a material (a built-in name or an object).
fem::Material resolve_material(const std::string& argument) {
  const auto names = fem::builtin_material_names();
  if (std::find(names.begin(), names.end(), argument) != names.end()) return fem::builtin_material(argument, "material");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(argument, ec)) {
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
    throw fem::InputError("material", "\"" + argument + "\" is neither a built-in material (" + known +
                                          ") nor a readable JSON file");
  }
  try {
    return fem::material_from_json(fem::load_json_file(argument), "");
  } catch (const fem::InputError& e) {
    // Keep the field path, and say which file it is in.
    const std::string prefix = "input error: " + (e.field().empty() ? std::string() : "'" + e.field() + "': ");
    std::string message = e.what();
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
    if (message.find(argument) != std::string::npos) throw;
    throw fem::InputError(e.field(), message + " (in " + argument + ")");
  }
}

/// A stability bound as printed: "<= x" / ">= x" when it is the end of the scan, not a boundary.
std::string stable_from(const fem::ModeStability& s) { return (s.bounded_below ? "" : "<= ") + number(s.lambda_min, 6); }
std::string stable_to(const fem::ModeStability& s) { return (s.bounded_above ? "" : ">= ") + number(s.lambda_max, 6); }

struct CheckReport {
  fem::Material material;
  double lambda_lo = 0, lambda_hi = 0;
  double stretch_at_break = NAN;  // 1 + elongation at break
  std::vector<fem::ModeStability> modes;
  std::vector<std::string> warnings;
};

CheckReport check_material(const fem::Material& m, double lambda_lo, double lambda_hi) {
  CheckReport r;
  r.material = m;
  r.stretch_at_break = 1.0 + m.elongation_at_break;
  // Scan at least to the stretch at break, so that the warning below is decided.
  r.lambda_lo = lambda_lo;
  r.lambda_hi = std::isfinite(r.stretch_at_break) ? std::max(lambda_hi, 1.1 * r.stretch_at_break) : lambda_hi;
  r.modes = fem::drucker_stability(*m.law, r.lambda_lo, r.lambda_hi);
  for (const auto& s : r.modes) {
    if (!s.stable_at_rest) {
      r.warnings.push_back(s.mode + ": not Drucker stable even at rest (lambda = 1): the law cannot be used");
      continue;
    }
    // The burst criterion caps the largest principal stretch at 1 + elongation at break in any
    // state, so the law must stay physical up to there on every path.
    if (std::isfinite(r.stretch_at_break) && s.bounded_above && s.lambda_max < r.stretch_at_break)
      r.warnings.push_back(s.mode + ": Drucker unstable beyond stretch " + number(s.lambda_max, 5) +
                           ", below the stretch at break " + number(r.stretch_at_break, 4) +
                           ": results past it are not physical");
  }
  return r;
}

json report_json(const CheckReport& r) {
  json modes = json::array();
  for (const auto& s : r.modes)
    modes.push_back({{"mode", s.mode},
                     {"stable_at_rest", s.stable_at_rest},
                     {"lambda_min", finite_or_null(s.lambda_min)},
                     {"lambda_max", finite_or_null(s.lambda_max)},
                     {"bounded_below", s.bounded_below},
                     {"bounded_above", s.bounded_above}});
  json out = material_summary(r.material);
  out["stretch_at_break"] = finite_or_null(r.stretch_at_break);
  out["scanned_lambda"] = {r.lambda_lo, r.lambda_hi};
  out["drucker_stability"] = modes;
  out["warnings"] = r.warnings;
  return out;
}

void print_report(const CheckReport& r) {
  const auto& m = r.material;
  std::cout << "material " << m.name << ": " << m.law->kind() << ", mu0 = " << number(m.law->initial_shear_modulus())
            << " MPa, " << bulk_modulus_text(m.law->initial_bulk_modulus()) << "\n"
            << "source: " << m.source << "\n"
            << "Drucker stability (incompressible, as Abaqus checks it), stretch scanned over " << number(r.lambda_lo)
            << " .. " << number(r.lambda_hi) << ":\n\n";
  std::cout << std::left << std::setw(14) << "mode" << std::right << std::setw(14) << "stable from" << std::setw(14)
            << "stable to" << "\n";
  for (const auto& s : r.modes) {
    std::cout << std::left << std::setw(14) << s.mode << std::right;
    if (!s.stable_at_rest) {
      std::cout << std::setw(28) << "unstable at rest" << "\n";
      continue;
    }
    std::cout << std::setw(14) << stable_from(s) << std::setw(14) << stable_to(s) << "\n";
  }
  std::cout << "\n(lambda: stretch along the loading direction; uniaxial (l, l^-1/2, l^-1/2), equibiaxial (l, l, l^-2), "
               "planar (l, 1, 1/l))\n";
  if (std::isfinite(r.stretch_at_break))
    std::cout << "stretch at break (1 + elongation at break " << number(m.elongation_at_break * 100.0) << " %) = "
              << number(r.stretch_at_break) << "\n";
  for (const auto& w : r.warnings) std::cout << "WARNING: " << w << "\n";
}

// ---------------------------------------------------------------- fit

struct FitRequest {
  std::string csv, output, name = "fitted";
  std::vector<std::string> models = fem::fit_model_names();
  double density_g_cm3 = NAN;
  double poisson_ratio = 0.48;
  double max_abs_alpha = 10.0;
};

std::string stable_range(const fem::FitResult& f, std::size_t mode) {
  if (!f.law) return "-";
  const auto& s = f.stability[mode];
  return s.stable_at_rest ? stable_from(s) + " .. " + stable_to(s) : "unstable at rest";
}

void print_fits(const fem::UniaxialData& data, const fem::FitSummary& summary) {
  const auto [lo, hi] = std::minmax_element(data.nominal_stress_MPa.begin(), data.nominal_stress_MPa.end());
  std::cout << "uniaxial data " << data.source << ": " << data.stretch.size() << " points, stretch "
            << number(data.stretch.front()) << " .. " << number(data.stretch.back()) << ", nominal stress "
            << number(*lo) << " .. " << number(*hi) << " MPa\n"
            << "least squares on the nominal stress (incompressible closed forms); Drucker-stable stretch range "
               "scanned over " << number(summary.scan_lambda_min) << " .. " << number(summary.scan_lambda_max) << ":\n\n";
  std::cout << std::left << std::setw(13) << "model" << std::right << std::setw(7) << "coeffs" << std::setw(10) << "R2"
            << std::setw(11) << "RMS MPa" << std::setw(22) << "uniaxial stable" << std::setw(22) << "equibiaxial stable"
            << std::setw(22) << "planar stable" << "\n";
  for (const auto& f : summary.fits) {
    const bool fitted = !f.fitted_stress_MPa.empty();
    std::cout << std::left << std::setw(13) << fem::fit_model_name(f.model) << std::right << std::setw(7) << f.parameters
              << std::setw(10) << (fitted ? number(f.r_squared, 6) : "-") << std::setw(11)
              << (fitted ? number(f.rms_error_MPa, 4) : "-");
    for (std::size_t mode = 0; mode < 3; ++mode) std::cout << std::setw(22) << stable_range(f, mode);
    std::cout << "\n";
  }
  std::cout << "\n";
  for (const auto& f : summary.fits) {
    std::cout << fem::fit_model_name(f.model) << ":";
    for (const auto& [key, value] : f.coefficients) std::cout << " " << key << " = " << number(value, 6);
    if (!f.note.empty()) std::cout << (f.coefficients.empty() ? " " : "; ") << f.note;
    std::cout << "\n";
  }
  std::cout << "\nselected: "
            << (summary.best < 0 ? std::string("none") : fem::fit_model_name(summary.fits[summary.best].model))
            << " (highest R2 among the fits Drucker stable in uniaxial tension over the data's stretch range "
            << number(summary.data_lambda_min) << " .. " << number(summary.data_lambda_max) << ")\n";
}

/// The selected fit as a material in the JSON form scene configs accept (material_from_json).
void write_selected(const FitRequest& request, const fem::UniaxialData& data, const fem::FitSummary& summary) {
  if (summary.best < 0)
    throw fem::InputError(request.csv, "no fitted model is Drucker stable in uniaxial tension over the data's stretch "
                                       "range; nothing written to " + request.output);
  if (!(request.density_g_cm3 > 0.0))
    throw fem::InputError("--density-g-cm3", "required with -o (the material file needs the density, g/cm^3, > 0)");
  const fem::FitResult& best = summary.fits[summary.best];
  fem::Material m;
  m.name = request.name;
  m.law = best.law;
  m.density_g_cm3 = request.density_g_cm3;
  m.source = "softarm material fit: " + fem::fit_model_name(best.model) + " least-squares fit to " + data.source +
             " (" + std::to_string(data.stretch.size()) + " points, R2 = " + number(best.r_squared, 6) +
             ", RMS = " + number(best.rms_error_MPa, 4) + " MPa); D1 from Poisson's ratio " +
             number(request.poisson_ratio) + " (not measured)";
  std::ofstream out(request.output);
  out << fem::material_to_json(m).dump(2) << "\n";
  if (!out) throw fem::InputError("-o", "cannot write " + request.output);
  std::cout << "wrote " << request.output << " (material \"" << m.name << "\", "
            << fem::fit_model_name(best.model) << ", " << bulk_modulus_text(m.law->initial_bulk_modulus()) << ")\n";
}

void run_fit(const FitRequest& request) {
  const fem::UniaxialData data = fem::read_uniaxial_csv(request.csv);
  fem::FitOptions options;
  options.models.clear();
  for (const auto& name : request.models) options.models.push_back(fem::fit_model_from_name(name, "--models"));
  options.poisson_ratio = request.poisson_ratio;
  options.max_abs_alpha = request.max_abs_alpha;
  const fem::FitSummary summary = fem::fit_uniaxial(data, options);
  print_fits(data, summary);
  if (request.output.empty())
    std::cout << "(no file written: give -o FILE --density-g-cm3 D to write the selected fit)\n";
  else
    write_selected(request, data, summary);
}

}  // namespace

void add_material_command(CLI::App& app) {
  struct Options {
    bool json = false;
    std::string material;
    double lambda_lo = 0.1, lambda_hi = 10.0;
  };
  auto options = std::make_shared<Options>();

  CLI::App* material =
      app.add_subcommand("material", "Built-in materials, the Drucker stability of a law, fits to uniaxial data");
  material->require_subcommand(1);

  CLI::App* list = material->add_subcommand("list", "List the built-in materials (law, mu0, K0, density, strength, elongation)");
  list->add_flag("--json", options->json, "Print JSON instead of a table");
  list->callback([options] { print_list(options->json); });

  CLI::App* check = material->add_subcommand(
      "check", "Drucker-stable stretch range (uniaxial, equibiaxial, planar) of a built-in or a JSON material");
  check->add_option("material", options->material, "Built-in material name or JSON file with a material")->required();
  check->add_flag("--json", options->json, "Print JSON instead of a table");
  check->add_option("--lambda-min", options->lambda_lo, "Smallest stretch scanned (0 < l < 1)")
      ->capture_default_str();
  check->add_option("--lambda-max", options->lambda_hi,
                    "Largest stretch scanned (> 1; extended to 1.1 x the stretch at break when known)")
      ->capture_default_str();
  check->callback([options] {
    const CheckReport report = check_material(resolve_material(options->material), options->lambda_lo, options->lambda_hi);
    if (options->json)
      std::cout << report_json(report).dump(2) << "\n";
    else
      print_report(report);
  });

  auto fit_request = std::make_shared<FitRequest>();
  CLI::App* fit = material->add_subcommand(
      "fit", "Fit Neo-Hookean, Yeoh and Ogden N=1..3 to uniaxial data; report R2 and stability; write the best");
  fit->add_option("csv", fit_request->csv, "CSV with header stretch,nominal_stress_MPa")->required();
  fit->add_option("-o,--output", fit_request->output, "Write the selected fit as a material JSON file");
  fit->add_option("--name", fit_request->name, "Material name in the written file")->capture_default_str();
  fit->add_option("--models", fit_request->models, "Models to fit (comma separated)")
      ->delimiter(',')
      ->check(CLI::IsMember(fem::fit_model_names()))
      ->capture_default_str();
  fit->add_option("--density-g-cm3", fit_request->density_g_cm3, "Density, g/cm^3 (required with -o)")
      ->check(CLI::PositiveNumber);
  fit->add_option("--poisson-ratio", fit_request->poisson_ratio,
                  "Sets D1 = 3(1 - 2 nu)/(mu0 (1 + nu)) of the written law; 0.5 = incompressible")
      ->check(CLI::Range(0.0, 0.5))
      ->capture_default_str();
  fit->add_option("--alpha-max", fit_request->max_abs_alpha, "Bound on the Ogden exponents |alpha_i|")
      ->check(CLI::Range(1.0, 50.0))
      ->capture_default_str();
  fit->callback([fit_request] { run_fit(*fit_request); });
}

}  // namespace softarm::engine
