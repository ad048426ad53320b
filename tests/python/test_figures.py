"""The figures of analyze, report, compare --resolution and validate (tidalcrust.figures), checked
without pixels: the artists on each figure's Axes carry the data the C++ program wrote (counts
of failed springs and cracks, the subsatellite point, axis labels with units, the tracks)."""
import json
import subprocess
import sys
import unittest
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import cartopy.crs as ccrs  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from small_run import MOON_WORKFLOW, make_small_run, scratch  # noqa: E402

import tidalcrust  # noqa: E402
from tidalcrust import figures  # noqa: E402


def by_gid(artists, gid):
    found = [a for a in artists if a.get_gid() == gid]
    if len(found) != 1:
        raise AssertionError(f"{len(found)} artists with gid {gid}")
    return found[0]


class AnalysisFigures(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = scratch()
        cls.encounter = make_small_run(cls.tmp.name)
        cls.analysis = cls.encounter / "analysis"
        cls.summary = json.loads((cls.analysis / "summary.json").read_text())
        cls.data = json.loads((cls.analysis / "figure_data.json").read_text())
        cls.cracks = json.loads((cls.analysis / "cracks.json").read_text())
        cls.failed = set(cls.summary["failed_springs"]["spring"])

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def tearDown(self):
        plt.close("all")

    def test_analyze_drew_every_figure_as_png_and_svg(self):
        names = self.data["figures"]
        self.assertEqual(set(names), set(figures.ANALYSIS_FIGURES))
        self.assertEqual(self.summary["figures"], [f"{n}.{e}" for n in names for e in ("png", "svg")])
        for name in names:
            self.assertEqual((self.analysis / f"{name}.png").read_bytes()[:8], b"\x89PNG\r\n\x1a\n")
            self.assertIn(b"</svg>", (self.analysis / f"{name}.svg").read_bytes())

    def test_fracture_map_draws_every_failed_spring_and_the_subsatellite_ring(self):
        self.assertGreater(len(self.failed), 0)
        fig = figures.fracture_map(self.encounter)
        self.assertEqual(len(fig.axes), 3)
        self.assertIn(self.data["titles"]["fracture_map"], fig._suptitle.get_text())
        self.assertIn("failed shell springs", fig._suptitle.get_text())
        self.assertIn("dt = ", fig._suptitle.get_text())  # the time step in the title
        mollweide, near, far = fig.axes
        self.assertIsInstance(mollweide.projection, ccrs.Mollweide)
        cracks = by_gid(mollweide.collections, "cracks")
        self.assertEqual(set(cracks.springs), self.failed)  # the global map shows every bar
        self.assertGreaterEqual(len(cracks.get_segments()), len(self.failed))
        angle = dict(zip(self.summary["failed_springs"]["spring"],
                         self.summary["failed_springs"]["angle_from_subsatellite_deg"]))
        shown_near, shown_far = set(by_gid(near.collections, "cracks").springs), set(by_gid(far.collections, "cracks").springs)
        self.assertEqual(shown_near | shown_far, self.failed)
        for spring, a in angle.items():  # a bar well inside a hemisphere is drawn on its view
            if a < 80:
                self.assertIn(spring, shown_near)
            if a > 100:
                self.assertIn(spring, shown_far)
                self.assertNotIn(spring, shown_near)
        # The ring at longitude 90, latitude 0: the centre of the orthographic view.
        for ax, expected in ((near, (0.0, 0.0)), (mollweide, None)):
            ring = by_gid(ax.lines, "subsatellite")
            np.testing.assert_array_equal(ring.get_xydata(), [[90.0, 0.0]])
            xy = ax.transData.inverted().transform(ring.get_transform().transform([[90.0, 0.0]]))[0]
            if expected is None:
                expected = ax.projection.transform_point(90.0, 0.0, ccrs.PlateCarree(globe=figures.UNIT_GLOBE))
            np.testing.assert_allclose(xy, expected, atol=1e-9)

    def test_fracture_map_into_a_users_axes_with_a_mosaic(self):
        fig = plt.figure()
        ax = fig.add_subplot(1, 1, 1, projection=figures.projection("orthographic"))
        mosaic = np.linspace(0, 1, 36 * 18).reshape(18, 36)
        self.assertIs(figures.fracture_map(self.encounter, "orthographic", ax=ax, mosaic=mosaic, linewidth=3), fig)
        self.assertEqual(len(ax.images), 1)
        self.assertEqual(by_gid(ax.collections, "cracks").get_linewidths()[0], 3)
        with self.assertRaisesRegex(ValueError, "view 'sideways'"):
            figures.fracture_map(self.encounter, "sideways")

    def test_fracture_map_shades_a_crust_that_varies_under_the_cracks(self):
        # The small run's crust is uniform: nothing is drawn for it (cracks.json's crust lists are empty).
        self.assertEqual(self.cracks["crust"]["strength"]["factor"], [])
        fig = figures.fracture_map(self.encounter, "mollweide")
        self.assertEqual([c for c in fig.axes[0].collections if (c.get_gid() or "").startswith("crust_")], [])
        # A strength field (docs/crust.md) is one scatter of its points, coloured by the factor, under the cracks.
        varied = dict(self.cracks, crust={"thickness": {"lon": [], "lat": [], "factor": []},
                                          "strength": {"lon": [0.0, 90.0, 180.0], "lat": [0.0, 10.0, -10.0],
                                                       "factor": [0.5, 1.0, 1.5]}})
        fig = plt.figure()
        ax = fig.add_subplot(1, 1, 1, projection=figures.projection("mollweide"))
        figures.encounter._map_axes(ax, "mollweide", varied)
        shade = by_gid(ax.collections, "crust_strength")
        np.testing.assert_array_equal(shade.get_array(), [0.5, 1.5])  # the points of factor 1 are the plain surface
        self.assertLess(shade.get_zorder(), by_gid(ax.collections, "cracks").get_zorder())

    def test_crack_geometry_draws_the_fitted_arcs_and_the_rose(self):
        fig = figures.crack_geometry(self.encounter)
        g = self.summary["crack_geometry"]
        map_ax, rose_ax = fig.axes[:2]
        self.assertEqual(set(by_gid(map_ax.collections, "cracks").springs), self.failed)
        poles = [c for c in map_ax.collections if c.get_gid() == "poles"]
        self.assertEqual(len(poles[0].get_offsets()) if poles else 0, len(g["arcs"]))
        self.assertEqual(len(self.data["crack_geometry"]["circles"]), len(g["arcs"]))
        petals = [p for p in rose_ax.patches if p.get_gid() == "rose"] or rose_ax.containers[0].patches
        self.assertEqual(len(petals), 2 * len(g["rose"]["histogram"]))  # each bin at a and a + 180
        counts = np.asarray(g["rose"]["histogram"], float)
        heights = np.array([p.get_height() for p in petals[:len(counts)]])
        np.testing.assert_allclose(heights, np.sqrt(counts / counts.max()))  # equal-area petals
        self.assertIn("concentricity", fig._suptitle.get_text())

    def test_hemisphere_panels_are_the_snapshots_and_the_end(self):
        fig = figures.hemisphere(self.encounter)
        panels = self.data["hemisphere"]["panels"]
        self.assertEqual(len(fig.axes), len(panels))
        self.assertGreaterEqual(len(panels), 2)
        last = fig.axes[-1]
        self.assertEqual(last.get_title(), panels[-1]["label"])
        self.assertIn("t_grav", last.get_title())
        self.assertIn(f"{self.summary['failures']['count']} failed", [t.get_text() for t in last.texts])
        faces = len(self.data["hemisphere"]["faces"])
        shown = len(by_gid(last.collections, "faces").get_paths())
        self.assertTrue(0.35 * faces < shown < 0.65 * faces, (shown, faces))  # the near hemisphere
        bars = len(by_gid(last.collections, "cracks").get_segments())
        self.assertGreater(bars, 0)
        self.assertLess(bars, len(panels[-1]["crack_bars"]))

    def test_orbit_draws_the_simulated_track(self):
        fig = figures.orbit(self.encounter)
        ax = fig.axes[0]
        o = self.data["orbit"]
        self.assertTrue(o["simulated"])
        np.testing.assert_array_equal(by_gid(ax.lines, "track").get_xydata(), o["track"])
        self.assertEqual(len(by_gid(ax.lines, "ticks").get_xdata()), len(o["ticks"]))
        self.assertEqual(by_gid(ax.patches, "body").get_radius(), 1.0)
        np.testing.assert_array_equal(by_gid(ax.lines, "stored").get_xydata()[0], o["stored_position"])
        self.assertEqual(len([p for p in ax.patches if p.get_gid() == "snapshot"]), len(o["snapshots"]))
        self.assertEqual((ax.get_xlabel(), ax.get_ylabel()), ("x [R]", "y [R]"))
        # The pericenter lies on +y (the subsatellite direction): the track's closest point.
        track = np.asarray(o["track"])
        closest = track[np.argmin(np.hypot(track[:, 0], track[:, 1]))]
        self.assertGreater(closest[1], 0.9 * np.hypot(*closest))

    def test_failures_end_at_the_failed_count(self):
        fig = figures.failures(self.encounter)
        ax = fig.axes[0]
        line = by_gid(ax.lines, "failures")
        self.assertEqual(line.get_ydata()[-1], self.summary["failures"]["count"])
        self.assertEqual(ax.get_xlabel(), "t \u2212 t_peri [t_grav]")
        self.assertEqual(ax.get_ylabel(), "failed shell springs")

    def test_conservation_panels(self):
        fig = figures.conservation(self.encounter)
        self.assertEqual(len(fig.axes), 3)
        energy = by_gid(fig.axes[0].lines, "energy").get_ydata()
        self.assertEqual(energy[0], 0.0)
        self.assertLess(np.max(np.abs(energy)), 1e-2)
        self.assertEqual(len(energy), self.summary["conservation"]["samples"])
        self.assertIn("3/5 GM\u00b2/R", fig.axes[0].get_ylabel())
        self.assertIn("\u221a(GM/R)", fig.axes[1].get_ylabel())

    def test_body_shape_and_axis_ratios_are_the_summarys(self):
        fig = figures.body_shape(self.encounter)
        panels = self.data["body_shape"]["panels"]
        self.assertEqual(len(fig.axes), len(panels))
        self.assertEqual(len(by_gid(fig.axes[-1].collections, "springs").get_segments()), len(panels[-1]["springs"]))
        fig = figures.axis_ratios(self.encounter)
        ratios = self.summary["principal_axis_ratios"]
        np.testing.assert_array_equal(by_gid(fig.axes[0].lines, "b_over_a").get_ydata(),
                                      [r["b_over_a"] for r in ratios])
        np.testing.assert_array_equal(by_gid(fig.axes[0].lines, "c_over_a").get_xdata(),
                                      [r["time_from_pericenter"] for r in ratios])

    def test_fracture_map_row_has_one_map_per_panel(self):
        spec = {"kind": "fracture_map_row", "title": "S: fracture maps by shell level",
                "panels": [{"title": "level 1", "cracks": self.cracks}, {"title": "level 2", "cracks": self.cracks}]}
        fig = figures.fracture_map_row(spec)
        self.assertEqual([ax.get_title() for ax in fig.axes], ["level 1", "level 2"])
        for ax in fig.axes:
            self.assertEqual(set(by_gid(ax.collections, "cracks").springs), self.failed)

    def test_svg_output_is_deterministic(self):
        out = Path(self.tmp.name)
        figures.save(figures.failures(self.encounter), out / "a")
        figures.save(figures.failures(self.encounter), out / "b")
        self.assertEqual((out / "a.svg").read_bytes(), (out / "b.svg").read_bytes())

    def test_command_line_errors_are_one_line_naming_the_file(self):
        done = subprocess.run([sys.executable, "-m", "tidalcrust.figures", "analysis", self.tmp.name],
                              capture_output=True, text=True)
        self.assertEqual(done.returncode, 2, done.stderr)
        self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
        self.assertIn(str(Path(self.tmp.name) / "figure_data.json"), done.stderr)
        bad = Path(self.tmp.name) / "bad"
        bad.mkdir()
        (bad / "figure_data.json").write_text('{"format": "tidalcrust-figure-data", "version": 1, '
                                              '"figures": {"x": {"kind": "pie"}}}')
        done = subprocess.run([sys.executable, "-m", "tidalcrust.figures", "report", str(bad)],
                              capture_output=True, text=True)
        self.assertEqual(done.returncode, 2, done.stderr)
        self.assertIn("figure 'x' of unknown kind 'pie'", done.stderr)


class MoonFigures(unittest.TestCase):
    """A workflow with a [moon] (docs/moon.md, "Output in SI"): maps in planetocentric longitude (0 at
    the subsatellite point) with a km scale bar, time axes in hours beside t_grav, a km axis on the
    orbit."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = scratch()
        cls.encounter = make_small_run(cls.tmp.name, MOON_WORKFLOW)
        cls.analysis = cls.encounter / "analysis"
        cls.summary = json.loads((cls.analysis / "summary.json").read_text())
        cls.data = json.loads((cls.analysis / "figure_data.json").read_text())

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def tearDown(self):
        plt.close("all")

    def test_summary_is_in_si_beside_the_model_units(self):
        si = self.summary["si"]
        self.assertEqual(si["moon"]["radius_km"], 1000.0)
        self.assertAlmostEqual(si["encounter"]["pericenter_km"], 1200.0, places=9)
        self.assertAlmostEqual(si["failures"]["total_crack_length_km"],
                               1000.0 * self.summary["failures"]["total_crack_length"], places=6)

    def test_fracture_map_is_planetocentric_with_a_km_scale(self):
        frame = figures.map_frame(self.encounter)
        self.assertEqual(frame["frame"], "planetocentric")
        self.assertEqual(frame["subsatellite"], [0.0, 0])
        fig = figures.fracture_map(self.encounter)
        mollweide, near, far = fig.axes
        self.assertIn("planetocentric", by_gid(fig.texts, "note").get_text())
        self.assertIn(" km", fig._suptitle.get_text())
        # The ring at planetocentric (0, 0): the centre of the near hemisphere.
        ring = by_gid(near.lines, "subsatellite")
        xy = near.transData.inverted().transform(ring.get_transform().transform(ring.get_xydata()))[0]
        np.testing.assert_allclose(xy, (0.0, 0.0), atol=1e-9)
        # Every failed spring's midpoint at its planetocentric longitude (summary.json's si) on the map.
        cracks = by_gid(mollweide.collections, "cracks")
        failed = self.summary["failed_springs"]
        self.assertEqual(set(cracks.springs), set(failed["spring"]))
        geodetic = ccrs.Geodetic(globe=figures.UNIT_GLOBE)
        for spring, lon, lat in list(zip(failed["spring"], self.summary["si"]["failed_springs"]["planetocentric_longitude_deg"],
                                         failed["latitude_deg"]))[:20]:
            point = mollweide.projection.transform_point(lon, lat, geodetic)
            vertices = np.concatenate([seg for seg, s in zip(cracks.get_segments(), cracks.springs) if s == spring])
            self.assertLess(np.min(np.hypot(*(vertices - point).T)), 1e-6, spring)
        # A scale bar on every map: its length the projected length of scale_bar length_R along the equator.
        bar = frame["scale_bar"]
        self.assertEqual(bar["label"], "500 km")
        for ax in fig.axes:
            line = by_gid(ax.lines, "scale_bar")
            lon0 = ax.projection.proj4_params.get("lon_0", 0.0)
            ends = ax.projection.transform_points(geodetic, np.array([lon0 - 1e-3, lon0 + 1e-3]), np.zeros(2))
            per_radian = np.hypot(*(ends[1] - ends[0])[:2]) / np.radians(2e-3)
            self.assertAlmostEqual(np.ptp(line.get_xdata()) / (per_radian * bar["length_R"]), 1.0, places=3)
            self.assertEqual(by_gid(ax.texts, "scale_bar_label").get_text(), "500 km")

    def test_time_axes_are_in_hours_beside_t_grav(self):
        per_t_grav = self.data["time_axis"]["per_t_grav"]
        self.assertAlmostEqual(per_t_grav, self.summary["si"]["moon"]["t_grav_s"] / 3600)
        fig = figures.failures(self.encounter)
        ax = fig.axes[0]
        self.assertEqual(ax.get_xlabel(), "t \u2212 t_peri [h]")
        np.testing.assert_allclose(by_gid(ax.lines, "failures").get_xdata(),
                                   np.asarray(self.data["failures"]["time_from_pericenter"]) * per_t_grav)
        self.assertEqual([c.get_gid() for c in ax.child_axes], ["t_grav_axis"])
        fig = figures.axis_ratios(self.encounter)
        np.testing.assert_allclose(by_gid(fig.axes[0].lines, "b_over_a").get_xdata(),
                                   [r["time_from_pericenter_h"] for r in self.summary["si"]["principal_axis_ratios"]])
        fig = figures.conservation(self.encounter)
        self.assertEqual(fig.axes[-1].get_xlabel(), "t \u2212 t_peri [h]")
        fig = figures.orbit(self.encounter)
        self.assertIn("km_axis", [c.get_gid() for c in fig.axes[0].child_axes])

    def test_every_figure_is_drawn(self):
        for name in self.data["figures"]:
            self.assertTrue((self.analysis / f"{name}.png").is_file(), name)


class SpecFigures(unittest.TestCase):
    """report, compare --resolution and validate: figures from one figure object each."""

    def tearDown(self):
        plt.close("all")

    def test_phase_diagram(self):
        spec = {"kind": "phase_diagram", "title": "w: failed fraction\n2 of 3 encounters finished",
                "x_label": "pericenter q [R]", "y_label": "pericenter speed V_q [\u221a(GM/R)]",
                "x_range": [1.0, 3.0], "y_range": [1.0, 2.0], "crack_probability": False,
                "colour_label": "failed fraction", "colour_top": 0.2, "boundary_label": "crack/no-crack boundary",
                "points": [{"encounter": "a", "q": 1.5, "v_q": 1.5, "finished": True, "cracked": True, "value": 0.2},
                           {"encounter": "b", "q": 2.5, "v_q": 1.5, "finished": True, "cracked": False, "value": 0.0},
                           {"encounter": "c", "q": 2.0, "v_q": 1.8, "finished": False, "cracked": False,
                            "value": None}],
                "boundary": [[[2.0, 1.4], [2.0, 1.6]]],
                "eq5": {"label": "eq. 5: strain = \u03b5_S", "q": [1.0, 3.0], "v_q": [1.9, 1.1]}}
        ax = figures.phase_diagram(spec).axes[0]
        self.assertEqual(len(by_gid(ax.collections, "cracked").get_offsets()), 1)
        self.assertEqual(len(by_gid(ax.collections, "intact").get_offsets()), 1)
        self.assertEqual(len(by_gid(ax.collections, "unfinished").get_offsets()), 1)
        self.assertEqual(len(by_gid(ax.collections, "boundary").get_segments()), 1)
        np.testing.assert_array_equal(by_gid(ax.lines, "eq5").get_ydata(), [1.9, 1.1])
        self.assertEqual(ax.get_xlim(), (1.0, 3.0))
        self.assertEqual(ax.get_xlabel(), "pericenter q [R]")

    def test_signal_and_tidal_strain_plots(self):
        spec = {"kind": "signal", "title": "Breathing", "x_label": "t [t_grav]", "y_label": "mean radius change [R]",
                "time": [0.0, 0.5, 1.0], "signal": [0.0, 1.0, 0.0],
                "marks": [{"time": 0.4, "label": "Lamb period", "measured": False},
                          {"time": 0.5, "label": "measured", "measured": True}]}
        ax = figures.signal_plot(spec).axes[0]
        np.testing.assert_array_equal(by_gid(ax.lines, "signal").get_ydata(), [0.0, 1.0, 0.0])
        self.assertEqual(by_gid(ax.lines, "measured").get_xdata()[0], 0.5)
        self.assertEqual(by_gid(ax.lines, "theory").get_xdata()[0], 0.4)
        self.assertEqual(sorted(t.get_text() for t in ax.texts), ["Lamb period", "measured"])
        spec = {"kind": "tidal_strain", "title": "tide", "x_label": "gamma [deg]", "y_label": "strain",
                "theory": {"gamma_deg": [0, 90], "meridional": [1.0, -0.5], "azimuthal": [0.2, 0.1]},
                "bands": [{"gamma_deg": 5.0, "meridional": 0.9, "azimuthal": 0.25}]}
        ax = figures.tidal_strain_plot(spec).axes[0]
        np.testing.assert_array_equal(by_gid(ax.lines, "measured_meridional").get_ydata(), [0.9])
        np.testing.assert_array_equal(by_gid(ax.lines, "theory_azimuthal").get_ydata(), [0.2, 0.1])


if __name__ == "__main__":
    unittest.main()
