"""scripts/bench_scenes.py DIR [--tilt A,B]: writes the benchmark scenes (rigidfmu.scenes.bench)
to DIR, as `python -m rigidfmu.scenes.bench DIR` does (bench/bench_core.cpp names this path)."""
import sys

from rigidfmu.scenes.bench import main

main(sys.argv[1:])
