# Sourced by the scripts that need the built core: configures $build once (Release)
# and builds the describe tool and every FMU binary; a rebuild only relinks what changed.
# Needs $root and $build set.
cmake_bin=/usr/bin/cmake
if [ ! -f "$build/CMakeCache.txt" ]; then
  "$cmake_bin" -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
"$cmake_bin" --build "$build" -j"$(nproc)" --target rigidfmu-describe rigidfmu_fmus >/dev/null
