# Install rules that belong to the package as a whole, and the Debian package (CPack DEB).
# Included at the end of the top-level CMakeLists.txt. Layout, with P the install prefix:
#   P/bin/pierce, P/share/man/man1/pierce.1.gz          CLI and man page (apps/)
#   P/<libdir>/libpierce.so.*, P/include/pierce/         core library and headers (core/)
#   P/<libdir>/cmake/Pierce/                             CMake package: Pierce::core
#   P/<libdir>/libPierceVTK*.so.*                        VTK filters (vtk_filter/)
#   P/<libdir>/paraview-5.11/plugins/PierceParaView/     ParaView plugin (plugins/paraview/)
#   P/bin/paraview.conf                                  makes ParaView list the plugin (below)
#   P/lib/python3/dist-packages/{pierce,pierce_vtk}/     Python packages (python/, vtk_filter/)
#   P/share/freecad/Mod/Pierce/                          FreeCAD workbench (freecad_addon/)
#   P/share/doc/pierce/                                  docs, samples, examples/consumer
include(CMakePackageConfigHelpers)


# --- CMake package -------------------------------------------------------------------------
install(EXPORT PierceTargets NAMESPACE Pierce:: FILE PierceTargets.cmake
  DESTINATION ${PIERCE_INSTALL_CMAKEDIR} COMPONENT pierce)
configure_package_config_file(cmake/PierceConfig.cmake.in ${CMAKE_BINARY_DIR}/cmake/PierceConfig.cmake
  INSTALL_DESTINATION ${PIERCE_INSTALL_CMAKEDIR}
  PATH_VARS CMAKE_INSTALL_INCLUDEDIR)
# 0.x: a new minor version may break the API, so only the same major.minor is compatible.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/PierceConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/PierceConfig.cmake ${CMAKE_BINARY_DIR}/cmake/PierceConfigVersion.cmake
  DESTINATION ${PIERCE_INSTALL_CMAKEDIR} COMPONENT pierce)

# --- ParaView plugin discovery -------------------------------------------------------------
# ParaView 5.11 lists (Tools > Manage Plugins) and LoadDistributedPlugin() finds only the plugins
# named in the XML files listed in <directory of the executable>/paraview.conf
# (vtkPVPluginTracker::LoadPluginConfigurationXMLs); Debian's paraview package ships no such file,
# and paraview.plugins.xml belongs to it. So the package installs bin/paraview.conf naming
# Pierce's plugin list, by a path relative to bin/ as ParaView expects. See docs/INSTALL.md.
if(PIERCE_BUILD_VTK)
  option(PIERCE_INSTALL_PARAVIEW_CONF "Install bin/paraview.conf so that ParaView lists the Pierce plugin" ON)
  if(PIERCE_INSTALL_PARAVIEW_CONF)
    file(RELATIVE_PATH _pierce_pv_xml "/prefix/${CMAKE_INSTALL_BINDIR}"
      "/prefix/${CMAKE_INSTALL_LIBDIR}/${PIERCE_PARAVIEW_PLUGINS_SUBDIR}/pierce.paraview.plugins.xml")
    file(WRITE ${CMAKE_BINARY_DIR}/packaging/paraview.conf "${_pierce_pv_xml}\n")
    install(FILES ${CMAKE_BINARY_DIR}/packaging/paraview.conf DESTINATION ${CMAKE_INSTALL_BINDIR}
      COMPONENT paraview)
  endif()
endif()

# --- FreeCAD workbench ---------------------------------------------------------------------
# FreeCAD's system Mod directory; the workbench imports the installed `pierce` module from
# dist-packages (on FreeCAD's sys.path), so no pierce_path.txt is written.
install(DIRECTORY freecad_addon/ DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/freecad/Mod/Pierce COMPONENT freecad
  PATTERN __pycache__ EXCLUDE
  PATTERN pierce_path.txt EXCLUDE)
install(FILES LICENSE DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/freecad/Mod/Pierce COMPONENT freecad)

