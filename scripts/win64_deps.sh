#!/usr/bin/env bash
# The win64 FMU binaries' dependencies, cross-compiled with MinGW-w64 from Debian's own
# source packages (apt-get source: the upstream tarball with Debian's patches) and
# installed as static libraries into a cache shared by every checkout on this machine:
#   libccd (double precision, as Debian builds it) and FCL (without OctoMap, which the
#   core does not use). Eigen and nlohmann-json are headers: the host's are used.
# Prints the cache's path on stdout; builds only when the cache lacks this version.
# Needs: g++-mingw-w64-x86-64-posix, dpkg-dev and a deb-src entry (scripts/setup.sh).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
toolchain="$root/cmake/mingw-w64-x86_64.cmake"
cmake=/usr/bin/cmake  # Debian's, as the other scripts use

# The cache key: the source versions, the compiler and the toolchain file.
fcl_version="$(apt-cache showsrc fcl | sed -n 's/^Version: //p' | head -1)"
ccd_version="$(apt-cache showsrc libccd | sed -n 's/^Version: //p' | head -1)"
if [ -z "$fcl_version" ] || [ -z "$ccd_version" ]; then
  echo "win64_deps: no Debian source package for fcl or libccd (a deb-src entry is needed: scripts/setup.sh adds it)" >&2
  exit 1
fi
key="$(printf '%s\n' "fcl $fcl_version" "libccd $ccd_version" "$(x86_64-w64-mingw32-g++-posix --version | head -1)" \
  "$(sha256sum "$toolchain" "$0" | cut -d' ' -f1)" | sha256sum | cut -c1-16)"
cache="${RIGIDFMU_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/rigidfmu}/win64-deps-$key"
if [ -f "$cache/.complete" ]; then
  echo "$cache"
  exit 0
fi

start=$SECONDS
work="$(mktemp -d "${TMPDIR:-/tmp}/rigidfmu-win64-deps.XXXXXX")"
trap 'rm -rf "$work"' EXIT
prefix="$cache.partial"  # installed straight there, then renamed: a reader never sees half a cache
mkdir -p "$(dirname "$cache")" && rm -rf "$prefix"
echo "win64_deps: building libccd $ccd_version and FCL $fcl_version for win64 (once per machine)" >&2
(cd "$work" && apt-get source -qq libccd fcl >/dev/null 2>&1) || {
  echo "win64_deps: apt-get source libccd fcl failed (deb-src entry, dpkg-dev?)" >&2; exit 1; }
common=(-DCMAKE_TOOLCHAIN_FILE="$toolchain" -DRIGIDFMU_WIN64_DEPS="$prefix" -DCMAKE_PREFIX_PATH="$prefix"
        -DCMAKE_INSTALL_PREFIX="$prefix" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF -Wno-dev)
jobs="-j$(nproc)"
log="$work/build.log"
quiet() { "$@" >>"$log" 2>&1 || { tail -30 "$log" >&2; echo "win64_deps: failed: $*" >&2; exit 1; }; }
quiet "$cmake" -S "$(echo "$work"/libccd-*/)" -B "$work/ccd" "${common[@]}" -DBUILD_SHARED_LIBS=OFF \
  -DENABLE_DOUBLE_PRECISION=ON
quiet "$cmake" --build "$work/ccd" "$jobs"
quiet "$cmake" --install "$work/ccd"
quiet "$cmake" -S "$(echo "$work"/fcl-*/)" -B "$work/fcl" "${common[@]}" -DFCL_STATIC_LIBRARY=ON \
  -DFCL_WITH_OCTOMAP=OFF -DFCL_BUILD_TESTS=OFF -DEigen3_DIR=/usr/share/eigen3/cmake
quiet "$cmake" --build "$work/fcl" "$jobs"
quiet "$cmake" --install "$work/fcl"

touch "$prefix/.complete"
rm -rf "$cache" && mv "$prefix" "$cache"
echo "win64_deps: done in $((SECONDS - start)) s: $cache" >&2
echo "$cache"
