# Installed like any Debian program: `cmake --install build` (or the .deb
# CPack makes, scripts/package.sh) puts the two programs in bin/, the rank
# program where lightmass_server looks for it (libexec/lightcuts/, beside
# itself first: mpi/rank_bake_launcher.cpp), the README and docs in
# share/doc/lightcuts/, and the service (packaging/) in /etc and systemd's unit folder.
include(GNUInstallDirs)

install(TARGETS lightmass_server editor_client RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET lightmass_rank)
  install(TARGETS lightmass_rank RUNTIME DESTINATION ${CMAKE_INSTALL_LIBEXECDIR}/lightcuts)
endif()
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} FILES_MATCHING PATTERN "*.md" PATTERN "*.png"
        PATTERN "bench" EXCLUDE)
# The service: its unit where systemd reads packages' units, its configuration (every flag) in /etc.
install(FILES packaging/lightmass_server.service DESTINATION lib/systemd/system)
install(FILES packaging/lightmass_server.conf DESTINATION /etc/lightcuts)

set(CPACK_PACKAGE_NAME lightcuts)
set(CPACK_PACKAGE_VENDOR "lightcuts")
set(CPACK_PACKAGE_CONTACT "lightcuts maintainers <lightcuts@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Lightcuts bake server (lightmass_server) and Vulkan render client (editor_client)")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
# /etc/lightcuts is absolute: staged under DESTDIR, never written to this machine's /etc.
set(CPACK_SET_DESTDIR ON)
set(CPACK_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # lightcuts_VERSION_ARCH.deb
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
# The shared libraries' packages from dpkg-shlibdeps; what the programs run, not link, by hand:
# mpirun for bakes over ranks, a Vulkan driver (lavapipe works anywhere) for the client.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "openmpi-bin")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "mesa-vulkan-drivers | vulkan-icd")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "openexr")
# The configuration is the admin's once installed: dpkg keeps their edits on upgrade.
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/packaging/debian/conffiles)
set(CPACK_STRIP_FILES ON)
include(CPack)