# --- Documentation, samples, the consumer example ------------------------------------------
install(FILES README.md LICENSE DESTINATION ${PIERCE_INSTALL_DOCDIR} COMPONENT pierce)
install(FILES LICENSE DESTINATION ${PIERCE_INSTALL_DOCDIR} RENAME copyright COMPONENT pierce)
install(DIRECTORY docs/ DESTINATION ${PIERCE_INSTALL_DOCDIR}/docs COMPONENT pierce)
install(DIRECTORY samples/ DESTINATION ${PIERCE_INSTALL_DOCDIR}/samples COMPONENT pierce)
install(DIRECTORY examples/consumer/ DESTINATION ${PIERCE_INSTALL_DOCDIR}/examples/consumer COMPONENT pierce)

# --- Debian package ------------------------------------------------------------------------
# packaging/build-deb.sh configures with -DCMAKE_INSTALL_PREFIX=/usr and runs cpack. One package
# holds every component listed here; the VTK client-server archives and the VTK modules'
# development links (component `development`) are left out: nothing can use them without headers.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME pierce)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "${PIERCE_MAINTAINER_NAME}")
set(CPACK_PACKAGE_CONTACT "${PIERCE_MAINTAINER_NAME} <${PIERCE_MAINTAINER_EMAIL}>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PIERCE_SUMMARY}")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_COMPONENTS_ALL pierce freecad)
if(PIERCE_BUILD_VTK)
  # vtk_module_build's shared libraries, the pierce_vtk modules, the plugin and paraview.conf
  list(APPEND CPACK_COMPONENTS_ALL runtime python paraview)
endif()
set(CPACK_DEBIAN_PACKAGE_NAME pierce)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${PIERCE_MAINTAINER_NAME} <${PIERCE_MAINTAINER_EMAIL}>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# (CPack puts CPACK_PACKAGE_DESCRIPTION_SUMMARY on the first line, then this.)
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "Pierce returns every surface a ray crosses, in order, none missed and none twice,
also where parts touch along a plane, where faces are duplicated, and where rays
pass exactly through edges and vertices.
.
This package holds the `pierce` command-line tool (thickness maps, overlap checks,
ray classification, shotlines on STL/OBJ/OFF/PLY/STEP/IGES/BREP models), the
libpierce C++ library with its headers and CMake package (Pierce::core), the
ParaView 5.11 plugin PierceParaView, the FreeCAD workbench Pierce and the Python
modules pierce and pierce_vtk for /usr/bin/python3.")
# Depends: computed by dpkg-shlibdeps from the ELF files (runtime libraries: Embree, TBB, OCCT,
# ParaView's VTK, Python), plus what the Python parts import.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${CMAKE_BINARY_DIR}/core ${CMAKE_BINARY_DIR}/lib)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3 (>= 3.11), python3 (<< 3.12), python3-numpy")
# pierce_vtk imports ParaView's vtkmodules; the workbench needs FreeCAD. The CMake package needs
# the development files of Embree and TBB and a compiler, which a user of the tools does not.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3-paraview, freecad")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "libembree-dev, libtbb-dev, cmake, g++")
set(PIERCE_DEB_PARAVIEW_CONF ${CPACK_PACKAGING_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}/paraview.conf)
set(PIERCE_DEB_PYCACHE_DIRS
  "${CPACK_PACKAGING_INSTALL_PREFIX}/${PIERCE_INSTALL_PYTHONDIR}/pierce ${CPACK_PACKAGING_INSTALL_PREFIX}/${PIERCE_INSTALL_PYTHONDIR}/pierce_vtk ${CPACK_PACKAGING_INSTALL_PREFIX}/${CMAKE_INSTALL_DATAROOTDIR}/freecad/Mod/Pierce")
configure_file(packaging/debian/preinst.in ${CMAKE_BINARY_DIR}/packaging/debian/preinst @ONLY)
configure_file(packaging/debian/prerm.in ${CMAKE_BINARY_DIR}/packaging/debian/prerm @ONLY)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
  ${CMAKE_BINARY_DIR}/packaging/debian/preinst ${CMAKE_BINARY_DIR}/packaging/debian/prerm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
