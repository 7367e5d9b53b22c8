#include "hole_fill_tool.h"

#include <mr/cli/run_tool.h>

#include <iostream>

int main(int argc, char** argv) {
  return mr::tools::hole_fill(mr::cli::arguments(argc, argv), std::cout, std::cerr);
}
