# Writes a C++ source that holds every OpenCL file given as a raw string literal, each
# named by its path relative to BASE (e.g. "deformers/bend.cl").
# Run as: cmake -DOUTPUT=file.cpp -DBASE=dir -DSOURCES="dir/a.cl;dir/b/c.cl"
#               [-DNAMESPACE=finflex::detail -DFUNCTION=kernel_sources -DHEADER=kernel_sources.hpp]
#               -P embed_kernels.cmake
if(NOT NAMESPACE)
  set(NAMESPACE finflex::detail)
endif()
if(NOT FUNCTION)
  set(FUNCTION kernel_sources)
endif()
if(NOT HEADER)
  set(HEADER kernel_sources.hpp)
endif()
set(body "// Generated from OpenCL files by cmake/embed_kernels.cmake: do not edit.\n")
string(APPEND body "#include \"${HEADER}\"\n\nnamespace ${NAMESPACE} {\n\n")
string(APPEND body "const std::vector<KernelSource>& ${FUNCTION}() {\n")
string(APPEND body "  static const std::vector<KernelSource> sources = {\n")
foreach(path IN LISTS SOURCES)
  file(RELATIVE_PATH name "${BASE}" "${path}")
  file(READ "${path}" text)
  string(APPEND body "    {\"${name}\", R\"FINFLEX_CL(${text})FINFLEX_CL\"},\n")
endforeach()
string(APPEND body "  };\n  return sources;\n}\n\n}  // namespace ${NAMESPACE}\n")
file(WRITE "${OUTPUT}.tmp" "${body}")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different "${OUTPUT}.tmp" "${OUTPUT}")
file(REMOVE "${OUTPUT}.tmp")
