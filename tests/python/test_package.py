"""The Python package against the files of a run it did not write (docs/python.md): values
compared with h5py's direct reads, exact counts against summary.json, clear errors."""
import json
import os
import sys
import unittest
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from small_run import make_small_run, scratch  # noqa: E402

import tidalcrust  # noqa: E402
from tidalcrust.cracks import _split_at_antimeridian  # noqa: E402


class SmallRun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = scratch()
        cls.encounter = make_small_run(cls.tmp.name)
        cls.ds = tidalcrust.open(cls.encounter)
        cls.summary = json.loads((cls.encounter / "analysis" / "summary.json").read_text())

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_files_are_the_snapshots_then_the_encounter(self):
        files = list(self.ds.file.values)
        self.assertEqual(files[-1], "encounter.h5")
        self.assertGreaterEqual(len(files), 3)
        self.assertTrue(all(f.startswith("encounter.snap-") for f in files[:-1]))
        self.assertTrue(np.all(np.diff(self.ds.step.values) > 0))

    def test_every_file_reads_as_h5py_reads_it(self):
        for k, name in enumerate(self.ds.file.values):
            with h5py.File(self.encounter / name, "r") as h:
                np.testing.assert_array_equal(self.ds.position[k].values, h["particles/body/position/value"][0])
                np.testing.assert_array_equal(self.ds.velocity[k].values, h["particles/body/velocity/value"][0])
                np.testing.assert_array_equal(self.ds.rest_length[k].values, h["checkpoint/springs/rest_length"][()])
                np.testing.assert_array_equal(self.ds.failed[k].values, h["checkpoint/springs/failed"][()] == 1)
                self.assertEqual(float(self.ds.time[k]), h["checkpoint"].attrs["time"])
                self.assertEqual(int(self.ds.step[k]), h["checkpoint"].attrs["step"])
        with h5py.File(self.encounter / "encounter.h5", "r") as h:
            np.testing.assert_array_equal(self.ds.spring_particles.values, h["connectivity/springs"][()])
            np.testing.assert_array_equal(self.ds.mass.values, h["particles/body/mass"][()])
            for key in h["checkpoint/failures"]:
                np.testing.assert_array_equal(self.ds[f"failure_{key}"].values, h["checkpoint/failures"][key][()])
            for key in h["checkpoint/timeseries"]:
                name = "sample_time" if key == "time" else f"ts_{key}"
                np.testing.assert_array_equal(self.ds[name].values, h["checkpoint/timeseries"][key][()])
            # Units are not converted: the file says "nm", the Dataset says R, the numbers are equal.
            self.assertEqual(h["particles/body/position/value"].attrs["unit"], b"nm" if isinstance(
                h["particles/body/position/value"].attrs["unit"], bytes) else "nm")
        self.assertEqual(self.ds.position.attrs["units"], "R")
        self.assertIn("G = M = R = 1", self.ds.attrs["units"])

    def test_strain_is_length_over_rest_length_minus_one(self):
        k, s = -1, 17
        i, j = self.ds.spring_particles.values[s]
        length = np.linalg.norm(self.ds.position[k, i].values - self.ds.position[k, j].values)
        rest = float(self.ds.rest_length[k, s])
        self.assertAlmostEqual(float(self.ds.strain[k, s]), (length - rest) / rest, places=14)

    def test_failed_springs_are_summary_counts(self):
        count = self.summary["failures"]["count"]
        self.assertGreater(count, 0)
        self.assertEqual(int(self.ds.failed[-1].sum()), count)
        self.assertEqual(self.ds.sizes["failure"], count)
        self.assertEqual(int(np.isfinite(self.ds.failed_at.values).sum()), count)
        failed = np.flatnonzero(self.ds.failed[-1].values)
        self.assertEqual(list(failed), self.summary["failed_springs"]["spring"])
        np.testing.assert_array_equal(self.ds.failed_at.values[self.ds.failure_spring.values], self.ds.failure_time.values)
        self.assertEqual(int(self.ds.ts_failed.values[-1]), count)

    def test_one_checkpoint_file_is_one_time(self):
        one = tidalcrust.open(self.encounter / "encounter.h5")
        self.assertEqual(one.sizes["time"], 1)
        np.testing.assert_array_equal(one.position[0].values, self.ds.position[-1].values)

    def test_cracks_are_the_analysis_clusters(self):
        cracks = tidalcrust.read_cracks(self.encounter)
        failures = self.summary["failures"]
        self.assertEqual(cracks["crack_count"], failures["clusters"])
        self.assertEqual(cracks["state_hash"], self.summary["state_hash"])
        springs = sorted(s for c in cracks["cracks"] for s in c["springs"])
        self.assertEqual(springs, self.summary["failed_springs"]["spring"])
        self.assertAlmostEqual(sum(c["length"] for c in cracks["cracks"]), failures["total_crack_length"], places=10)
        self.assertEqual([c["length"] for c in cracks["cracks"]], [c["length"] for c in self.summary["clusters"]])
        for c in cracks["cracks"]:
            self.assertEqual(len(c["polylines"]), len(c["springs"]))
            for line in c["polylines"]:
                self.assertEqual(len(line), 3)  # centroid, midpoint, centroid: a closed shell
                for lon, lat in line:
                    self.assertTrue(-180 < lon <= 180 and -90 <= lat <= 90)

    def test_geojson_and_shapefile_open_in_geopandas_with_the_body_crs(self):
        import geopandas as gpd
        out = Path(self.tmp.name)
        expected = self.summary["failures"]["clusters"]
        tethys = gpd.read_file(tidalcrust.write_geojson(self.encounter, out / "t.geojson", body="Tethys"))
        self.assertEqual(len(tethys), expected)
        self.assertEqual(tethys.crs.name, "Tethys (2015) - Sphere / Ocentric")
        self.assertEqual(tethys.crs.ellipsoid.semi_major_metre, 531000.0)
        np.testing.assert_allclose(tethys["length_km"], tethys["length"] * 531.0)
        self.assertEqual(sorted(tethys["springs"]), sorted(c["springs"] for c in self.summary["clusters"]))
        unit = gpd.read_file(tidalcrust.write_geojson(self.encounter, out / "u.geojson"))
        self.assertEqual(len(unit), expected)
        self.assertEqual(unit.crs.ellipsoid.semi_major_metre, 1.0)  # not WGS 84
        shp = gpd.read_file(tidalcrust.write_shapefile(self.encounter, out / "shp" / "cracks.shp", body="Tethys"))
        self.assertEqual(len(shp), expected)
        self.assertTrue((out / "shp" / "cracks.prj").is_file())
        self.assertEqual(shp.crs.ellipsoid.semi_major_metre, 531000.0)

    def test_maps_return_figures_with_every_crack(self):
        import matplotlib.figure
        for view in ("equirectangular", "mollweide", "orthographic", "antipode"):
            fig = tidalcrust.fracture_map(self.encounter, view, title=f"{view} map")
            self.assertIsInstance(fig, matplotlib.figure.Figure)
            self.assertEqual(fig.axes[0].get_title(), f"{view} map")
            self.assertTrue(any(c.get_gid() == "cracks" for c in fig.axes[0].collections))
        fig = tidalcrust.failure_history(self.ds)
        line = fig.axes[0].lines[0]
        self.assertEqual(int(line.get_ydata()[-1]), self.summary["failures"]["count"])
        fig = tidalcrust.energy_budget(self.ds)
        error = fig.axes[0].lines[0].get_ydata()
        self.assertEqual(error[0], 0.0)
        self.assertLess(np.nanmax(np.abs(error)), 1e-2)
        with self.assertRaisesRegex(ValueError, "view 'polar'"):
            tidalcrust.fracture_map(self.encounter, "polar")


