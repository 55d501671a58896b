#include "fem/reduced/cell_tables_json.hpp"

namespace softarm::fem {

nlohmann::json cell_tables_json(const SpatialCellRodSpec& rod) {
  nlohmann::json pieces = nlohmann::json::array();
  for (const auto& p : rod.pieces) {
    nlohmann::json cells = nlohmann::json::array();
    for (const auto& c : p.cells) {
      nlohmann::json k = nlohmann::json::array(), b = nlohmann::json::array();
      for (const auto& v : c.curvature_per_mm) k.push_back({v.x(), v.y()});
      for (const auto& m : c.bending_compliance_per_Nmm2) b.push_back({m(0, 0), m(0, 1), m(1, 0), m(1, 1)});
      cells.push_back({{"z_mm", c.z_mm}, {"level", c.level}, {"stretch", c.stretch},
                       {"axial_compliance_per_N", c.axial_compliance_per_N}, {"curvature_per_mm", k},
                       {"bending_compliance_per_Nmm2", b}, {"torsion_compliance_per_Nmm2", c.torsion_compliance_per_Nmm2},
                       {"mass_per_length_kg_per_mm", c.mass_per_length_kg_per_mm}});
    }
    nlohmann::json ends = nlohmann::json::array();
    for (const auto& e : p.ends) {
      nlohmann::json turn = nlohmann::json::array();
      for (const auto& v : e.rotation_rad) turn.push_back({v.x(), v.y()});
      ends.push_back({{"at_top", e.at_top}, {"length_mm", e.length_mm}, {"level", e.level},
                      {"rotation_rad", turn}, {"elongation_mm", e.elongation_mm},
                      {"twist_compliance_per_Nmm", e.twist_compliance_per_Nmm}});
    }
    pieces.push_back({{"length_mm", p.length_mm}, {"cap_mm", p.cap_mm}, {"mass_kg", p.mass_kg}, {"cells", cells}, {"ends", ends}});
  }
  return {{"pieces", pieces}};
}

void read_cell_tables(const nlohmann::json& j, SpatialCellRodSpec& rod) {
  rod.pieces.clear();
  for (const auto& p : j.at("pieces")) {
    SpatialCellPiece piece;
    piece.length_mm = p.at("length_mm");
    piece.cap_mm = p.at("cap_mm");
    piece.mass_kg = p.at("mass_kg");
    for (const auto& c : p.at("cells")) {
      SpatialCellTable t;
      t.z_mm = c.at("z_mm");
      t.level = c.at("level").get<std::vector<double>>();
      t.stretch = c.at("stretch").get<std::vector<double>>();
      t.axial_compliance_per_N = c.at("axial_compliance_per_N").get<std::vector<double>>();
      t.mass_per_length_kg_per_mm = c.at("mass_per_length_kg_per_mm");
      t.torsion_compliance_per_Nmm2 = c.value("torsion_compliance_per_Nmm2", 0.0);
      for (const auto& k : c.at("curvature_per_mm")) t.curvature_per_mm.emplace_back(k[0].get<double>(), k[1].get<double>());
      for (const auto& b : c.at("bending_compliance_per_Nmm2")) {
        Eigen::Matrix2d m;
        m << b[0].get<double>(), b[1].get<double>(), b[2].get<double>(), b[3].get<double>();
        t.bending_compliance_per_Nmm2.push_back(m);
      }
      piece.cells.push_back(t);
    }
    for (const auto& e : p.value("ends", nlohmann::json::array())) {
      SpatialEndTable t;
      t.at_top = e.at("at_top");
      t.length_mm = e.at("length_mm");
      t.level = e.at("level").get<std::vector<double>>();
      t.elongation_mm = e.at("elongation_mm").get<std::vector<double>>();
      t.twist_compliance_per_Nmm = e.value("twist_compliance_per_Nmm", 0.0);
      for (const auto& v : e.at("rotation_rad")) t.rotation_rad.emplace_back(v[0].get<double>(), v[1].get<double>());
      piece.ends.push_back(t);
    }
    rod.pieces.push_back(piece);
  }
}

}  // namespace softarm::fem
