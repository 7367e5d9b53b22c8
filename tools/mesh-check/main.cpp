#include "mesh_check.h"

#include <mr/cli/run_tool.h>

#include <iostream>

int main(int argc, char** argv) {
  return mr::tools::mesh_check(mr::cli::arguments(argc, argv), std::cout, std::cerr);
}
