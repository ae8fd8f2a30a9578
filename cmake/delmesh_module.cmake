# delmesh_module(NAME DEPENDENCIES...): one static library per top-level module folder.
# Every .cpp file under NAME/, in any subfolder, belongs to the library delmesh_NAME, so adding a
# concept to a module means adding a .h/.cpp pair, never editing CMake.  The one exception is
# common/tcmalloc/, the allocator hook that only the programs link (CMakeLists.txt).  The sources' include root is
# the source tree in the build, and include/delmesh once installed (cmake/delmesh_install.cmake).
function(delmesh_module name)
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${name}/*.cpp)
  list(FILTER sources EXCLUDE REGEX "/common/tcmalloc/")
  if(sources)
    add_library(delmesh_${name} STATIC ${sources})
    target_include_directories(delmesh_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>)
    target_link_libraries(delmesh_${name} PUBLIC ${ARGN})
  else()
    add_library(delmesh_${name} INTERFACE)
    target_include_directories(delmesh_${name} INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>)
    target_link_libraries(delmesh_${name} INTERFACE ${ARGN})
  endif()
endfunction()
