"""scripts/failure_history.py on a synthetic run whose failures are known: a sheet of two point
layers, points followed by id (reordered between snapshots, one removed, one eroded), another
body's failures ignored. Every fraction is a ratio of small integers, checked exactly."""
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
import failure_history  # noqa: E402


def write_snapshot(path, time, ids, body, position, failed, reference=None):
    """Besides the given fields, each point's state is set by its id: velocity_z = -id m/s,
    volume_ratio = 1 + id / 1000, pressure = id MPa, plastic_strain = id / 100, and a stress of that
    pressure plus an xy shear of 2 MPa, so its largest principal stress is (2 - id) MPa."""
    with h5py.File(path, "w") as f:
        f.attrs["time"] = time
        f["id"], f["body"], f["position"], f["failed"] = ids, body, position, failed
        f["velocity"] = np.stack([np.zeros(ids.size), np.zeros(ids.size), -ids.astype(float)], axis=1)
        f["volume_ratio"] = 1.0 + ids / 1000.0
        f["pressure"] = ids * 1e6
        f["plastic_strain"] = ids / 100.0
        stress = np.zeros((ids.size, 6))  # xx xy xz yy yz zz
        stress[:, 0] = stress[:, 3] = stress[:, 5] = -ids * 1e6
        stress[:, 1] = 2e6
        f["stress"] = stress
        if reference is not None:
            f["reference_position"] = reference


def make_run(root):
    """Body 1 ('sheet'): points at x = 0.25, 0.75, 1.25, 1.75 mm on y = 0, in two layers
    (z = 0 and z = -0.1 mm), ids 10..17 (top layer first). Body 0 ('projectile'): two points on the
    axis, failed from the start. At 1 us the top layer's points at x = 0.25 and 0.75 mm have
    failed (one of them eroded); at 2 us the bottom layer's point at x = 0.25 mm has left the
    model too, and the snapshot lists the points in reverse order. From 1 us on each sheet point
    has moved (id - 9) * 0.01 mm along +x, away from the axis."""
    run = root / "run"
    (run / "snapshots").mkdir(parents=True)
    (run / "run.json").write_text(json.dumps({"bodies": ["projectile", "sheet"]}))
    xs = [0.25e-3, 0.75e-3, 1.25e-3, 1.75e-3]
    sheet = np.array([[x, 0.0, z] for z in (0.0, -0.1e-3) for x in xs])
    position = np.vstack([[[0.0, 0.0, 1e-3], [0.0, 0.0, 2e-3]], sheet])
    ids = np.array([1, 2] + list(range(10, 18)))
    body = np.array([0, 0] + [1] * 8)
    failed = np.array([1.0, 1.0] + [0.0] * 8)
    write_snapshot(run / "snapshots/particles_000000.h5", 0.0, ids, body, position, failed)
    failed1 = failed.copy()
    failed1[2], failed1[3] = 1.0, 2.0  # ids 10 (failed) and 11 (eroded)
    position = position.copy()
    position[2:, 0] += (ids[2:] - 9) * 1e-5
    write_snapshot(run / "snapshots/particles_000001.h5", 1e-6, ids, body, position, failed1)
    keep = ids != 14  # the bottom layer's point at x = 0.25 mm has left the grid
    write_snapshot(run / "snapshots/particles_000002.h5", 2e-6, ids[keep][::-1], body[keep][::-1],
                   position[keep][::-1], failed1[keep][::-1])
    return run


