#pragma once

namespace softarm::engine {

/// The `softarm` command line. Returns the process exit code:
/// 0 success, 1 numerical outcome short of the request (e.g. a stall), 2 bad input.
int run_cli(int argc, char** argv);

}  // namespace softarm::engine
