# regdae.pc for pkg-config, installed to <libdir>/pkgconfig by
# regdae_install_pkg_config(TARGETS...).
#
# Libs.private lists the libraries behind TARGETS (imported SUNDIALS and LAPACK
# targets, followed through their link interfaces) as -l flags, each before the
# libraries it needs, then the gfortran run-time libraries (for C programs).
# The prefix is the one given at install time (cmake --install --prefix, or
# CPack's), so the file is written then, straight into its destination.

# _regdae_link_order(ITEM): append the -l flag of ITEM, then those of what it
# needs, to the caller's _regdae_order. Keeping each flag's last occurrence
# then puts every library before all those it needs.
function(_regdae_link_order item)
  set(library "${item}")
  set(dependencies "")
  if(TARGET ${item})
    set(library "")
    get_target_property(type ${item} TYPE)
    if(NOT type STREQUAL "INTERFACE_LIBRARY")
      get_target_property(library ${item} IMPORTED_LOCATION)
      if(NOT library)
        get_target_property(configs ${item} IMPORTED_CONFIGURATIONS)
        list(GET configs 0 config)
        get_target_property(library ${item} IMPORTED_LOCATION_${config})
      endif()
    endif()
    get_target_property(dependencies ${item} INTERFACE_LINK_LIBRARIES)
    if(NOT dependencies)
      set(dependencies "")
    endif()
  elseif(item MATCHES "^\\$<LINK_ONLY:(.*)>$")
    set(library "${CMAKE_MATCH_1}")
  endif()
  if(library MATCHES "^-")
    list(APPEND _regdae_order "${library}")
  elseif(IS_ABSOLUTE "${library}")
    get_filename_component(name "${library}" NAME_WE)
    string(REGEX REPLACE "^lib" "-l" flag "${name}")
    list(APPEND _regdae_order "${flag}")
  elseif(library MATCHES "^[A-Za-z0-9_.+-]+$")
    list(APPEND _regdae_order "-l${library}")
  elseif(library)
    message(FATAL_ERROR "regdae.pc: cannot write '${library}' (from ${item}) as a linker flag")
  endif()
  foreach(dependency IN LISTS dependencies)
    _regdae_link_order("${dependency}")
  endforeach()
  set(_regdae_order "${_regdae_order}" PARENT_SCOPE)
endfunction()

function(regdae_install_pkg_config)
  set(_regdae_order "")
  foreach(target IN LISTS ARGN)
    _regdae_link_order(${target})
  endforeach()
  # Each library once, at its last place.
  list(REVERSE _regdae_order)
  list(REMOVE_DUPLICATES _regdae_order)
  list(REVERSE _regdae_order)
  list(APPEND _regdae_order -lgfortran -lquadmath -lm)
  list(JOIN _regdae_order " " REGDAE_PC_LIBS_PRIVATE)

  # Everything but the prefix now; the prefix (self-substituted here) at install time.
  set(REGDAE_PC_PREFIX "@REGDAE_PC_PREFIX@")
  set(REGDAE_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
  set(REGDAE_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
  configure_file(${PROJECT_SOURCE_DIR}/cmake/regdae.pc.in ${PROJECT_BINARY_DIR}/regdae.pc.in @ONLY)
  install(CODE "
    set(REGDAE_PC_PREFIX \"\${CMAKE_INSTALL_PREFIX}\")
    set(regdae_pc \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig/regdae.pc\")
    message(STATUS \"Installing: \${regdae_pc}\")
    configure_file(\"${PROJECT_BINARY_DIR}/regdae.pc.in\" \"\${regdae_pc}\" @ONLY)
    list(APPEND CMAKE_INSTALL_MANIFEST_FILES \"\${regdae_pc}\")")
endfunction()
