# The jaus-node Debian package (CPack DEB): `cpack -G DEB` in a built tree, or
# scripts/package.sh. Everything `cmake --install` installs goes in, under
# /usr (the configuration under /etc, cmake/install.cmake): programs, man
# pages, docs, jausd.service, libraries, headers and the CMake package.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME jaus-node)
set(CPACK_PACKAGE_VENDOR "jaus-node")
# The Maintainer field: set it to whoever publishes the package (lintian's
# bogus-mail-host until then).
set(JAUS_PACKAGE_MAINTAINER "jaus-node maintainers <jaus-node@localhost>" CACHE STRING "Maintainer of the .deb")
set(CPACK_PACKAGE_CONTACT "${JAUS_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "JAUS RA 3.x node daemon (jausd), OCU tool (jausctl) and C++20 framework")
# The control file's extended description: lines under 80 columns.
string(JOIN "\n" CPACK_PACKAGE_DESCRIPTION
       "jausd hosts JAUS RA 3.x components (node manager, communicator, primitive"
       "driver, pose and velocity sensors, visual sensor, manipulator) on UDP and"
       "drives a Clearpath platform over its serial protocol; it runs as the systemd"
       "service jausd.service with /etc/jaus/jausd.yaml. jausctl talks to nodes as an"
       "OCU, jaus-console is an operator console in a browser (drive, control,"
       "emergency, camera), jaus-conform tests any node's conformance and"
       "clearpath-sim simulates a Clearpath platform. The static libraries, headers"
       "and CMake package"
       "(find_package(jaus)) build components of your own.")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
# Executables only (never the static libraries' symbol tables).
set(CPACK_STRIP_FILES TRUE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # jaus-node_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION net)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Shared libraries the programs link: computed by dpkg-shlibdeps; adduser for postinst.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "adduser")
# Building a component against the installed libraries needs their headers' dependencies;
# the Wireshark plugin needs a Wireshark.
set(CPACK_DEBIAN_PACKAGE_SUGGESTS
    "wireshark | tshark, cmake, g++, pkg-config, libboost-dev, nlohmann-json3-dev, libpng-dev, libjpeg-dev, libgeographiclib-dev")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${PROJECT_SOURCE_DIR}/packaging/debian/postinst ${PROJECT_SOURCE_DIR}/packaging/debian/prerm
    ${PROJECT_SOURCE_DIR}/packaging/debian/postrm ${PROJECT_SOURCE_DIR}/packaging/debian/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
include(CPack)
