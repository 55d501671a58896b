#pragma once
// `softarm fidelity [--report FILE]`: the fidelity ladder (fem/scenes/fidelity.hpp)
// as a table on the terminal and, with --report, an HTML page with one Pareto
// plot per scene (measured error against wall time, both logarithmic).
#include <string>

namespace softarm::engine {

void print_fidelity_ladders();
void write_fidelity_report(const std::string& file);

}  // namespace softarm::engine
