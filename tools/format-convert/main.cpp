#include "format_convert.h"

#include <mr/cli/run_tool.h>
#include <mr/io/unfinished_files.h>

#include <iostream>

int main(int argc, char** argv) {
  mr::io::remove_unfinished_files_on_signals();
  return mr::tools::format_convert(mr::cli::arguments(argc, argv), std::cout, std::cerr);
}
