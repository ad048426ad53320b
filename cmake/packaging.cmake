# A Debian package of the install rules (CMakeLists.txt: the program, the Python package, the man
# page, the completion, the example notebook) with CPack: `make package`, or in build/
# `cpack -G DEB`. Checked by CTest package.deb_holds_the_install_and_its_dependencies
# (tests/install/test_package.sh).
# cpack (and `make install`) install what is built and build nothing first: without this, cpack's
# preinstall step would build every target (the test suite, the benchmarks) before packaging.
# `make package` and `make install` build the program and its man page and completion first.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY TRUE)
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME tidalcrust)
set(CPACK_PACKAGE_VENDOR "tidalcrust")
set(CPACK_PACKAGE_CONTACT "tidalcrust developers <tidalcrust@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "crustal failure on icy moons from a strong tidal encounter (mass-spring N-body)")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://github.com/tidalcrust/tidalcrust")
# The shared libraries the program links (HDF5, fmt, toml++, xxHash, SLEEF, libgomp, libstdc++, ...) become
# Depends through dpkg-shlibdeps, with the versions this build needs.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The Python package lies in lib/python3.X/dist-packages under /usr (TIDALCRUST_PYTHON_SITE, read by
# Debian's python3.X) unless configured with CMAKE_INSTALL_PREFIX=/usr (lib/python3/dist-packages):
# then it needs that python3. Its imports: docs/python.md.
if(TIDALCRUST_PYTHON_SITE MATCHES "python3\\.([0-9]+)/")
  math(EXPR TIDALCRUST_PYTHON_NEXT_MINOR "${CMAKE_MATCH_1} + 1")
  set(TIDALCRUST_PYTHON_DEPENDS "python3 (>= 3.${CMAKE_MATCH_1}), python3 (<< 3.${TIDALCRUST_PYTHON_NEXT_MINOR})")
else()
  set(TIDALCRUST_PYTHON_DEPENDS "python3")
endif()
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "${TIDALCRUST_PYTHON_DEPENDS}, python3-numpy, python3-h5py, python3-xarray, python3-matplotlib, python3-pyproj, python3-geopandas, python3-shapely, python3-cartopy")
include(CPack)
