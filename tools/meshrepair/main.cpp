#include "meshrepair.h"

#include <mr/cli/run_tool.h>

#include <iostream>

int main(int argc, char** argv) {
  return mr::tools::meshrepair(mr::cli::arguments(argc, argv), std::cout, std::cerr);
}
