"""The figures of a run (matplotlib, PNG): every body's position and velocity, the
mechanical energy with what has been dissipated, and the contact events. Bodies keep
the colours they have in the 3D replay (replay.PALETTE; driven bodies in
replay.DRIVEN_COLOUR, their lines dashed, dotted, ...). Driven bodies and surfaces
(rigidfmu.driven) are in the position and contact figures; they have no mass, so the
energy leaves them out and says so."""
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from rigidfmu.driven import all_bodies, driven_names, is_driven  # noqa: E402
from rigidfmu.references.mechanical_energy import energies  # noqa: E402
from rigidfmu.replay import body_colour  # noqa: E402


def has(result, column):
    return column in result.dtype.names


def label_of(body):
    return f"{body['name']} (driven)" if is_driven(body) else body["name"]


DRIVEN_LINES = ["--", ":", "-.", (0, (6, 2, 1, 2, 1, 2))]  # driven bodies share a colour


def line_styles(bodies):
    """Each body's colour, as in the replay, and line: solid, or for the driven bodies
    dashed, dotted, ... in turn."""
    styles, j = [], 0
    for k, body in enumerate(bodies):
        dash = "-"
        if is_driven(body):
            dash, j = DRIVEN_LINES[j % len(DRIVEN_LINES)], j + 1
        styles.append({"color": body_colour(body, k), "linestyle": dash})
    return styles


def motion(result, scene, field, unit, title, path):
    """x, y, z of one vector column, one line per body whose CSV holds it (a driven
    body's position is its recorded input, its velocity is not recorded)."""
    t = result["time"]
    bodies = all_bodies(scene)
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(8, 7))
    for i, axis in enumerate("xyz"):
        for body, style in zip(bodies, line_styles(bodies)):
            column = f"{body['name']}.{field}[{i + 1}]"
            if has(result, column):
                axes[i].plot(t, result[column], label=label_of(body), **style)
        axes[i].set_ylabel(f"{field} {axis} [{unit}]")
        axes[i].grid(True)
    axes[0].legend(loc="best")
    axes[-1].set_xlabel("time [s]")
    missing = [label_of(b) for b in bodies if not has(result, f"{b['name']}.{field}[1]")]
    fig.suptitle(title + (f"\nnot in the CSV: {', '.join(missing)}" if missing else ""))
    fig.savefig(path, dpi=100)
    plt.close(fig)


def energy(result, scene, masses, g, title, path):
    kinetic, gravity, buoyancy, left_out = energies(result, scene, masses, g)
    total = kinetic + gravity + buoyancy
    t = result["time"]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(t, kinetic, label="kinetic")
    ax.plot(t, gravity, label="potential (gravity)")
    if scene.get("media"):
        ax.plot(t, buoyancy, label="potential (buoyancy)")
    ax.plot(t, total, label="total E", color="k")
    given = driven_names(scene)
    lost = "dissipated less the driven bodies' work" if given else "dissipated"
    ax.plot(t, total[0] - total, label=f"{lost} E(0) − E(t)", color="tab:red", linestyle="--")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("energy [J]")
    ax.grid(True)
    ax.legend(loc="best", fontsize="small")
    fig.suptitle(f"{title}\n{energy_note(left_out, given)}", fontsize="medium")
    fig.savefig(path, dpi=100)
    plt.close(fig)


def energy_note(left_out, given):
    """What the energy figure counts, under its title."""
    note = "friction, impacts and drag dissipate"
    if given:
        note += f"; driven, not counted (no mass, motion given): {', '.join(given)}"
    if left_out:
        note += f"; not counted (no pose/velocity outputs): {', '.join(left_out)}"
    return note


def contacts(result, scene, title, path):
    """One row per body: a bar while it touches something (b.contacts > 0, at the
    communication points), a tick where its number of contact points changes."""
    t = result["time"]
    bodies = all_bodies(scene)
    fig, ax = plt.subplots(figsize=(8, 1.2 + 0.5 * len(bodies)))
    dt = np.diff(t, append=t[-1] + (t[-1] - t[-2] if len(t) > 1 else 1.0))
    for row, body in enumerate(bodies):
        column = f"{body['name']}.contacts"
        if not has(result, column):
            ax.text(t[0], row, "  (contacts not an output)", va="center", fontsize="small")
            continue
        n = np.asarray(result[column])
        touching = n > 0
        ax.broken_barh([(t[i], dt[i]) for i in np.flatnonzero(touching)], (row - 0.3, 0.6),
                       color=body_colour(body, row), alpha=0.6, linewidth=0)
        changes = np.flatnonzero(np.diff(n) != 0) + 1
        ax.vlines(t[changes], row - 0.4, row + 0.4, color="k", linewidth=0.8)
        for i in changes:
            ax.text(t[i], row + 0.42, str(n[i]), fontsize=6, ha="center")
    ax.set_yticks(range(len(bodies)), [label_of(b) for b in bodies])
    ax.set_ylim(-0.7, len(bodies) - 0.3)
    ax.invert_yaxis()
    ax.set_xlim(t[0], t[-1])
    ax.set_xlabel("time [s]")
    ax.grid(True, axis="x")
    fig.suptitle(f"{title}\nbar: in contact; tick and number: contact points change", fontsize="medium")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_run(result, scene, masses, g, out_dir, name):
    """Writes out_dir/<name>_{position,velocity,energy,contacts}.png; returns the paths."""
    label = scene.get("name", name)
    paths = {kind: out_dir / f"{name}_{kind}.png" for kind in ("position", "velocity", "energy", "contacts")}
    motion(result, scene, "position", "m", f"{label}: position of the centre of mass", paths["position"])
    motion(result, scene, "velocity", "m/s", f"{label}: velocity", paths["velocity"])
    bodies = "the free bodies" if driven_names(scene) else "all bodies"
    energy(result, scene, masses, g, f"{label}: mechanical energy of {bodies}", paths["energy"])
    contacts(result, scene, f"{label}: contact events", paths["contacts"])
    return list(paths.values())
