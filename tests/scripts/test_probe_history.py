"""scripts/probe_history.py on a synthetic run with known displacements: particles followed by id
(reordered and one removed between snapshots), averaged over the nearest body's points within one
grid cell; outside a hybrid's zone the nearest far-field node of zlib-compressed and ascii VTU
files as deal.II writes them, and where a growing zone took the node, the points born there by
their undeformed positions. Every value is exact to round-off (1e-15 m; 1e-12 m from float32 VTU
values)."""
import base64
import contextlib
import io
import pathlib
import struct
import sys
import tempfile
import unittest
import zlib

import h5py
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import probe_history  # noqa: E402

CELL = 1e-3  # grid cell, m


def write_snapshot(path, time, ids, body, position, reference=None):
    with h5py.File(path, "w") as f:
        f.attrs["time"] = time
        f["id"], f["body"], f["position"] = ids, body, position
        if reference is not None:
            f["reference_position"] = reference


def compressed(array):
    raw = np.ascontiguousarray(array).tobytes()
    block = zlib.compress(raw)
    header = struct.pack("<4I", 1, len(raw), len(raw), len(block))
    return base64.b64encode(header).decode() + base64.b64encode(block).decode()


def write_vtu(path, points, displacement, ascii=False):
    def array(name, data, components):
        attrs = f'type="Float32"{name} NumberOfComponents="{components}"'
        if ascii:
            return f'<DataArray {attrs} format="ascii">{" ".join(map(str, data.ravel()))}</DataArray>\n'
        return f'<DataArray {attrs} format="binary">\n{compressed(data.astype(np.float32))}\n</DataArray>\n'

    compressor = "" if ascii else ' compressor="vtkZLibDataCompressor"'
    path.write_text(
        f'<?xml version="1.0" ?>\n<VTKFile type="UnstructuredGrid" version="0.1"{compressor} byte_order="LittleEndian">\n'
        f'<UnstructuredGrid>\n<Piece NumberOfPoints="{len(points)}" NumberOfCells="0">\n<Points>\n'
        + array("", points, 3)
        + "</Points>\n<PointData>\n"
        + array(' Name="displacement"', displacement, 3)
        + "</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n"
    )


def make_run(root, ascii=False):
    run = root / "run"
    (run / "snapshots").mkdir(parents=True)
    (run / "far_field").mkdir()
    (run / "scene.resolved.toml").write_text(
        "[far_field]\n[far_field.zone]\nlower = [0.0, 0.0]\nupper = [0.01, 0.01]\n[grid]\ncell_size = 0.001\n"
    )
    # Body 0: a row of points 0.5 mm apart along x at z = 0; body 1 the same row 0.3 mm below.
    # The probe at (2, 0, -0.25) mm is nearest to body 1's point at x = 2 mm, so body 1 is read:
    # its points within a cell, at x = 1.5, 2 and 2.5 mm (indices 3, 4, 5).
    xs = np.arange(0.0, 5e-3, 0.5e-3)
    pos0 = np.array([[x, 0.0, z] for z in (0.0, -0.3e-3) for x in xs])
    ids = np.arange(len(pos0)) + 100
    body = np.repeat([0, 1], len(xs))
    write_snapshot(run / "snapshots/particles_000000.h5", 0.0, ids, body, pos0)
    # At 1 us body 1's points move down by 1 um times their index and body 0's up by 7 um. The
    # file lists them in reverse order, and the point at x = 1.5 mm (index 3) has left the
    # model: the mean over indices 4 and 5 is -4.5 um.
    moved = pos0.copy()
    index = np.tile(np.arange(len(xs)), 2)
    moved[body == 1, 2] -= 1e-6 * index[body == 1]
    moved[body == 0, 2] += 7e-6
    keep = ids != 100 + len(xs) + 3
    write_snapshot(run / "snapshots/particles_000001.h5", 1e-6, ids[keep][::-1], body[keep][::-1], moved[keep][::-1])
    # Far field: three nodes, the nearest to (20, 0, -0.2) mm is the second.
    points = np.array([[15e-3, 0, 0], [19.5e-3, 0, -0.3e-3], [25e-3, 0, 0]])
    for k, (t, scale) in enumerate(((0.0, 0.0), (1e-6, 1.0))):
        u = scale * np.array([[0, 0, 1e-6], [0, 0, -3e-6], [0, 0, 5e-6]])
        write_vtu(run / f"far_field/far_field_{k}.vtu", points, u, ascii)
    (run / "far_field.pvd").write_text(
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1"><Collection>\n'
        '<DataSet timestep="0" file="far_field/far_field_0.vtu"/>\n'
        '<DataSet timestep="1e-06" file="far_field/far_field_1.vtu"/>\n</Collection></VTKFile>\n'
    )
    return run


