"""scripts/bench_scenes.py DIR [--tilt A,B]: writes the benchmark scenes (reports.scenes)
to DIR, as `python -m reports.scenes DIR` does (bench/bench_core.cpp names this path)."""
import sys

from reports.scenes import main

main(sys.argv[1:])
