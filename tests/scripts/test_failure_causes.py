"""scripts/failure_causes.py on a synthetic run: of a sheet's three points, one fails (damage 0.7,
a projectile point 0.1 mm away closing at 500 m/s) and one leaves the model (damage 0.1, nothing
within a cell) between the two snapshots; the third stays whole. Every value is checked exactly."""
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
import failure_causes  # noqa: E402


def write(path, time, ids, body, position, velocity, failed, damage, plastic):
    with h5py.File(path, "w") as f:
        f.attrs["time"] = time
        f["id"], f["body"], f["position"], f["velocity"] = ids, body, position, velocity
        f["failed"], f["damage"], f["plastic_strain"] = failed, damage, plastic
        f["pressure"] = -1e8 * np.ones(ids.size)
        f["volume_ratio"] = np.ones(ids.size)
        stress = np.zeros((ids.size, 6))  # xx xy xz yy yz zz
        stress[:, 0] = stress[:, 3] = stress[:, 5] = 1e8
        f["stress"] = stress


class FailureCauses(unittest.TestCase):
    def test_state_before_failing(self):
        with tempfile.TemporaryDirectory() as d:
            run = pathlib.Path(d)
            (run / "snapshots").mkdir()
            (run / "run.json").write_text(json.dumps({"bodies": ["projectile", "panel.rear"]}))
            ids = np.array([1, 10, 11, 12])
            body = np.array([0, 1, 1, 1])
            x = np.array([[0, 0, 1e-4], [0, 0, 0], [1e-3, 0, 0], [2e-3, 0, 0]], float)
            v = np.array([[0, 0, -500], [0, 0, 0], [0, 0, 0], [0, 0, 0]], float)
            write(run / "snapshots/particles_000000.h5", 0.0, ids, body, x, v, np.zeros(4),
                  np.array([0, 0.7, 0.1, 0]), np.array([0, 0.2, 0.01, 0]))
            keep = np.array([0, 1, 3])  # id 11 has left the model; id 10 has failed
            write(run / "snapshots/particles_000001.h5", 1e-6, ids[keep], body[keep], x[keep], v[keep],
                  np.array([0, 1.0, 0]), np.array([0, 1.0, 0]), np.array([0, 0.3, 0]))
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                sys.argv = ["failure_causes.py", str(run), "--body", "panel.rear", "--cell", "0.2 mm"]
                failure_causes.main()
            header, row = out.getvalue().strip().splitlines()
            values = dict(zip(header.split(","), row.split(",")))
            self.assertEqual(values["failed"], "2")
            self.assertEqual(values["damaged"], "0.500")
            self.assertEqual(values["plastic_strain"], "0.105")
            self.assertEqual(values["pressure"], "-1e+08")
            self.assertEqual(values["principal"], "1e+08")
            self.assertEqual(values["foreign"], "0.500")
            self.assertEqual(values["relative_speed"], "500")


if __name__ == "__main__":
    unittest.main()
