// The rigidity command line: run, validate, materials, compare (docs/cli.md).
#include "rigidity/cli.hpp"

int main(int argc, char** argv) { return rigidity::cli_main(argc, argv); }
