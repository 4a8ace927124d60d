"""kerf view under Xvfb with scripted mouse events (drag_across.txt): the hanging block settles, the blade is
dragged across its middle, and it hangs open. The screenshots' pixels must show it: none of the background
(white) inside the body before the drag, a thin slot right after it (the cells the blade crossed), and a gap
at least 1.6 times that once the body's weight has opened the cut (measured: 2.1).

Before that, what it cannot draw (no display, a 2D scene, a bad --size) must be refused naming why.

    /usr/bin/python3 drag_opens_the_cut.py KERF OUT_DIR     (exit 77: no X server here, the drag is skipped)
"""
import os
import shutil
import subprocess
import sys

import numpy as np
import matplotlib.image

HERE = os.path.dirname(os.path.abspath(__file__))


def background_pixels(path):
    """White pixels in the window's middle (where the body is; the status text is at the bottom)."""
    image = matplotlib.image.imread(path)[:, :, :3]
    h, w = image.shape[:2]
    middle = image[int(0.3 * h):int(0.7 * h), int(0.3 * w):int(0.7 * w)]
    return int(np.all(middle == 1.0, axis=2).sum())


def refusal(kerf, arguments, environment):
    """kerf view's exit code and its error output."""
    done = subprocess.run([kerf, "view"] + arguments, env=environment, capture_output=True, text=True)
    return done.returncode, done.stderr


def check_refusals(kerf):
    """What kerf view cannot draw is refused naming why, before any window opens."""
    scene = os.path.join(HERE, "hanging_block.yaml")
    no_display = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    code, error = refusal(kerf, [scene], no_display)
    assert code == 1 and "no display is set (DISPLAY)" in error and "xvfb-run" in error, error
    flat = os.path.join(HERE, "..", "..", "scenes", "plate_tension_2d.yaml")
    code, error = refusal(kerf, [flat], dict(os.environ, DISPLAY=":0"))
    assert code == 1 and "key 'domain'" in error and "3D" in error, error
    code, error = refusal(kerf, [scene, "--size", "big"], no_display)
    assert code == 1 and "--size" in error and "WIDTHxHEIGHT" in error, error


def main(kerf, out):
    check_refusals(kerf)
    if shutil.which("xvfb-run") is None:
        print("skipped: xvfb-run is not installed (package xvfb)")
        return 77
    if subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 64x64x24", "true"], capture_output=True).returncode != 0:
        print("skipped: no X server can start here")
        return 77
    os.makedirs(out, exist_ok=True)
    for name in ("hanging_block.yaml", "drag_across.txt"):
        shutil.copy(os.path.join(HERE, name), out)
    command = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", kerf, "view", "hanging_block.yaml",
               "--script", "drag_across.txt", "--size", "600x600", "--blade-depth", "0.05", "--out", "run"]
    subprocess.run(command, cwd=out, check=True)
    before, cut, opened = (background_pixels(os.path.join(out, f)) for f in ("before.png", "cut.png", "opened.png"))
    print(f"background pixels inside the body: before the drag {before}, right after it {cut}, opened {opened}")
    assert before == 0, "the body is not whole before the drag"
    assert cut > 500, "the drag left no slot: the blade did not cut"
    assert opened > 1.6 * cut, "the cut did not open under the body's weight"
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
