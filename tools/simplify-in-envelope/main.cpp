#include "simplify_in_envelope.h"

#include <mr/cli/run_tool.h>

#include <iostream>

int main(int argc, char** argv) {
  return mr::tools::simplify_in_envelope(mr::cli::arguments(argc, argv), std::cout, std::cerr);
}
