"""Simulates an FMU with fmpy; writes the result as CSV and plots of every body's
position, velocity and the energy (kinetic, potential, total)."""
import argparse
import pathlib

import matplotlib
import numpy as np
from fmpy import read_model_description, simulate_fmu
from fmpy.util import write_csv

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def bodies_of(md):
    return sorted({v.name.split(".")[0] for v in md.modelVariables if v.name.endswith(".mass")})


def vector(result, body, field):
    return np.column_stack([result[f"{body}.{field}[{i}]"] for i in (1, 2, 3)])


def energies(result, md, bodies):
    """Kinetic 1/2 (m v.v + omega.L) and potential -m g.x of all bodies, J."""
    start = {v.name: float(v.start) for v in md.modelVariables if v.start is not None and v.type == "Real"}
    g = np.array([start[f"gravity[{i}]"] for i in (1, 2, 3)])
    kinetic = np.zeros(len(result))
    potential = np.zeros(len(result))
    for b in bodies:
        m = start[f"{b}.mass"]
        v, w, L = (vector(result, b, f) for f in ("velocity", "angularVelocity", "angularMomentum"))
        kinetic += 0.5 * (m * np.sum(v * v, axis=1) + np.sum(w * L, axis=1))
        potential += -m * vector(result, b, "position") @ g
    return kinetic, potential


def plot(result, md, out_dir, name):
    bodies = bodies_of(md)
    t = result["time"]
    files = []
    for field, unit in (("position", "m"), ("velocity", "m/s")):
        fig, axes = plt.subplots(3, 1, sharex=True, figsize=(8, 7))
        for i, axis in enumerate("xyz"):
            for b in bodies:
                axes[i].plot(t, result[f"{b}.{field}[{i + 1}]"], label=b)
            axes[i].set_ylabel(f"{field} {axis} [{unit}]")
            axes[i].grid(True)
        axes[0].legend(loc="best")
        axes[-1].set_xlabel("time [s]")
        fig.suptitle(f"{name}: {field}")
        files.append(out_dir / f"{name}_{field}.png")
        fig.savefig(files[-1], dpi=100)
        plt.close(fig)
    kinetic, potential = energies(result, md, bodies)
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.plot(t, kinetic, label="kinetic")
    ax.plot(t, potential, label="potential")
    ax.plot(t, kinetic + potential, label="total", color="k")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("energy [J]")
    ax.grid(True)
    ax.legend(loc="best")
    fig.suptitle(f"{name}: energy")
    files.append(out_dir / f"{name}_energy.png")
    fig.savefig(files[-1], dpi=100)
    plt.close(fig)
    return files


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("fmu")
    parser.add_argument("--stop-time", type=float, default=5.0)
    parser.add_argument("--output-interval", type=float, default=0.01)
    parser.add_argument("--out", default="out")
    args = parser.parse_args()
    out_dir = pathlib.Path(args.out)
    out_dir.mkdir(parents=True, exist_ok=True)
    md = read_model_description(args.fmu)
    name = pathlib.Path(args.fmu).stem
    result = simulate_fmu(args.fmu, stop_time=args.stop_time, output_interval=args.output_interval)
    csv = out_dir / f"{name}.csv"
    write_csv(str(csv), result)
    files = plot(result, md, out_dir, name)
    print(f"{md.modelName}: simulated {args.stop_time} s, {len(bodies_of(md))} bodies")
    for f in [csv, *files]:
        print(f"  wrote {f}")


if __name__ == "__main__":
    main()
