#include "tetrahedralize.h"

#include <mr/cli/run_tool.h>

#include <iostream>

int main(int argc, char** argv) {
  return mr::tools::tetrahedralize(mr::cli::arguments(argc, argv), std::cout, std::cerr);
}