def make_growing_run(root, references=True):
    """A hybrid whose zone grows over the probe's far-field node between 1 and 2 us: the node's
    cells leave the VTU at 2 us, and points born there carry their undeformed positions."""
    run = make_run(root)
    (run / "scene.resolved.toml").write_text(
        "[far_field]\n[far_field.zone]\nlower = [0.0, 0.0]\nupper = [0.01, 0.01]\n"
        "[far_field.zone.grow]\nlower = [0.0, 0.0]\nupper = [0.03, 0.03]\n[grid]\ncell_size = 0.001\n"
    )
    # At 2 us the far field keeps only the node at 25 mm; the zone's new points: body 1 at
    # X = 19.2, 19.5, 20, 21.5 mm (z = -0.3 mm) moved down by 1, 2, 3, 4 um, and body 0 at X = 20 mm,
    # z = 0, moved up by 9 um. The probe at (20, 0, -0.2) mm is nearest to body 1's point at
    # 20 mm: its points within a cell are the first three (21.5 mm is 1.5 mm away), mean -2 um.
    write_vtu(run / "far_field/far_field_2.vtu", np.array([[25e-3, 0, 0]]), np.array([[0, 0, 8e-6]]))
    pvd = (run / "far_field.pvd").read_text().replace(
        "</Collection>", '<DataSet timestep="2e-06" file="far_field/far_field_2.vtu"/>\n</Collection>')
    (run / "far_field.pvd").write_text(pvd)
    X = np.array([[19.2e-3, 0, -0.3e-3], [19.5e-3, 0, -0.3e-3], [20e-3, 0, -0.3e-3], [21.5e-3, 0, -0.3e-3], [20e-3, 0, 0.0]])
    x = X + np.array([[0, 0, -1e-6], [0, 0, -2e-6], [0, 0, -3e-6], [0, 0, -4e-6], [0, 0, 9e-6]])
    write_snapshot(run / "snapshots/particles_000002.h5", 2e-6, np.arange(5) + 500, np.array([1, 1, 1, 1, 0]), x,
                   X if references else None)
    return run


class ProbeHistory(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = pathlib.Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_particles_followed_by_id(self):
        run = make_run(self.root)
        rows, what = probe_history.history(run, np.array([2e-3, 0.0, -0.25e-3]), 2)
        self.assertIn("3 particles of body 1", what)
        self.assertEqual([t for t, _ in rows], [0.0, 1e-6])
        self.assertAlmostEqual(rows[0][1], 0.0, delta=1e-15)
        self.assertAlmostEqual(rows[1][1], -4.5e-6, delta=1e-15)

    def test_far_field_node_compressed_and_ascii(self):
        for ascii in (False, True):
            with self.subTest(ascii=ascii):
                run = make_run(self.root / ("a" if ascii else "b"), ascii)
                rows, what = probe_history.history(run, np.array([20e-3, 0.0, -0.2e-3]), 2)
                self.assertIn("far-field node at 0.0195", what)
                self.assertAlmostEqual(rows[0][1], 0.0, delta=1e-15)
                self.assertAlmostEqual(rows[1][1], -3e-6, delta=1e-12)  # float32 in the file

    def test_growing_zone_goes_on_with_the_points_that_took_the_node(self):
        run = make_growing_run(self.root)
        rows, what = probe_history.history(run, np.array([20e-3, 0.0, -0.2e-3]), 2)
        self.assertIn("far-field node at 0.0195", what)
        self.assertIn("from t = 2e-06 s, the zone grown over it) 3 points of body 1", what)
        self.assertEqual([t for t, _ in rows], [0.0, 1e-6, 2e-6])
        self.assertAlmostEqual(rows[1][1], -3e-6, delta=1e-12)  # the node, float32
        self.assertAlmostEqual(rows[2][1], -2e-6, delta=1e-15)  # the points, by their X

    def test_growing_zone_without_reference_positions_is_refused(self):
        run = make_growing_run(self.root, references=False)
        with self.assertRaisesRegex(ValueError, "no reference_position"):
            probe_history.history(run, np.array([20e-3, 0.0, -0.2e-3]), 2)

    def test_units_and_bad_point(self):
        self.assertAlmostEqual(probe_history.length("-15.2 mm"), -0.0152, delta=1e-15)
        self.assertAlmostEqual(probe_history.length("20um"), 2e-5, delta=1e-18)
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            self.assertEqual(probe_history.main([str(self.root), "--point", "0 mm,20 furlongs,0"]), 2)
        self.assertIn("'20 furlongs' is not a length", err.getvalue())


if __name__ == "__main__":
    unittest.main()
