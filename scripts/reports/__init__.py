"""The generated reports (`scripts/report.sh KIND`), made from the source tree's build:
accuracy (the methods' error and order), stability (the stress suite), performance
(core, FMU and MuJoCo benchmarks; pruning; FMU timing) and the example FMUs' table.
The *_peers modules and mujoco_free_body run in the peers' own venv (.venv-peers,
scripts/peers_venv.sh), which has MuJoCo and this package's Python code."""
