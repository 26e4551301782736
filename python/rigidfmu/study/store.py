"""A study's results on disk: one Parquet part-file per finished batch in OUT/parts/
(written whole or not at all, so an interrupted study loses at most the batches in
flight), and OUT/results.parquet, the design's rows consolidated at the end."""
import os
import pathlib
import time
import uuid

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq


def parts_dir(out: pathlib.Path) -> pathlib.Path:
    return out / "parts"


def write_part(out: pathlib.Path, rows: list) -> pathlib.Path:
    parts = parts_dir(out)
    parts.mkdir(parents=True, exist_ok=True)
    frame = pd.DataFrame(rows)
    # the order rows were written in, so that a retried run's newer row wins
    frame["written"] = time.time_ns()
    name = f"part-{time.time_ns()}-{uuid.uuid4().hex[:8]}.parquet"
    tmp = parts / f".{name}.tmp"
    pq.write_table(pa.Table.from_pandas(frame, preserve_index=False), tmp)
    os.replace(tmp, parts / name)  # atomic: a part is there whole or not at all
    return parts / name


def read_parts(out: pathlib.Path, columns=None) -> pd.DataFrame:
    files = sorted(parts_dir(out).glob("part-*.parquet"))
    if not files:
        return pd.DataFrame(columns=columns or ["run_id", "status", "written"])
    frames = [pq.read_table(f, columns=columns).to_pandas() for f in files]
    frame = pd.concat(frames, ignore_index=True)
    # the newest row of each run (a run retried with --retry-failed has two)
    return frame.sort_values("written", kind="stable").drop_duplicates("run_id", keep="last")


def finished(out: pathlib.Path) -> dict:
    """run_id -> status of every run with a result in OUT."""
    frame = read_parts(out, columns=["run_id", "status", "written"])
    return dict(zip(frame["run_id"], frame["status"]))


def consolidate(out: pathlib.Path, design: pd.DataFrame) -> pd.DataFrame:
    """OUT/results.parquet: the design's runs (design columns first, in design order)
    joined with their results; rows of runs no longer in the study stay in parts/."""
    results = read_parts(out).drop(columns=["written"])
    frame = design.merge(results, on="run_id", how="left", validate="one_to_one")
    frame = frame.sort_values("run").reset_index(drop=True)
    tmp = out / ".results.parquet.tmp"
    pq.write_table(pa.Table.from_pandas(frame, preserve_index=False), tmp)
    os.replace(tmp, out / "results.parquet")
    return frame
