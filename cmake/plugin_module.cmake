# mr_add_plugin_module(target file_stem source library): the module
# lib<file_stem>.so that mr::PluginModule (mr/core/plugin_module.h) loads at
# run time. `source` defines its extern "C" entry points; the static
# `library`, and every static library it links, is built position-independent
# and linked in hidden: only the entry points are exported. Installed in
# <libdir>/meshrepair, where PluginModule looks beside an installed bin/.
include_guard(GLOBAL)
include(GNUInstallDirs)
include(${CMAKE_CURRENT_LIST_DIR}/position_independent.cmake)
function(mr_add_plugin_module target file_stem source library)
  add_library(${target} MODULE ${source})
  set_target_properties(${target} PROPERTIES OUTPUT_NAME ${file_stem} PREFIX lib)
  target_link_libraries(${target} PRIVATE ${library} mr_warnings)
  target_link_options(${target} PRIVATE -Wl,--exclude-libs,ALL)
  mr_make_position_independent(${library})
  install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/meshrepair)
endfunction()