def run_script(*argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = failure_history.main(list(argv))
    return code, out.getvalue().splitlines(), err.getvalue()


class FailureHistory(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.run_dir = str(make_run(pathlib.Path(self.tmp.name)))

    def tearDown(self):
        self.tmp.cleanup()

    def test_by_radius(self):
        code, lines, err = run_script(self.run_dir, "--body", "sheet", "--bin", "0.5 mm", "--radius", "2 mm")
        self.assertEqual(code, 0, err)
        self.assertEqual(lines[0], "time_s,r_0_0.5_mm,r_0.5_1_mm,r_1_1.5_mm,r_1.5_2_mm")
        # Two points per bin (one per layer).
        self.assertIn("r_0_0.5_mm 2, r_0.5_1_mm 2, r_1_1.5_mm 2, r_1.5_2_mm 2", err)
        self.assertEqual(lines[1], "0,0.0000,0.0000,0.0000,0.0000")
        self.assertEqual(lines[2], "1e-06,0.5000,0.5000,0.0000,0.0000")
        self.assertEqual(lines[3], "2e-06,1.0000,0.5000,0.0000,0.0000")

    def test_by_layer_within_a_radius(self):
        code, lines, err = run_script(self.run_dir, "--body", "sheet", "--by", "layer", "--radius", "1 mm")
        self.assertEqual(code, 0, err)
        self.assertEqual(lines[0], "time_s,z_0_mm,z_-0.1_mm")  # top layer first
        self.assertIn("z_0_mm 2, z_-0.1_mm 2", err)  # only the points within 1 mm
        self.assertEqual(lines[2], "1e-06,1.0000,0.0000")
        self.assertEqual(lines[3], "2e-06,1.0000,0.5000")

    def test_by_height_bins(self):
        # Bins of 0.1 mm from the sheet's top: the same two groups as its two point layers.
        code, lines, err = run_script(self.run_dir, "--body", "sheet", "--by", "height", "--bin", "0.1 mm",
                                      "--radius", "1 mm")
        self.assertEqual(code, 0, err)
        self.assertEqual(lines[0], "time_s,z_0_-0.1_mm,z_-0.1_-0.2_mm")
        self.assertIn("z_0_-0.1_mm 2, z_-0.1_-0.2_mm 2", err)
        self.assertEqual(lines[3], "2e-06,1.0000,0.5000")

    def test_medians_over_intact_points(self):
        # At 1 us the bins' intact points are ids 14 | 15 | 12, 16 | 13, 17; at 2 us id 14 is gone.
        def rows(quantity):
            code, lines, err = run_script(self.run_dir, "--body", "sheet", "--bin", "0.5 mm", "--radius", "2 mm",
                                          "--quantity", quantity)
            self.assertEqual(code, 0, err)
            return [[float(v) for v in line.split(",")[1:]] for line in lines[1:]]
        outward = rows("outward")
        self.assertEqual(outward[0], [0.0, 0.0, 0.0, 0.0])
        for got, want in zip(outward[1], [5e-5, 6e-5, 5e-5, 6e-5]):
            self.assertAlmostEqual(got, want, delta=1e-12)
        self.assertTrue(np.isnan(outward[2][0]))  # no intact point left in the first bin
        self.assertEqual(rows("velocity_z")[1], [-14.0, -15.0, -14.0, -15.0])
        self.assertEqual(rows("volume_ratio")[1], [1.014, 1.015, 1.014, 1.015])
        self.assertEqual(rows("pressure")[1], [14e6, 15e6, 14e6, 15e6])
        self.assertEqual(rows("plastic_strain")[1], [0.14, 0.15, 0.14, 0.15])
        for got, want in zip(rows("principal")[1], [-12e6, -13e6, -12e6, -13e6]):
            self.assertAlmostEqual(got, want, delta=1e-6)

    def test_an_axis_off_the_origin(self):
        # Axis at x = 2 mm: the points at 1.75 and 1.25 mm fall in the first two bins, unfailed.
        code, lines, _ = run_script(self.run_dir, "--body", "sheet", "--axis", "2 mm,0 mm", "--radius", "1 mm")
        self.assertEqual(code, 0)
        self.assertEqual(lines[3], "2e-06,0.0000,0.0000")

    def test_by_distance_from_the_walls(self):
        # Cells of 4 mm centred on the axis: the walls' mid-surfaces at x = +-2 mm, so the points at
        # x = 0.25 .. 1.75 mm stand 1.75 .. 0.25 mm from a wall (one bin each of 0.5 mm).
        pathlib.Path(self.run_dir, "scene.resolved.toml").write_text(
            "[[panel]]\ncell_diameter = 0.004\nrotation = 0.0\npattern_origin = [0.0, 0.0]\n"
            "origin_at = 'cell-center'\n")
        code, lines, err = run_script(self.run_dir, "--body", "sheet", "--by", "wall", "--bin", "0.5 mm",
                                      "--radius", "2 mm")
        self.assertEqual(code, 0, err)
        self.assertEqual(lines[0], "time_s,w_0_0.5_mm,w_0.5_1_mm,w_1_1.5_mm,w_1.5_2_mm")
        self.assertEqual(lines[2], "1e-06,0.0000,0.0000,0.5000,0.5000")  # x = 0.75 and 0.25 mm, top layer
        self.assertEqual(lines[3], "2e-06,0.0000,0.0000,0.5000,1.0000")

    def test_wall_distance_of_turned_and_shifted_patterns(self):
        D = 4e-3
        def panel(rotation=0.0, origin=(0.0, 0.0), at="cell-center"):
            return {"cell_diameter": D, "rotation": rotation, "pattern_origin": list(origin), "origin_at": at}
        xy = np.array([[1.75e-3, 0.0], [0.0, 0.0], [2.0e-3, 0.0], [0.0, 1.0e-3]])
        d = failure_history.wall_distance(xy, panel())
        np.testing.assert_allclose(d, [0.25e-3, 2e-3, 0.0, 2e-3 - 1e-3 * np.sin(np.pi / 3)], atol=1e-12)
        # Turned by 30 degrees the nearest walls of the centre cell face 30 and -30 degrees.
        d = failure_history.wall_distance(xy[:1], panel(rotation=np.pi / 6))
        np.testing.assert_allclose(d, [2e-3 - 1.75e-3 * np.cos(np.pi / 6)], atol=1e-12)
        # A wall's middle at the origin: the point 0.25 mm off it along x is 0.25 mm from the wall.
        d = failure_history.wall_distance(np.array([[0.25e-3, 0.0]]), panel(at="wall"))
        np.testing.assert_allclose(d, [0.25e-3], atol=1e-12)
        # Shifted by half a cell of the grid: the same distances, shifted.
        d = failure_history.wall_distance(xy[:1] + [1e-4, 0.0], panel(origin=(1e-4, 0.0)))
        np.testing.assert_allclose(d, [0.25e-3], atol=1e-12)

    def test_bad_input_is_refused(self):
        code, _, err = run_script(self.run_dir, "--body", "rear")
        self.assertEqual(code, 2)
        self.assertIn("--body 'rear': the run's bodies are projectile, sheet", err)
        code, _, err = run_script(self.run_dir, "--body", "sheet", "--bin", "0.5 furlongs")
        self.assertEqual(code, 2)
        self.assertIn("--bin '0.5 furlongs': unknown unit 'furlongs'", err)


def make_growing_run(root):
    """A growing zone's run: snapshots carry reference_position. At 0 us the sheet holds ids 10, 11
    (X at x = 0.25 and 1.25 mm). At 1 us a take-over adds ids 20, 21 (X at x = 0.75 and 1.75 mm),
    and id 10, failed, has flown out to x = 1.8 mm (still grouped by its X, 0.25 mm). At 2 us id
    21 has failed too and id 11 has left the model."""
    run = root / "growing"
    (run / "snapshots").mkdir(parents=True)
    (run / "run.json").write_text(json.dumps({"bodies": ["sheet"]}))
    X = {10: 0.25e-3, 11: 1.25e-3, 20: 0.75e-3, 21: 1.75e-3}

    def snapshot(k, time, ids, failed, moved=None):
        ids = np.array(ids)
        reference = np.array([[X[i], 0.0, 0.0] for i in ids])
        position = reference.copy()
        for i, x in (moved or {}).items():
            position[list(ids).index(i), 0] = x
        write_snapshot(run / f"snapshots/particles_{k:06d}.h5", time, ids, np.zeros(ids.size, dtype=int), position,
                       np.array(failed, dtype=float), reference)
    snapshot(0, 0.0, [10, 11], [0, 0])
    snapshot(1, 1e-6, [21, 10, 11, 20], [0, 1, 0, 0], {10: 1.8e-3})
    snapshot(2, 2e-6, [10, 20, 21], [1, 0, 1], {10: 1.9e-3})
    return run


class GrowingZone(unittest.TestCase):
    def test_points_born_later_are_grouped_by_where_they_started(self):
        with tempfile.TemporaryDirectory() as root:
            run = str(make_growing_run(pathlib.Path(root)))
            code, lines, err = run_script(run, "--body", "sheet", "--bin", "0.5 mm", "--radius", "2 mm")
            self.assertEqual(code, 0, err)
            # One point per bin, each counted from the snapshot that first holds it.
            self.assertIn("r_0_0.5_mm 1, r_0.5_1_mm 1, r_1_1.5_mm 1, r_1.5_2_mm 1", err)
            self.assertEqual(lines[1], "0,0.0000,0.0000,0.0000,0.0000")
            self.assertEqual(lines[2], "1e-06,1.0000,0.0000,0.0000,0.0000")  # the fragment, by its X
            self.assertEqual(lines[3], "2e-06,1.0000,0.0000,1.0000,1.0000")  # id 11 gone, id 21 failed
            code, lines, err = run_script(run, "--body", "sheet", "--bin", "0.5 mm", "--radius", "2 mm",
                                          "--quantity", "outward")
            self.assertEqual(code, 0, err)
            self.assertEqual(lines[2], "1e-06,nan,0,0,0")  # outward from X: the intact points have not moved


if __name__ == "__main__":
    unittest.main()
