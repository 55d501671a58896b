#pragma once
// `softarm material list`, `softarm material check <name-or-json-file>` and
// `softarm material fit <uniaxial.csv>`: the built-in materials, where a law
// is Drucker stable (the thesis' Dragon Skin fits have negative μ_i, so users
// must see where they stop being physical before trusting a simulation that
// strains them further), and least-squares fits of the thesis' law families
// to uniaxial test data (thesis Ch. 3), written as a material JSON.
#include <CLI/CLI.hpp>

namespace softarm::engine {

/// Registers the `material` subcommand and its `list` / `check` / `fit` children on `app`.
/// Bad names and bad files (a malformed CSV: file, line and value) throw
/// fem::InputError (the CLI main reports it, exit 2).
void add_material_command(CLI::App& app);

}  // namespace softarm::engine
