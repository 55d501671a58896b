#include "fem/mesh/chamber_lids.hpp"

#include <map>
#include <set>
#include <stdexcept>

namespace softarm::fem {
namespace {

/// One edge of a lid's loop: start, midside node (−1 on a linear facet), end.
struct LidEdge {
  int start = -1, mid = -1, end = -1;
};

/// A facet's edges in its node order (VTK quads: corners 0–3, midside 4–7 on edges 01, 12, 23, 30).
std::vector<LidEdge> facet_edges(const std::vector<int>& f) {
  std::vector<LidEdge> edges;
  for (int k = 0; k < 4; ++k) edges.push_back({f[k], f.size() >= 8 ? f[4 + k] : -1, f[(k + 1) % 4]});
  return edges;
}

}  // namespace

void add_chamber_lids(Mesh& mesh, const std::vector<int>& cut_nodes) {
  if (mesh.dim != 3) throw std::logic_error("add_chamber_lids: 3D meshes only");
  const std::set<int> on_cut(cut_nodes.begin(), cut_nodes.end());
  const auto cut = [&](int n) { return n < 0 || on_cut.count(n) > 0; };
  for (Chamber& chamber : mesh.chambers) {
    // The lid runs along the facets' cut edges in the opposite sense.
    std::map<int, LidEdge> from;  // keyed by the lid edge's start
    std::set<int> ends;
    for (const auto& f : chamber.facets)
      for (const LidEdge& e : facet_edges(f))
        if (cut(e.start) && cut(e.mid) && cut(e.end)) {
          if (!from.emplace(e.end, LidEdge{e.end, e.mid, e.start}).second)
            throw std::logic_error("add_chamber_lids: chamber " + chamber.name + " has a branching cut edge");
          ends.insert(e.start);
        }
    while (!from.empty()) {
      // Open chains start where no edge ends; closed loops anywhere.
      auto first = from.begin();
      for (auto it = from.begin(); it != from.end(); ++it)
        if (!ends.count(it->first)) {
          first = it;
          break;
        }
      std::vector<int> loop;
      int at = first->first;
      const int start = at;
      while (true) {
        const auto it = from.find(at);
        if (it == from.end()) {
          loop.push_back(at);  // the open chain's last node
          break;
        }
        loop.push_back(at);
        if (it->second.mid >= 0) loop.push_back(it->second.mid);
        at = it->second.end;
        from.erase(it);
        if (at == start) break;  // closed
      }
      chamber.lids.push_back(std::move(loop));
    }
  }
}

}  // namespace softarm::fem
