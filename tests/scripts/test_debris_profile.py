"""scripts/debris_profile.py on a synthetic run whose debris is placed by hand: points of the
chosen bodies in and out of the slab and the rings, a body not chosen, and the models cut by
symmetry planes through the axis or beside it. Every areal mass is a closed form, 8/pi kg/m^2
and the like, checked to the six digits the script prints."""
import contextlib
import io
import json
import pathlib
import sys
import tempfile
import unittest

import h5py
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import debris_profile  # noqa: E402

MM = 1e-3
# body, x, y, z (mm), mass (kg), v_z (m/s) of each point at 1 us. At 0 us every point is at
# z = +1 mm, above the slab.
POINTS = [
    (0, 0.25, 0.0, -1.0, 2e-6, -3000.0),   # projectile, ring 0-0.5 mm
    (0, 0.0, 0.75, -1.5, 1e-6, -1000.0),   # projectile, ring 0.5-1 mm
    (1, 0.36, 0.48, -1.2, 3e-6, -2000.0),  # front sheet, r = 0.6 mm: ring 0.5-1 mm
    (0, 0.25, 0.0, 1.0, 4e-6, -5000.0),    # projectile above the slab
    (0, 1.2, 0.0, -1.0, 5e-6, -5000.0),    # projectile beyond the outer ring
    (2, 0.25, 0.0, -1.0, 6e-6, -5000.0),   # rear sheet: not a chosen body
]


def make_run(root, boundaries):
    run = root / "run"
    (run / "snapshots").mkdir(parents=True)
    (run / "run.json").write_text(json.dumps({"bodies": ["projectile", "front", "rear"]}))
    scene = "".join(f"[[boundary]]\nface = '{face}'\nposition = {position}\ntype = '{kind}'\n\n"
                    for face, position, kind in boundaries)
    (run / "scene.resolved.toml").write_text(scene)
    p = np.array(POINTS)
    for k, time in enumerate([0.0, 1e-6]):
        position = p[:, 1:4] * MM
        if time == 0.0:
            position[:, 2] = 1.0 * MM
        with h5py.File(run / f"snapshots/particles_{k:06d}.h5", "w") as f:
            f.attrs["time"] = time
            f["body"], f["mass"], f["position"] = p[:, 0].astype(np.int64), p[:, 4], position
            f["velocity"] = np.stack([np.zeros(len(p)), np.zeros(len(p)), p[:, 5]], axis=1)
    return str(run)


def run_script(*argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = debris_profile.main(list(argv))
    return code, out.getvalue().splitlines(), err.getvalue()


SLAB = ("--bodies", "projectile,front", "--z", "-0.5 mm,-2 mm", "--bin", "0.5 mm", "--radius", "1 mm")


class DebrisProfile(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = pathlib.Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def profile(self, boundaries, *extra):
        code, lines, err = run_script(make_run(self.root, boundaries), *SLAB, *extra)
        self.assertEqual(code, 0, err)
        self.assertEqual(lines[0], "time_s,r_0_0.5_mm,r_0.5_1_mm")
        return lines, err

    def test_whole_model(self):
        # Ring 0: 2 mg over pi (0.5 mm)^2 = 8/pi kg/m^2; ring 1: 4 mg over 0.75 pi mm^2 = 16/(3 pi).
        lines, err = self.profile([("z-", -0.042, "fixed")])
        self.assertEqual(lines[1], "0,0,0")
        self.assertEqual(lines[2], "1e-06,2.54648,1.69765")
        self.assertIn("holds 1 of each ring", err)

    def test_quarter_model_holds_a_quarter_of_each_ring(self):
        lines, err = self.profile([("x-", 0.0, "symmetry"), ("y-", 0.0, "symmetry")])
        self.assertEqual(lines[2], "1e-06,10.1859,6.79061")  # 32/pi, 64/(3 pi)
        self.assertIn("holds 0.25 of each ring", err)

    def test_a_plane_beside_the_axis_does_not_cut_the_rings(self):
        lines, err = self.profile([("y-", 0.0, "symmetry"), ("x+", 0.005, "symmetry"), ("x-", 0.0, "fixed")])
        self.assertEqual(lines[2], "1e-06,5.09296,3.39531")  # 16/pi, 32/(3 pi)
        self.assertIn("holds 0.5 of each ring", err)

    def test_median_velocity(self):
        lines, _ = self.profile([], "--quantity", "velocity_z")
        self.assertEqual(lines[1], "0,nan,nan")
        self.assertEqual(lines[2], "1e-06,-3000,-1500")

    def test_bad_input_is_refused(self):
        run = make_run(self.root, [])
        code, lines, err = run_script(run, "--bodies", "projectile,core", "--z", "0 mm,-1 mm")
        self.assertEqual((code, lines), (2, []))
        self.assertIn("--bodies 'core': the run's bodies are projectile, front, rear", err)
        code, lines, err = run_script(run, "--bodies", "projectile", "--z", "-1 mm")
        self.assertEqual((code, lines), (2, []))
        self.assertIn("--z '-1 mm': expected two lengths", err)
        code, lines, err = run_script(run, "--bodies", "projectile", "--z", "0 mm,-1 mm", "--radius", "1.2 mm")
        self.assertEqual((code, lines), (2, []))
        self.assertIn("--radius 1.2 mm is not a whole number of 0.5 mm rings", err)


if __name__ == "__main__":
    unittest.main()
