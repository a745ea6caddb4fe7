# feedplan_module(<name> [PUBLIC <targets>…] [PRIVATE <targets>…])
#
# One module of feedplan, from the folder that calls it: the static library feedplan_<name> built from
# every src/*.cpp there (one concept per file; new files need no list to change), alias feedplan::<name>,
# public headers in include/feedplan/<name>/, exported and installed as feedplan::<name>. PUBLIC names
# what the module's headers expose, PRIVATE what only its sources use (CGAL, Ceres, SQLite, yaml-cpp …
# stay there, so their headers never reach the rest of the build).
function(feedplan_module name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "" "PUBLIC;PRIVATE")
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(feedplan_${name} ${sources})
  add_library(feedplan::${name} ALIAS feedplan_${name})
  target_include_directories(feedplan_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(feedplan_${name} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
  set_target_properties(feedplan_${name} PROPERTIES EXPORT_NAME ${name})
  install(TARGETS feedplan_${name} EXPORT feedplanTargets)
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()
