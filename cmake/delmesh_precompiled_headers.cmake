# Precompiled headers.  Most translation units spend more time parsing the third-party headers
# that the public headers pull in (GiNaC, Boost.Multiprecision's MPFR/MPFI wrappers, CGAL's kernel,
# Interval_nt and Surface_mesh, nlohmann::json, Boost.Test in the suites) than compiling their own
# code: a typical test file took 16 s, 8 s with these precompiled.  Off with
# -DDELMESH_PRECOMPILE_HEADERS=OFF; the build is otherwise the same (the precompiled header is
# force-included first, and none of these headers depends on a macro that a source file defines
# before its includes).
option(DELMESH_PRECOMPILE_HEADERS "Precompile the third-party headers that most sources include" ON)

set(DELMESH_PRECOMPILED_HEADERS
    <algorithm> <array> <functional> <map> <memory> <optional> <string> <vector>
    <CGAL/Exact_predicates_inexact_constructions_kernel.h> <CGAL/Interval_nt.h> <CGAL/Surface_mesh.h>
    <boost/multiprecision/mpfi.hpp> <boost/multiprecision/mpfr.hpp>
    <ginac/ginac.h> <nlohmann/json.hpp>)

# delmesh_precompile(TARGET GROUP [HEADER...]): TARGET's sources see DELMESH_PRECOMPILED_HEADERS and
# the HEADERs precompiled.  The first target of a GROUP builds the precompiled header; the other
# targets of the group reuse it, so each group parses them once.  The targets of a group must have
# the same compiler flags and macro definitions (GCC refuses a precompiled header made with a macro
# defined otherwise, and parses the headers again).
function(delmesh_precompile target group)
  if(NOT DELMESH_PRECOMPILE_HEADERS)
    return()
  endif()
  get_property(first GLOBAL PROPERTY DELMESH_PCH_${group})
  if(first)
    target_precompile_headers(${target} REUSE_FROM ${first})
  else()
    set_property(GLOBAL PROPERTY DELMESH_PCH_${group} ${target})
    target_precompile_headers(${target} PRIVATE ${DELMESH_PRECOMPILED_HEADERS} ${ARGN})
  endif()
endfunction()
