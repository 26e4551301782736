#!/usr/bin/env bash
# Installs everything rigidfmu needs on a fresh Debian machine: the Debian packages
# (compiler, CMake, Eigen, FCL, nlohmann-json, GoogleTest, clang-format for the style
# test, chromium for the replay's browser test; MinGW-w64, dpkg-dev and a deb-src
# entry for the win64 binaries, which scripts/win64_deps.sh builds from Debian's FCL
# and libccd sources, and wine64 to test them), a Python venv (.venv) with the pinned packages of requirements.txt and
# the replay page's npm packages (python/rigidfmu/replay/page/package-lock.json; Node.js and npm come
# with the machine). Idempotent and quick when done.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

debian_packages=(
  build-essential cmake python3-venv patchelf
  libeigen3-dev libfcl-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev clang-format
  chromium
  g++-mingw-w64-x86-64-posix dpkg-dev wine64
)
sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
# Debian's source packages (apt-get source fcl libccd, scripts/win64_deps.sh)
sources=/etc/apt/sources.list.d/rigidfmu-deb-src.sources
if [ -z "$(apt-cache showsrc libccd 2>/dev/null)" ]; then
  echo "setup: adding Debian's source packages ($sources)"
  . /etc/os-release
  printf 'Types: deb-src\nURIs: http://deb.debian.org/debian\nSuites: %s %s-updates\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
    "$VERSION_CODENAME" "$VERSION_CODENAME" | "${sudo_cmd[@]}" tee "$sources" >/dev/null
  "${sudo_cmd[@]}" apt-get update -qq
fi
missing=()
for p in "${debian_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing Debian packages: ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

venv="$root/.venv"
stamp="$venv/.requirements.sha256"
want="$(sha256sum "$root/requirements.txt" | cut -d' ' -f1)"
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  echo "setup: creating $venv with the pinned Python packages"
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q --disable-pip-version-check -r "$root/requirements.txt"
  echo "$want" > "$stamp"
fi
# The source tree's package (python/rigidfmu) on the venv's path, as an editable install
# would put it, so that `.venv/bin/python -m rigidfmu` and the tests run this tree.
site="$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
[ -f "$site/rigidfmu-source.pth" ] || echo "$root/python" > "$site/rigidfmu-source.pth"
# and the command, as pip's entry point would write it: .venv/bin/rigidfmu
if [ ! -x "$venv/bin/rigidfmu" ]; then
  printf '#!/bin/sh\nexec "%s/bin/python" -m rigidfmu "$@"\n' "$venv" > "$venv/bin/rigidfmu"
  chmod +x "$venv/bin/rigidfmu"
fi

# three.js, esbuild and playwright-core exactly as locked; npm ci empties node_modules
# first, so a changed lock never leaves a stale package behind.
replay="$root/python/rigidfmu/replay/page"
stamp="$replay/node_modules/.package-lock.sha256"
want="$(sha256sum "$replay/package-lock.json" | cut -d' ' -f1)"
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  echo "setup: installing the replay page's npm packages"
  (cd "$replay" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
  echo "$want" > "$stamp"
fi
# The page's template (dist/replay.html, rebuilt when a source is newer): a package
# installed from this tree (pip install .) carries it.
"$venv/bin/python" -c 'from rigidfmu.replay import ensure_template; ensure_template()'
