# Installation and packaging (README "Installing", CONTRIBUTING.md "Installing and packaging").
#   cmake --install build/release --prefix /opt/vrsph   # or: cpack -G DEB, from the build folder
# lays out
#   bin/vrsph
#   share/vrsph/{cases, reference, scripts}   the shipped data, found by the program at run time
#                                             (src/vrsph/driver/data_dir.hpp)
#   share/doc/vrsph/{README.md, CONTRIBUTING.md, LICENSE, copyright, docs/}
# The program finds its data as VRSPH_DATA_RELATIVE from the folder of the executable, so the
# tree can be moved or installed under any prefix.
include(GNUInstallDirs)

set(VRSPH_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/vrsph)
file(RELATIVE_PATH VRSPH_DATA_RELATIVE ${CMAKE_INSTALL_FULL_BINDIR}
     ${CMAKE_INSTALL_FULL_DATADIR}/vrsph)
set_property(SOURCE ${CMAKE_SOURCE_DIR}/src/vrsph/driver/data_dir.cpp APPEND PROPERTY
             COMPILE_DEFINITIONS VRSPH_DATA_RELATIVE="${VRSPH_DATA_RELATIVE}")

install(TARGETS vrsph RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/cases ${CMAKE_SOURCE_DIR}/reference
        DESTINATION ${VRSPH_INSTALL_DATADIR})
# The plot and analysis scripts users run on their outputs (not the repository's own checks).
install(PROGRAMS ${CMAKE_SOURCE_DIR}/scripts/plot_run.sh ${CMAKE_SOURCE_DIR}/scripts/plot_window.sh
                 ${CMAKE_SOURCE_DIR}/scripts/laplace_window.sh
                 ${CMAKE_SOURCE_DIR}/scripts/compare_max_speed.sh
                 ${CMAKE_SOURCE_DIR}/scripts/dam_break_front.sh
        DESTINATION ${VRSPH_INSTALL_DATADIR}/scripts)
install(FILES ${CMAKE_SOURCE_DIR}/README.md ${CMAKE_SOURCE_DIR}/CONTRIBUTING.md
              ${CMAKE_SOURCE_DIR}/LICENSE
        DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${CMAKE_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR} RENAME copyright)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs DESTINATION ${CMAKE_INSTALL_DOCDIR})

# cpack -G DEB (from the build folder) -> vrsph_<version>_<arch>.deb, installing under /usr.
# The library dependencies (libgomp1, libfmt9, libtomlplusplus3, ...) are read from the binary by
# dpkg-shlibdeps (package dpkg-dev). A package built with VRSPH_NATIVE=ON (the default) runs only
# on CPUs with the build machine's instruction set: configure with -DVRSPH_NATIVE=OFF for a
# package meant for other machines.
set(CPACK_PACKAGE_NAME vrsph)
set(CPACK_PACKAGE_VENDOR "vrsph")
# The Maintainer field of the .deb: set it to whoever distributes the package
# (-DVRSPH_PACKAGE_CONTACT="Name <mail>").
set(VRSPH_PACKAGE_CONTACT "vrsph developers" CACHE STRING "Maintainer field of the package")
set(CPACK_PACKAGE_CONTACT "${VRSPH_PACKAGE_CONTACT}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Weakly compressible SPH with surface tension and variable resolution")
set(CPACK_PACKAGE_DESCRIPTION
    "vrsph solves free-surface flows in 2D and 3D with weakly compressible SPH, carrying \
single-phase surface tension across variable resolution. The package holds the vrsph command, \
the shipped cases, the reference data, the plot scripts and the documentation.")
set(CPACK_RESOURCE_FILE_LICENSE ${CMAKE_SOURCE_DIR}/LICENSE)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "gnuplot-nox")
include(CPack)
