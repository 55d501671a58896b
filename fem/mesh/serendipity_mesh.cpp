#include "fem/mesh/serendipity_mesh.hpp"

#include <stdexcept>

namespace softarm::fem {

Mesh serendipity_from_triquadratic(const Mesh& hex27) {
  if (hex27.dim != 3 || hex27.nodes_per_element != 27)
    throw std::logic_error("serendipity_from_triquadratic: needs a 3D Hex27 mesh");
  constexpr int kKept = 20;
  std::vector<int> new_index(hex27.num_nodes(), -1);
  for (int e = 0; e < hex27.num_elements(); ++e)
    for (int a = 0; a < kKept; ++a) new_index[hex27.element(e)[a]] = 0;
  int count = 0;
  for (int& n : new_index)
    if (n == 0) n = count++;

  Mesh out;
  out.dim = 3;
  out.nodes_per_element = kKept;
  out.X.resize(count, 3);
  for (int n = 0; n < hex27.num_nodes(); ++n)
    if (new_index[n] >= 0) out.X.row(new_index[n]) = hex27.X.row(n);
  out.connectivity.reserve(static_cast<std::size_t>(hex27.num_elements()) * kKept);
  for (int e = 0; e < hex27.num_elements(); ++e)
    for (int a = 0; a < kKept; ++a) out.connectivity.push_back(new_index[hex27.element(e)[a]]);
  out.part = hex27.part;
  out.part_names = hex27.part_names;
  for (const auto& [name, nodes] : hex27.node_sets) {
    std::vector<int>& kept = out.node_sets[name];
    for (int n : nodes)
      if (new_index[n] >= 0) kept.push_back(new_index[n]);
  }
  for (const Chamber& chamber : hex27.chambers) {
    Chamber c{chamber.id, chamber.name, {}, {}};
    for (const auto& lid : chamber.lids) {  // lids run along facet edges: corners and midsides, all kept
      std::vector<int> loop;
      for (int n : lid) loop.push_back(new_index[n]);
      c.lids.push_back(std::move(loop));
    }
    for (const auto& facet : chamber.facets) {
      // 9-node facets: corners, mid-edges, centre; the centre is not a Hex20 node.
      const std::size_t kept = facet.size() == 9 ? 8 : facet.size();
      std::vector<int> f;
      for (std::size_t a = 0; a < kept; ++a) f.push_back(new_index[facet[a]]);
      c.facets.push_back(std::move(f));
    }
    out.chambers.push_back(std::move(c));
  }
  return out;
}

}  // namespace softarm::fem
