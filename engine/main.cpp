#include "engine/cli.hpp"
#include "fem/core/allocator.hpp"

int main(int argc, char** argv) {
  softarm::fem::restart_with_huge_pages(argv);
  softarm::fem::keep_freed_memory_mapped();
  return softarm::engine::run_cli(argc, argv);
}
