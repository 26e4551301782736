# Sourced by the scripts that run the peer engines (peers.sh, bench.sh): creates or
# updates their own venv, .venv-peers, from scripts/peers-requirements.txt (MuJoCo),
# so that the project's packages never depend on them. Needs $root; sets $peers_venv.
peers_venv="$root/.venv-peers"
peers_stamp="$peers_venv/.requirements.sha256"
peers_want="$(sha256sum "$root/scripts/peers-requirements.txt" | cut -d' ' -f1)"
if [ ! -f "$peers_stamp" ] || [ "$(cat "$peers_stamp")" != "$peers_want" ]; then
  python3 -m venv "$peers_venv"
  "$peers_venv/bin/pip" install -q --disable-pip-version-check -r "$root/scripts/peers-requirements.txt"
  echo "$peers_want" > "$peers_stamp"
fi
# this package's Python code (python/rigidfmu: the peers' modules in reports/, the
# references) on its path, as in .venv
peers_site="$("$peers_venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
[ -f "$peers_site/rigidfmu-source.pth" ] || echo "$root/python" > "$peers_site/rigidfmu-source.pth"
