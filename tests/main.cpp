// The test binary's main: Catch2's session, in a process set up as softarm's own main sets it up
// (engine/main.cpp), so that the tests run the solvers as the program runs them: without the
// allocator's settings (fem/core/allocator.hpp) each 3D Newton iteration's large arrays fault in
// afresh (docs/performance.md, The processes the tests and benchmarks run in).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "fem/core/allocator.hpp"

int main(int argc, char** argv) {
  softarm::fem::restart_with_huge_pages(argv);
  softarm::fem::keep_freed_memory_mapped();
  return Catch::Session().run(argc, argv);
}