class BadInput(unittest.TestCase):
    def setUp(self):
        self.tmp = scratch()
        self.dir = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def assert_error(self, path, pattern, opener=tidalcrust.open):
        with self.assertRaises(tidalcrust.TidalcrustError) as caught:
            opener(path)
        self.assertIn(str(path), str(caught.exception))
        self.assertRegex(str(caught.exception), pattern)
        self.assertIsInstance(caught.exception, ValueError)

    def test_missing_path(self):
        self.assert_error(self.dir / "nowhere.h5", "no such checkpoint file")

    def test_not_hdf5(self):
        (self.dir / "text.h5").write_text("hello\n")
        self.assert_error(self.dir / "text.h5", "not an HDF5 file")

    def test_hdf5_not_tidalcrust(self):
        with h5py.File(self.dir / "other.h5", "w") as h:
            h["x"] = np.arange(3)
        self.assert_error(self.dir / "other.h5", "not a tidalcrust checkpoint")

    def test_newer_format(self):
        with h5py.File(self.dir / "new.h5", "w") as h:
            h.create_group("checkpoint").attrs["format_version"] = np.int64(max(tidalcrust.checkpoint.READABLE_FORMATS) + 1)
        self.assert_error(self.dir / "new.h5", f"format {max(tidalcrust.checkpoint.READABLE_FORMATS) + 1}")

    def test_folder_without_encounter(self):
        self.assert_error(self.dir, "no encounter.h5")

    def test_cracks(self):
        self.assert_error(self.dir, "no cracks.json", tidalcrust.read_cracks)
        (self.dir / "cracks.json").write_text("{")
        self.assert_error(self.dir / "cracks.json", "not a readable JSON file", tidalcrust.read_cracks)
        (self.dir / "cracks.json").write_text('{"format": "other"}')
        self.assert_error(self.dir / "cracks.json", "not a tidalcrust cracks.json", tidalcrust.read_cracks)

    def test_unknown_body(self):
        with self.assertRaisesRegex(tidalcrust.CracksError, "Vulcan"):
            tidalcrust.body_crs("Vulcan")
        self.assertEqual(tidalcrust.body_crs("tethys").to_authority(), ("IAU_2015", "60300"))


class Antimeridian(unittest.TestCase):
    def test_a_bar_across_180_is_cut_there(self):
        pieces = _split_at_antimeridian([[179.0, 0.0], [-179.0, 2.0], [-178.0, 2.0]])
        self.assertEqual(pieces, [[(179.0, 0.0), (180.0, 1.0)], [(-180.0, 1.0), (-179.0, 2.0), (-178.0, 2.0)]])

    def test_a_bar_away_from_it_is_kept(self):
        self.assertEqual(_split_at_antimeridian([[10.0, 1.0], [12.0, 2.0]]), [[(10.0, 1.0), (12.0, 2.0)]])


if __name__ == "__main__":
    unittest.main()
