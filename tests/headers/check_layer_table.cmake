# cmake -DHEADER_DIR=<engine/include/finflex> -DLAYERS=<tests/headers/layers.cmake>
#       -P check_layer_table.cmake
#
# Fails, naming each header, when a header of HEADER_DIR (its subfolders included) is in
# no layer of the table, when a header is in two layers, when the table lists a header
# that is not there (generated ones aside), or when finflex.hpp does not include every
# public header (those of the layers before its own, the generated ones aside) or
# includes an internal one.
cmake_minimum_required(VERSION 3.20)
include(${LAYERS})

set(problems "")
set(listed "")
set(public "")
set(umbrella_layer_reached OFF)
foreach(layer IN LISTS FINFLEX_HEADER_LAYERS)
  foreach(header IN LISTS FINFLEX_LAYER_${layer})
    if(header IN_LIST listed)
      list(APPEND problems "${header} is in two layers (the second: ${layer})")
    endif()
    list(APPEND listed ${header})
    if(NOT header IN_LIST FINFLEX_GENERATED_HEADERS AND NOT EXISTS ${HEADER_DIR}/${header})
      list(APPEND problems "${header} (layer ${layer}) is not in engine/include/finflex/")
    endif()
    if(header STREQUAL "finflex.hpp")
      set(umbrella_layer_reached ON)
    elseif(NOT umbrella_layer_reached AND NOT header IN_LIST FINFLEX_GENERATED_HEADERS)
      list(APPEND public ${header})
    endif()
  endforeach()
endforeach()

file(GLOB_RECURSE present RELATIVE ${HEADER_DIR} ${HEADER_DIR}/*.hpp ${HEADER_DIR}/*.h)
list(SORT present)
foreach(header IN LISTS present)
  if(NOT header IN_LIST listed)
    list(APPEND problems "${header} is in no layer: add it to the lowest layer that holds "
                         "everything it includes")
  endif()
endforeach()

if(EXISTS ${HEADER_DIR}/finflex.hpp)
  file(STRINGS ${HEADER_DIR}/finflex.hpp include_lines REGEX "^[ \t]*#[ \t]*include")
  set(included "")
  foreach(line IN LISTS include_lines)
    if(line MATCHES "[\"<]finflex/([^\">]+)[\">]")
      list(APPEND included ${CMAKE_MATCH_1})
    endif()
  endforeach()
  foreach(header IN LISTS public)
    if(EXISTS ${HEADER_DIR}/${header} AND NOT header IN_LIST included)
      list(APPEND problems "finflex.hpp does not include finflex/${header}")
    endif()
  endforeach()
  foreach(header IN LISTS included)
    if(header MATCHES "^${FINFLEX_INTERNAL_HEADER_DIR}/")
      list(APPEND problems "finflex.hpp includes finflex/${header}, which is not installed")
    endif()
  endforeach()
else()
  list(APPEND problems "there is no finflex.hpp")
endif()

list(LENGTH present present_count)
if(problems)
  list(JOIN problems "\n  " text)
  message(FATAL_ERROR "The layer table (tests/headers/layers.cmake) and engine/include/finflex/ "
                      "disagree:\n  ${text}")
endif()
message(STATUS "All ${present_count} headers of engine/include/finflex/ are in the layer table")
