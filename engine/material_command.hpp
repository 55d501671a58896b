#pragma once
// `softarm material list` and `softarm material check <name-or-json-file>`:
// the built-in materials, and where a law is Drucker stable (the thesis'
// Dragon Skin fits have negative μ_i, so users must see where they stop
// being physical before trusting a simulation that strains them further).
#include <CLI/CLI.hpp>

namespace softarm::engine {

/// Registers the `material` subcommand and its `list` / `check` children on `app`.
/// Bad names and bad files throw fem::InputError (the CLI main reports it, exit 2).
void add_material_command(CLI::App& app);

}  // namespace softarm::engine
