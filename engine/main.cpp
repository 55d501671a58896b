#include "engine/cli.hpp"

int main(int argc, char** argv) { return softarm::engine::run_cli(argc, argv); }
