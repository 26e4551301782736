"""scripts/bench_scenes.py DIR: writes the benchmark scenes (rigidfmu.scenes.bench) to DIR,
as `python -m rigidfmu.scenes.bench DIR` does (bench/bench_core.cpp names this path)."""
import sys

from rigidfmu.scenes.bench import write

write(sys.argv[1] if len(sys.argv) > 1 else "build/bench-scenes")
