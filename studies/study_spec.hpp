#pragma once
// A parameter study (thesis Ch. 5–6, spec §5): one base scene, the parameters
// swept over it, the model that evaluates each point, and the rule that turns
// the curves into a design choice. Read from a JSON study config
// (configs/studies/*.json); every key is documented by `softarm schema
// --scene study`, unknown keys are rejected with the field named.
//
//   {
//     "study": "ring_count", "title": "…", "description": "…",
//     "scene": { a scene document as for `softarm simulate`, without "output" }
//              or "../rra_thesis.json" (a scene file, relative to the study config),
//     "scene_changes": { a JSON merge patch applied to the scene, e.g. {"mesh": {"level": 1}} },
//     "model": "fem" | "rod",
//     "sweep": [ {"parameter": "geometry.ring_count_normalised", "values": [0.125, …]},
//                {"parameter": "materials.tube", "values": ["dragon_skin_10", …]} ],
//     "plot": {"x": "parameter" | "pressure", "y": "extension_mm"},
//     "rule": {"goal": "max", "output": "extension_mm", "keep_percent": 99,
//              "then_minimise": "mass_g", "limits": [{"output": "burst_utilisation", "max": 1}]},
//     "thesis": {"choice": 0.375, "figure": "Fig 26", "finding": "…", "trend": "peak", "peak_at": 0.5}
//   }
//
// The first sweep axis is the plot's parameter; every combination of the
// others is one curve (e.g. one per material), and the rule is applied per curve.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace softarm::studies {

struct SweepAxis {
  std::string parameter;                // a path into the scene ("geometry.wall_thickness_normalised",
                                        // "materials.tube") or a derived parameter ("taper_ratio")
  std::string label;                    // axis label for plots and words
  std::vector<nlohmann::json> values;   // numbers or names, in sweep order
  bool numeric() const { return !values.empty() && values.front().is_number(); }
};

/// A bound on an output that excludes a point from the choice (e.g. burst_utilisation ≤ 1).
struct OutputLimit {
  std::string output;
  std::optional<double> min, max;
};

/// The design rule, in the thesis' terms: take the best value of `output`, then
/// among the points within `keep_percent` of it pick the one that minimises
/// `then_minimise` (the thesis' "0.375 keeps the extension with fewer rings").
/// Points that break a limit are not eligible.
struct DesignRuleSpec {
  std::string goal = "max";          // "max" | "min" of `output`
  std::string output;
  double keep_percent = 100;         // 100: the best point itself
  std::string then_minimise;         // empty: no secondary criterion
  std::vector<OutputLimit> limits;
};

/// What the thesis found, for the report's comparison (spec §5).
struct ThesisFinding {
  nlohmann::json choice;             // the value the thesis picked (null if none)
  std::string figure, finding;
  std::string trend_of;              // the output the thesis' trend and order speak of (default: the rule's)
  std::string trend;                 // "increasing" | "decreasing" | "peak" | "" (not stated)
  std::optional<double> peak_at;     // for trend "peak"
  std::vector<nlohmann::json> order; // first-axis values from the largest output to the smallest (categorical axes)
  std::string discussion;            // why softarm's result differs, written after reading the data
};

struct StudySpec {
  std::string name, title, description;
  nlohmann::json scene;              // the base scene document ("scene": "rra" | "tca", geometry, …)
  std::string model = "fem";         // "fem": the scene's FEM model; "rod": the reduced rod (fem/reduced)
  int rod_nodes = 17;                // rod nodes per segment (model "rod")
  double safety_factor = 1.5;        // burst criteria (a), (b) of spec §4
  std::vector<SweepAxis> axes;
  std::string plot_x = "parameter";  // "parameter": output at the peak pressure vs the first axis;
                                     // "pressure": one curve per point vs normalised pressure
  std::string plot_y;                // the plotted output (normalised by its largest value)
  DesignRuleSpec rule;
  ThesisFinding thesis;
  double point_timeout_s = 900;      // a point running longer is stopped and recorded as failed
  std::string fingerprint;           // hash of everything that changes a point's result
};

/// Reads and validates a study config; throws fem::InputError naming the field.
/// `base_directory`: where a scene file named by "scene" is looked up.
StudySpec read_study(const nlohmann::json& document, const std::filesystem::path& base_directory = {});
StudySpec load_study(const std::string& file_name);

/// Outputs a point of this scene/model reports (for validating rule and plot keys).
std::vector<std::string> scalar_outputs(const std::string& scene, const std::string& model);

}  // namespace softarm::studies
