# The Debian package version of the library behind an imported target: for a library whose headers carry no
# version macro and whose CMake config declares another version than the package it came in (Siconos 4.4's
# says 4.5.0). Sets OUT to the version of the package that owns the target's library file, as dpkg-query
# says it, or to FALLBACK where there is no dpkg-query, no such file or no owning package.
function(debian_package_version target fallback out)
  set(version "${fallback}")
  get_target_property(library_file ${target} IMPORTED_LOCATION_NONE)
  find_program(IMPACTBENCH_DPKG_QUERY dpkg-query)
  if(IMPACTBENCH_DPKG_QUERY AND library_file)
    get_filename_component(library_real "${library_file}" REALPATH)
    execute_process(COMMAND ${IMPACTBENCH_DPKG_QUERY} -S "${library_real}" OUTPUT_VARIABLE owner RESULT_VARIABLE status
                    ERROR_QUIET)
    if(status EQUAL 0)
      string(REGEX REPLACE ":.*" "" owner "${owner}")
      execute_process(COMMAND ${IMPACTBENCH_DPKG_QUERY} -W -f=\${Version} "${owner}" OUTPUT_VARIABLE package_version
                      RESULT_VARIABLE status)
      if(status EQUAL 0 AND package_version)
        set(version "${package_version}")
      endif()
    endif()
  endif()
  set(${out} "${version}" PARENT_SCOPE)
endfunction()
