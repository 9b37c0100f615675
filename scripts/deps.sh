# Sourced by scripts/test, scripts/studio and scripts/package: installs the Debian packages the
# product needs (the whole set, so that later work does not fight the install), only those that
# are missing. clang and clang-format are the second compiler and the format check
# (scripts/check-clang, scripts/check-format); desktop-file-utils and shared-mime-info check the
# installed desktop entry and MIME type (tests/install_test.cmake). The Python module needs
# pybind11 and Python's headers, its tests numpy, pytest and Dask's distributed (docs/python.md);
# libclang-rt-14-dev holds libFuzzer and the sanitizer runtimes of clang 14 (scripts/fuzz).
# libtiff-dev and libpng-dev read and write the field's GeoTIFF rasters and draw the maps' PNGs
# (docs/field.md; 7 packages, 1.6 MB, where GDAL would pull 100 more: docs/install.md).
# --no-install-recommends: the recommended packages of this list (SciPy, pandas, numba, LLVM's
# tools, Qt 5, GTK, systemd: 131 packages on a fresh machine) are not used by the build or the
# tests and took 80 of the install's 139 s (docs/install.md, "Build time").
# A script that needs more than the product (scripts/screenshots: openbox; scripts/package:
# file, which CPack's package generator runs) passes them: terra_install_dependencies openbox.
# Uses sudo only when not root.

TERRA_PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  qt6-base-dev qt6-svg-dev libqcustomplot-dev
  libeigen3-dev libbullet-dev libceres-dev libboost-dev libtiff-dev libpng-dev
  nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth fonts-dejavu-core
  clang clang-format desktop-file-utils shared-mime-info libclang-rt-14-dev
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-distributed
)

terra_install_dependencies() {
  local missing=()
  local package
  for package in "${TERRA_PACKAGES[@]}" "$@"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$package")
    fi
  done
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  echo "Installing missing packages: ${missing[*]}"
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    sudo=(sudo)
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo[@]}" apt-get update -q
  "${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
}

# Configures and builds the Release tree in build/ (or $TERRA_BUILD_DIR). A new tree uses Ninja:
# it compiles a target's files while the libraries it links are still being linked, where make
# waits for each library (docs/install.md, "Build time"); a tree configured before keeps its
# generator (CMake refuses to change it). When ccache is installed (it is not in the package
# list: a fresh machine has nothing cached), a new tree compiles through it, with the paths taken
# relative to the checkout and the settings precompiled headers need (CCACHE_BASEDIR,
# CCACHE_SLOPPINESS), so that a rebuild, another clone or a worktree on the same machine reuses
# the objects already compiled. Such a tree needs ccache for as long as it is used.
terra_build() {
  local root="$1"
  local build="${TERRA_BUILD_DIR:-$root/build}"
  local options=()
  if [ ! -f "$build/CMakeCache.txt" ]; then
    if command -v ninja > /dev/null; then
      options+=(-G Ninja)
    fi
    if command -v ccache > /dev/null; then
      options+=("-DCMAKE_CXX_COMPILER_LAUNCHER=env;CCACHE_BASEDIR=$root;CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime;ccache")
    fi
  fi
  cmake -S "$root" -B "$build" "${options[@]}" -DCMAKE_BUILD_TYPE=Release
  cmake --build "$build" -j "$(nproc)"
}
