#pragma once
// Deformed-shape pictures for the study reports, from the "shape" a study
// point records (studies/point_evaluation.hpp):
//   axisymmetric_outline  the RRA's deformed boundary edges per part, drawn in
//                         the r–z plane and mirrored about the axis, as a
//                         section through the actuator;
//   rod_centreline        the 3CA's deformed centreline with its envelope
//                         (± the section's half-width normal to the centreline).
// Equal scales on both axes, so what looks bent is bent.
#include <nlohmann/json.hpp>
#include <string>

namespace softarm::engine {

/// One self-contained <svg> (or "" when the shape kind is unknown or empty).
std::string render_shape_svg(const nlohmann::json& shape, const std::string& caption, int height_px = 320);

}  // namespace softarm::engine
