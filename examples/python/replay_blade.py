"""A recorded blade trajectory replayed through a kerf session: the organ of
scenes/organ_cut.yaml sags under its own weight while the blade's positions
(a CSV of times and the blade's two end points, as a tracker records a hand)
are fed to its live cut as the run reaches them; the support's reaction is
read after every step and plotted against time (matplotlib).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/replay_blade.py OUT_DIR [TRAJECTORY.csv]
"""
import csv
import os
import sys

import kerf  # first: it caps OpenMP before numpy loads it

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "..", "scenes", "organ_cut.yaml")
SUPPORT = "{name: support, field: reaction, select: {plane: {axis: z, at: -0.012}}}"


def read_trajectory(path):
    """[(t, top, bottom)], t in s, the blade's ends in m, in time order."""
    with open(path, newline="") as f:
        rows = [[float(v) for v in row.values()] for row in csv.DictReader(f)]
    return [(r[0], r[1:4], r[4:7]) for r in sorted(rows, key=lambda r: r[0])]


def replay(trajectory, out_dir):
    """Steps the organ with its cut fed from `trajectory`; returns times, the support's vertical reaction, the
    times the blade moved, the positions skipped (off the organ: the session refuses a piece that cuts nothing)
    and the cut's growths."""
    duration = trajectory[-1][0] + 0.05  # the last cut settles a little
    overrides = ["cuts.0.strip=[]", "cuts.0.times=[]", f"solve.duration={duration}", "output.vtk={every: 100}",
                 f"output.probes=[{SUPPORT}]"]
    times, reaction, fed_at, skipped = [], [], [], 0
    with kerf.Session(SCENE, overrides, out=out_dir) as session:
        fed = 0
        while not session.done:
            # The positions recorded within the next step, fed before it (their pieces appear by its end).
            while fed < len(trajectory) and trajectory[fed][0] <= session.time + session.dt:
                _, top, bottom = trajectory[fed]
                fed += 1
                try:
                    session.extend_cut(0, [top, bottom])
                except kerf.Error as refused:
                    if "outside the body" not in str(refused):
                        raise
                    skipped += 1  # the blade not on the organ yet: the next position goes on from the last kept
                    continue
                fed_at.append(session.time)
            session.step()
            times.append(session.time)
            reaction.append(session.probes["support"]["reaction"][2])
        growths = session.finish().summary["timing"]["cut_update_ms"]["count"]
    return times, reaction, fed_at, skipped, growths


def main(out_dir, trajectory_path):
    os.makedirs(out_dir, exist_ok=True)
    trajectory = read_trajectory(trajectory_path)
    times, reaction, fed_at, skipped, growths = replay(trajectory, os.path.join(out_dir, "run"))
    plt.figure(figsize=(6, 3.5))
    plt.plot(times, reaction, label="support reaction, z")
    for t in fed_at:
        plt.axvline(t, color="0.85", linewidth=0.8, zorder=0)
    plt.xlabel("time (s); grey: a blade position fed")
    plt.ylabel("reaction (N)")
    plt.title("organ_cut: a recorded blade replayed through a session")
    plt.tight_layout()
    plot = os.path.join(out_dir, "replay_blade.png")
    plt.savefig(plot, dpi=120)
    print(f"{len(fed_at)} blade positions fed ({skipped} off the organ skipped) over {len(times)} steps, "
          f"the cut grown {growths} times; "
          f"final reaction z {reaction[-1]:.6g} N; {plot}")


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2] if len(sys.argv) == 3 else os.path.join(HERE, "blade_trajectory.csv"))
