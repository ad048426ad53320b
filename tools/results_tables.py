#!/usr/bin/env python3
"""The tables of docs/results/, regenerated from tidalcrust's own outputs.

A table is the text of a page between two marker lines,

    <!-- results-quick:NAME begin -->        <!-- results-full:NAME begin -->
    ...                                      ...
    <!-- results-quick:NAME end -->          <!-- results-full:NAME end -->

and this script is the only writer of that text: each NAME is one function below that turns the
program's JSON (summary.json, `inspect --json`, `compare --json`, validate's validation.json,
report's sweep.json) into Markdown with a fixed number of digits, so the same bits give the same
text.

  quick  runs every workflow a quick body can produce (about 2 minutes of CPU, one thread, the
         portable gravity kernel, so any x86-64 CPU with FMA gives the same bits) into a fresh
         temporary folder and regenerates the `results-quick` tables.
  full   regenerates the `results-full` tables from runs already made into --runs DIR by the
         commands each table names (hours of CPU; they are not rerun here).
  bench  runs the benchmarks of the speed table (BENCH_RUNS) --repeat times each into
         --work DIR/bench (what `full --only speed-here --runs DIR` reads) and prints that table
         (`make bench`).

--write rewrites the pages in place. --check writes a temporary copy of the pages instead and
exits 1 naming each table that differs from the page and its first differing line (CTest
`results.quick_tables` runs `quick --check`); it then edits one number of the copy and makes sure
the comparison notices (so a check that could not fail fails). Exit 2: bad usage or a command of
the program failed; 77: skipped (a CPU without FMA, whose libm rounds differently).

Python 3 standard library only.
"""

import argparse
import difflib
import json
import os
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

MARKER = re.compile(r"^<!-- results-(quick|full):([A-Za-z0-9_.-]+) (begin|end) -->$")


class Failure(Exception):
    """A command of the program failed, or an input is missing: exit 2 with this line."""


# ---------------------------------------------------------------- numbers as text


def fixed(x, digits):
    if x is None:
        return "-"
    text = f"{x:.{digits}f}"
    return text[1:] if text.startswith("-") and float(text) == 0 else text  # never -0.00


def pct(x, digits=1):
    return "-" if x is None else fixed(100.0 * x, digits) + "%"


def sci(x, digits=2):
    """1.30e-7, not 1.30e-07."""
    if x is None:
        return "-"
    mantissa, exponent = f"{x:.{digits}e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def sig(x, digits=3):
    """digits significant digits, plain notation while it stays short."""
    if x is None:
        return "-"
    if x != 0 and not 1e-3 <= abs(x) < 1e5:
        return sci(x, digits - 1)
    text = f"{x:.{digits}g}"
    return text


def short(x):
    """A grid value as written in a workflow: 2.0, 1.84, 0.003."""
    if x is None:
        return "-"
    text = repr(float(x))
    return text if "e" not in text else sig(x)


def count(n):
    return "-" if n is None else f"{int(n):,}"


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return lines


# ---------------------------------------------------------------- the program and its outputs


class Program:
    """tidalcrust, run with one thread; its JSON outputs read once."""

    def __init__(self, exe, source, work):
        self.exe = str(exe)
        self.source = Path(source)
        self.work = Path(work)
        self.cache = {}

    def __call__(self, *args, capture=True):
        argv = [self.exe, *map(str, args)]
        done = subprocess.run(argv, cwd=self.source, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if done.returncode != 0:
            tail = "\n".join(done.stderr.strip().splitlines()[-5:])
            raise Failure(f"`{' '.join(argv)}` exited {done.returncode}:\n{tail}")
        return done.stdout

    def json_of(self, *args):
        key = args
        if key not in self.cache:
            self.cache[key] = json.loads(self(*args))
        return self.cache[key]

    def inspect(self, path):
        return self.json_of("inspect", path, "--json")

    def compare(self, a, b):
        return self.json_of("compare", a, b, "--json")

    def load_text(self, path):
        path = Path(path)
        if not path.is_file():
            raise Failure(f"{path}: missing (run the command its table names)")
        return path.read_text()

    def load(self, path):
        path = Path(path)
        if path not in self.cache:
            if not path.is_file():
                raise Failure(f"{path}: missing (run the command its table names)")
            self.cache[path] = json.loads(path.read_text())
        return self.cache[path]


def summary(p, folder):
    return p.load(Path(folder) / "analysis" / "summary.json")


def network_length(f):
    """The largest connected crack network's length (R) of a `failures` object: the key
    largest_network_length, or longest_crack in summaries written before issue 27."""
    return f["largest_network_length"] if "largest_network_length" in f else f["longest_crack"]


def failures_row(f):
    """The fracture statistics every encounter table shows, from a `failures` object."""
    return [
        count(f["count"]),
        pct(f["failed_area_fraction"]),
        fixed(f["total_crack_length"], 2) + " R",
        fixed(network_length(f), 2) + " R" if f["count"] else "-",
        count(f["clusters"]),
        pct(f["hemisphere_fraction"]) if f["count"] else "-",
        fixed(f["median_angle_from_subsatellite_deg"], 1) + " deg" if f["count"] else "-",
    ]


FAILURE_COLUMNS = ["failed shell springs", "failed area", "total crack length", "longest crack", "cracks (clusters)",
                   "on the pericenter hemisphere", "median angle from the subsatellite point"]


def measured_by(p, checkpoint):
    """Which code and kernel wrote a checkpoint: 'commit c5d9b8c26cb7, gravity kernel fast/generic'."""
    prov = p.inspect(checkpoint)["provenance"]
    kernel = prov.get("gravity_kernel", "")
    if not kernel or kernel.startswith("none"):  # a build: no gravity computed yet
        return f"commit {prov['git_commit']}"
    return f"commit {prov['git_commit']}, gravity kernel {kernel}"


# ---------------------------------------------------------------- the quick tables

QUICK = {}
FULL = {}


def quick_table(name):
    def register(f):
        QUICK[name] = f
        return f
    return register


def full_table(name):
    def register(f):
        FULL[name] = f
        return f
    return register


KERNEL = ["--gravity-kernel", "portable"]  # the same bits on every x86-64 CPU with FMA
# sweep-quick without each encounter's figures (its tables read summary.json; the figures took
# most of the time): the run and the command the table prints.
SWEEP_QUICK_SETTINGS = ["--set", "analysis.figures=false"]


def quick_runs(p):
    """Everything the quick tables read, in order; `run` is restart-driven, so a rerun reuses."""
    w, o = "workflows", p.work
    one = ["--threads", "1", "--quiet"]
    qb = o / "quick-balanced"
    p("run", f"{w}/quick-balanced.toml", "--out", qb, *KERNEL, *one)
    p("run", f"{w}/quick-balanced.toml", "--out", qb, "--dt-factor", "0.5", *KERNEL, *one)
    p("run", f"{w}/quick-balanced.toml", "--out", qb, "--dt-factor", "0.25", *KERNEL, *one)
    for name, setting in QUICK_RULE_VARIANTS:
        (qb / name).mkdir(exist_ok=True)
        if not (qb / name / "encounter.h5").is_file():
                p("encounter", "--from", qb / "body" / "relax.h5", "--out", qb / name / "encounter.h5", "--encounter",
              "strong", "--set", setting, "--threads", "1")
    p("run", f"{w}/quick.toml", "--out", o / "quick", *KERNEL, *one)
    p("validate", f"{w}/quick.toml", "--out", o / "quick", "--set", "gravity.kernel=portable", *one)
    p("run", f"{w}/sweep-quick.toml", "--out", o / "sweep-quick", *KERNEL, *SWEEP_QUICK_SETTINGS, *one)
    p("report", f"{w}/sweep-quick.toml", "--out", o / "sweep-quick", "--set", "gravity.kernel=portable")


QUICK_RULE_VARIANTS = [("tr2", "encounter.relaxation_crossings=1.0"),
                       ("tr4", "encounter.relaxation_crossings=0.5"),
                       ("paper-rule", "encounter.failure_rule=paper")]


@quick_table("demo")
def demo(p):
    qb = p.work / "quick-balanced"
    a, b = qb / "strong" / "encounter.h5", qb / "dt0.5" / "strong" / "encounter.h5"
    c = p.compare(a, b)
    rows = []
    for label, path, side in (("A", a, c["a"]), ("B: A at dt/2", b, c["b"])):
        rows.append([label, fixed(p.inspect(path)["dt"], 4), count(side["step"])] + failures_row(side["failures"]))
    lines = ["```",
             "tidalcrust run workflows/quick-balanced.toml --gravity-kernel portable",
             "tidalcrust run workflows/quick-balanced.toml --gravity-kernel portable --dt-factor 0.5",
             "tidalcrust compare checkpoints/quick-balanced/strong/encounter.h5 "
             "checkpoints/quick-balanced/dt0.5/strong/encounter.h5 --json",
             "```", ""]
    lines += table(["run", "dt (t_grav)", "steps"] + FAILURE_COLUMNS, rows)
    lines += ["", f"Failed in both runs: {c['common_failed']} of the {c['either_failed']} springs that failed in either "
              f"(Jaccard overlap {fixed(c['jaccard'], 3)}); Kolmogorov-Smirnov distance of the two distributions of the "
              f"angle from the subsatellite point {fixed(c['ks_distance_angle_from_subsatellite'], 3)}."]
    return lines


@quick_table("local-rule")
def local_rule(p):
    qb = p.work / "quick-balanced"
    base = qb / "strong" / "encounter.h5"
    settings = [("dt = 0.004 t_grav, t_r = 2 L_S / V_SP (the demo's A)", base),
                ("dt/2", qb / "dt0.5" / "strong" / "encounter.h5"),
                ("dt/4", qb / "dt0.25" / "strong" / "encounter.h5"),
                ("t_r/2", qb / "tr2" / "encounter.h5"),
                ("t_r/4", qb / "tr4" / "encounter.h5"),
                ("the paper's rule (one spring per t_fail), dt", qb / "paper-rule" / "encounter.h5")]
    rows = []
    for label, path in settings:
        c = p.compare(base, path)
        rows.append([label] + failures_row(c["b"]["failures"]) + [fixed(c["jaccard"], 3)])
    lines = ["```",
             "tidalcrust run workflows/quick-balanced.toml --gravity-kernel portable [--dt-factor 0.5 | 0.25]",
             "tidalcrust encounter --from checkpoints/quick-balanced/body/relax.h5 --out tr2/encounter.h5 "
             "--encounter strong --set encounter.relaxation_crossings=1.0",
             "    (tr4: relaxation_crossings=0.5; paper-rule: --set encounter.failure_rule=paper)",
             "tidalcrust compare checkpoints/quick-balanced/strong/encounter.h5 OTHER.h5 --json",
             "```", ""]
    lines += table(["setting"] + FAILURE_COLUMNS + ["Jaccard overlap with the first row"], rows)
    return lines


@quick_table("quick-paper")
def quick_paper(p):
    enc = p.work / "quick" / "strong"
    s = summary(p, enc)
    i = p.inspect(enc / "encounter.h5")
    con = s["conservation"]
    lines = ["```", "tidalcrust run workflows/quick.toml --gravity-kernel portable", "```", ""]
    lines += table(["encounter", "dt (t_grav)", "steps"] + FAILURE_COLUMNS +
                   ["largest momentum change", "largest relative angular momentum change"],
                   [[f"strong (M2 = {s['encounter']['perturber_mass']}, q = {s['encounter']['pericenter']}, "
                     f"V_q = {s['encounter']['pericenter_speed']})", fixed(i["dt"], 4), count(s["step"])]
                    + failures_row(s["failures"])
                    + [sci(con["max_momentum_change"], 1), sci(con["max_relative_angular_momentum_change"], 1)]])
    return lines


def relaxed_row(p, label, relax):
    r = p.inspect(relax)["record"]
    probe = f"{r['probe_failures']} at eps_S = {short(r['probe_failure_strain'])}"
    others = sorted(zip(r.get("probe_other_strains", []), r.get("probe_other_failures", [])), reverse=True)
    for eps, n in others:  # largest strain first, as the stored order is the configuration's
        probe += f", {int(n)} at {short(eps)}"
    return [label, sci(r["max_shell_strain"], 1), sci(r["internal_kinetic_energy"], 1),
            fixed(r["mean_shell_radius"], 4) + " R", probe, sci(r["probe_max_shell_strain"], 1)]


RELAXED_COLUMNS = ["body, crust support", "largest shell strain after relax", "internal kinetic energy (G M^2/R)",
                   "mean shell radius", "stability probe: failures (3 t_grav, gamma = 0.01)",
                   "largest shell strain in the probe"]


@quick_table("relaxed-quick")
def relaxed_quick(p):
    lines = ["```", "tidalcrust run workflows/quick.toml --gravity-kernel portable",
             "tidalcrust run workflows/quick-balanced.toml --gravity-kernel portable",
             "tidalcrust inspect checkpoints/{quick,quick-balanced}/body/relax.h5 --json", "```", ""]
    lines += table(RELAXED_COLUMNS, [relaxed_row(p, "quick, paper", p.work / "quick" / "body" / "relax.h5"),
                                     relaxed_row(p, "quick-balanced, balanced",
                                                 p.work / "quick-balanced" / "body" / "relax.h5")])
    return lines


def energy_rows(p, label, folders):
    """One row per time step: the largest and final energy error, what the body kept and lost."""
    rows, first = [], None
    for dt_label, folder in folders:
        s = summary(p, folder)
        r = p.inspect(Path(folder) / "encounter.h5")["record"]
        e, con = s["energy"], s["conservation"]
        ratio = "" if first is None else fixed(first / con["max_energy_error"], 2)
        first = con["max_energy_error"] if first is None else first
        rows.append([label, dt_label, sci(con["max_energy_error"]), ratio, sci(con["final_energy_error"], 1),
                     sci(e["deposited_in_body"]), sci(r["damping_dissipated"], 1), sci(r["failure_released"], 2),
                     sci(r["hinge_residual_work"], 1)])
    return rows


ENERGY_COLUMNS = ["run", "dt", "largest energy error", "ratio to the first row", "energy error at the end",
                  "left in the body", "damping", "failures", "hinge work"]


@quick_table("energy-quick")
def energy_quick(p):
    qb = p.work / "quick-balanced"
    lines = ["```", "tidalcrust run workflows/quick-balanced.toml --gravity-kernel portable [--dt-factor 0.5 | 0.25]",
             "```", ""]
    lines += table(ENERGY_COLUMNS, energy_rows(p, "quick-balanced strong", [
        ("0.004", qb / "strong"), ("0.002", qb / "dt0.5" / "strong"), ("0.001", qb / "dt0.25" / "strong")]))
    return lines


VALIDATE_ROWS = [
    ("breathing", "(a) breathing period (t_grav)", "Lamb 1882, E_I of eq. 15, nu = 1/4"),
    ("breathing-network", "", "Lamb, the measured network moduli"),
    ("love", "(b) Love number h2", "Takeuchi & Saito 1972, eq. 15"),
    ("love-network", "", "same, the measured network moduli"),
    ("love-layered", "", "layered sphere x the measured factors"),
    ("flexure", "(c) flexural rigidity (G M^2/R)", "eq. 23: k_e L_S / 2"),
    ("p-wave", "(d) P-wave time pole to pole (t_grav)", "eq. 16: path / V_IP"),
    ("p-wave-network", "", "path / V_P of the measured network moduli"),
    ("p-wave-layered", "", "layered eq. 15/16 x the measured factors"),
]


def comparison_cells(docs, key, cell):
    """One cell per validation.json for its comparison `key` ("" where absent), and the tolerance."""
    cells, tolerance = [], ""
    for _, d in docs:
        c = d["comparisons"].get(key)
        cells.append("" if c is None else cell(c))
        if c is not None:
            tolerance = pct(c["tolerance"], 0)
    return cells, tolerance


def validation_lines(p, columns):
    """One row per check of validation.json, one column per body: measured / theory = ratio."""
    docs = [(label, p.load(Path(folder) / "validate" / "validation.json")) for label, folder in columns]
    header = ["check", "theory"] + [f"{label}: measured / theory = ratio" for label, _ in docs] + ["tolerance"]
    rows = []
    def cell(c):
        digits = 4 if c["measured"] >= 0.1 else 3
        return f"{sig(c['measured'], digits)} / {sig(c['theory'], digits)} = {fixed(c['ratio'], 3)}"
    for key, check, theory in VALIDATE_ROWS:
        cells, tolerance = comparison_cells(docs, key, cell)
        rows.append([check, theory] + cells + [tolerance])
    extra = []
    for key, check, theory, field in (("breathing", "", "Lamb with self-gravity", "self_gravitating_ratio"),
                                      ("flexure", "", "the hinge lattice: k_e / 4", "lattice_ratio"),
                                      ("p-wave", "", "layered eq. 15/16", "layered_ratio")):
        cells = []
        for _, d in docs:
            v = d.get("details", {}).get(key, {}).get(field)
            cells.append("" if v is None else f"ratio {fixed(v, 3)}")
        extra.append((key, [check, theory] + cells + [""]))
    # each extra row right after its check's first row
    out = []
    for key_row, row in zip(VALIDATE_ROWS, rows):
        out.append(row)
        out += [r for k, r in extra if k == key_row[0]]
    lines = table(header, out)
    materials = [f"{label} E_I = {fixed(d['material']['youngs_modulus'], 3)} e_g, "
                 f"V_IP = {fixed(d['material']['p_wave_speed'], 3)}"
                 + (f", L_S = {fixed(d['material']['shell_spacing'], 4)} R" if d['material']['shell_spacing'] else "")
                 for label, d in docs]  # a body without a crust has no L_S
    lines += ["", "Material (eq. 15 on the relaxed interior): " + "; ".join(materials) + "."]
    measured = [(label, d["network_moduli"]) for label, d in docs if "youngs_factor" in d.get("network_moduli", {})]
    if measured:
        def iso(n, part):
            m = n[part]
            return m["relaxed"], m["affine"]
        rows = [["free / held interior nodes"] + [f"{n['network']['free_nodes']} / {n['network']['held_nodes']}"
                                                  for _, n in measured],
                ["geometric non-affine factor, bulk K / shear G"] + [
                    f"{fixed(n['bulk_factor'], 3)} / {fixed(n['shear_factor'], 3)}" for _, n in measured],
                ["E / E_I, measured nu"] + [f"{fixed(n['youngs_factor'], 3)}, {fixed(n['poisson_ratio'], 3)}"
                                            for _, n in measured],
                ["the springs as they are: E relaxed / E affine (nu)"] + [
                    f"{fixed(iso(n, 'network')[0]['youngs'] / iso(n, 'network')[1]['youngs'], 3)} "
                    f"({fixed(iso(n, 'network')[0]['poisson'], 3)})" for _, n in measured]]
        lines += ["", "The interior network's measured moduli (static strain test, `network_moduli`):", ""]
        lines += table([""] + [label for label, _ in measured], rows)
    return lines


@quick_table("validate-quick")
def validate_quick(p):
    lines = ["```", "tidalcrust validate workflows/quick.toml --set gravity.kernel=portable", "```", ""]
    return lines + validation_lines(p, [("quick (level 3, 1042 particles)", p.work / "quick")])


def sweep_lines(p, folder):
    d = p.load(Path(folder) / "report" / "sweep.json")
    encounters = d["encounters"]
    lines = []
    for m2 in sorted({e["perturber_mass"] for e in encounters}):
        mine = [e for e in encounters if e["perturber_mass"] == m2]
        qs = sorted({e["pericenter"] for e in mine})
        vs = sorted({e["pericenter_speed"] for e in mine})
        for eps in sorted({e["failure_strain"] for e in mine}):
            cell = {(e["pericenter"], e["pericenter_speed"]): e for e in mine if e["failure_strain"] == eps}
            rows = []
            for v in vs:
                row = [f"V_q = {short(v)}"]
                for q in qs:
                    e = cell.get((q, v))
                    row.append("" if e is None or e["status"] != "finished" else
                               ("0" if not e["failures"] else pct(e["failed_fraction"])))
                rows.append(row)
            lines += [f"M2 = {short(m2)}, eps_S = {short(eps)}: failed fraction of the shell springs", ""]
            lines += table([""] + [f"q = {short(q)} R" for q in qs], rows) + [""]
    finished = [e for e in encounters if e["status"] == "finished"]
    cracked = [e for e in finished if e["failures"]]
    lines.append(f"{len(finished)} of {len(encounters)} encounters finished, {len(cracked)} cracked; "
                 f"E_I = {fixed(d['youngs_modulus_E_I'], 2)} e_g. Per line of the grid, the largest q that cracked, "
                 "the smallest larger one that did not, and where eq. 5 gives strain = eps_S:")
    lines.append("")
    rows = [[short(b["perturber_mass"]), short(b["pericenter_speed"]), short(b["failure_strain"]),
             "-" if b["largest_cracked_q"] is None else short(b["largest_cracked_q"]) + " R",
             "-" if b["smallest_intact_q"] is None else short(b["smallest_intact_q"]) + " R",
             fixed(b["eq5_q"], 2) + " R"] for b in d["crack_boundaries"]]
    lines += table(["M2", "V_q", "eps_S", "largest q cracked", "smallest larger q intact", "eq. 5: strain = eps_S at"],
                   rows)
    return lines


@quick_table("sweep-quick")
def sweep_quick(p):
    lines = ["```", " ".join(["tidalcrust run workflows/sweep-quick.toml", *KERNEL, *SWEEP_QUICK_SETTINGS]),
             "tidalcrust report workflows/sweep-quick.toml --set gravity.kernel=portable", "```", ""]
    return lines + sweep_lines(p, p.work / "sweep-quick")


# ---------------------------------------------------------------- the full tables (from --runs DIR)


def commands(*lines):
    return ["```", *lines, "```", ""]


def validated_line(p, *validations):
    """'Validated at commit X.' from validate's validation.json files (all of them, if they differ)."""
    seen = []
    for v in validations:
        commit = p.load(v).get("git_commit", "unknown")
        if commit not in seen:
            seen.append(commit)
    return ["Tides measured (validate) at commit " + ", ".join(seen) + ".", ""] if seen else []


def measured_line(p, *checkpoints):
    """'Measured at commit X, gravity kernel K.' (all of them, if the checkpoints differ)."""
    seen = []
    for c in checkpoints:
        m = measured_by(p, c)
        if m not in seen:
            seen.append(m)
    return ["Measured at " + "; ".join(seen) + ".", ""]


# The paper's Table 3, T-series column (Quillen et al. 2016), with d_I and d_IS read the right way
# round: the reference the built body is compared with.
TABLE3_T = {"shell": "2562 / 7680 / - / -", "N_I": "1869", "interior springs": "23363", "N_C": "5966",
            "L_I": "0.176", "E_I": "3.73", "L_S": "0.075", "M_S": "0.07", "L_C": "0.156", "V_IP": "4.5",
            "V_SP": "3.28", "V_Co": "3.3", "h_S": "0.02", "dt": "dt = 0.002"}


@full_table("paper-T-body")
def paper_t_body(p):
    build = p.work / "paper-T" / "body" / "build.h5"
    i = p.inspect(build)
    c, d = i["counts"], i["derived"]
    rows = [
        ["shell nodes / springs / hinges / faces", f"{c['shell']} / {c['springs_shell']} / {c['hinges']} / {c['faces']}",
         TABLE3_T["shell"]],
        ["interior nodes N_I", str(c["interior"]), TABLE3_T["N_I"]],
        ["interior springs", str(c["springs_interior"]), TABLE3_T["interior springs"]],
        ["cross springs N_C", str(c["springs_cross"]), TABLE3_T["N_C"]],
        ["L_I (mean interior rest length)", fixed(d["L_I"], 4), TABLE3_T["L_I"]],
        ["E_I (eq. 15, V = 4/3 pi r_I^3)", fixed(d["E_I"], 2), TABLE3_T["E_I"]],
        ["L_S", fixed(d["L_S"], 4), TABLE3_T["L_S"]],
        ["M_S", fixed(d["M_S"], 3), TABLE3_T["M_S"]],
        ["L_C", fixed(d["L_C"], 4), TABLE3_T["L_C"]],
        ["V_IP (eq. 16)", fixed(d["V_IP"], 2), TABLE3_T["V_IP"]],
        ["V_SP (eq. 19)", fixed(d["V_SP"], 3), TABLE3_T["V_SP"]],
        ["V_Co (eq. 25)", fixed(d["V_Co"], 2), TABLE3_T["V_Co"]],
        ["h_S (E_2D = E_S h_S)", fixed(d["h_S"], 4), TABLE3_T["h_S"]],
        ["dt_max (eq. 13)", fixed(d["dt_max"], 5), TABLE3_T["dt"]],
    ]
    return (commands("tidalcrust build --config workflows/paper-T.toml --out body.h5",
                     "tidalcrust inspect body.h5 --json")
            + measured_line(p, build) + table(["quantity", "built", "Table 3"], rows))


@full_table("paper-T-stretch-relax")
def paper_t_stretch_relax(p):
    body = p.work / "paper-T" / "body"
    s = p.inspect(body / "stretch.h5")
    r = p.inspect(body / "relax.h5")["record"]
    st = s["record"]
    rows = [["stretch", "common rest-length factor f", fixed(st["stretch_factor"], 5)],
            ["", "force evaluations", str(st["iterations"])],
            ["", "residual mean radial surface acceleration", sci(st["residual_surface_acceleration"], 1)],
            ["", "largest strengthening of an interior spring", fixed(st["strengthening_max"], 2) + "x"],
            ["", "strengthened out to", "r = " + fixed(st["strengthening_radius"], 2) + " R"],
            ["", "E_I after strengthening (eq. 15)", fixed(s["derived"]["E_I"], 2)],
            ["relax", "internal kinetic energy", sci(r["internal_kinetic_energy"], 1) + " G M^2/R"],
            ["", "mean shell radius", fixed(r["mean_shell_radius"], 4) + " R"],
            ["", "largest shell strain / tension", f"{sci(r['max_shell_strain'], 1)} / {sci(r['max_shell_tension'], 1)}"],
            ["stability probe", "failures (3 t_grav, gamma = 0.01, no perturber)",
             ", ".join([f"{r['probe_failures']} at eps_S = {short(r['probe_failure_strain'])}"] +
                       [f"{int(n)} at {short(e)}" for e, n in zip(r["probe_other_strains"], r["probe_other_failures"])])],
            ["", "largest shell strain", sci(r["probe_max_shell_strain"], 1)]]
    return (commands("tidalcrust run workflows/paper-T.toml",
                     "tidalcrust inspect checkpoints/paper-T/body/stretch.h5 --json   (and relax.h5)")
            + measured_line(p, body / "stretch.h5", body / "relax.h5") + table(["stage", "quantity", "value"], rows))


def encounter_table_rows(p, folders, with_orbit=True):
    rows = []
    for label, folder in folders:
        s = summary(p, folder)
        e, f, con = s["encounter"], s["failures"], s["conservation"]
        row = [label]
        if with_orbit:
            row += [short(e["perturber_mass"]), f"{short(e['pericenter'])} / {fixed(e['min_distance'], 4)}",
                    f"{short(e['pericenter_speed'])} / {fixed(e['speed_at_min'], 4)}"]
        row += [f"{count(f['count'])} ({pct(f['fraction_shell'])})"] + failures_row(f)[1:]
        if with_orbit:
            row += [f"{sci(con['max_momentum_change'], 1)}, {sci(con['max_relative_angular_momentum_change'], 1)}"]
        rows.append(row)
    return rows


PAPER_T = [("T5", "T5"), ("T1 (eps_S = 0.002)", "T1"), ("T10", "T10"), ("T10b", "T10b")]


@full_table("paper-T-encounters")
def paper_t_encounters(p):
    root = p.work / "paper-T"
    folders = [(label, root / name) for label, name in PAPER_T]
    return (commands("tidalcrust run workflows/paper-T.toml")
            + measured_line(p, *[f / "encounter.h5" for _, f in folders])
            + table(["run", "M2", "q / reached", "V_q / at closest"] + FAILURE_COLUMNS
                    + ["largest drift of P, L/L0"], encounter_table_rows(p, folders)))


def half_dt_rows(p, pairs):
    rows = []
    for label, a, b in pairs:
        c = p.compare(a, b)
        fa, fb = c["a"]["failures"], c["b"]["failures"]
        rows.append([label, f"{fa['count']} / {fb['count']}",
                     f"{fixed(fa['total_crack_length'], 2)} / {fixed(fb['total_crack_length'], 2)} R",
                     f"{pct(fa['hemisphere_fraction'])} / {pct(fb['hemisphere_fraction'])}",
                     f"{fixed(fa['median_angle_from_subsatellite_deg'], 1)} / "
                     f"{fixed(fb['median_angle_from_subsatellite_deg'], 1)} deg",
                     f"{fixed(network_length(fa), 2)} / {fixed(network_length(fb), 2)} R",
                     fixed(c["jaccard"], 3), fixed(c["ks_distance_angle_from_subsatellite"], 3)])
    return rows


@full_table("paper-T-half-dt")
def paper_t_half_dt(p):
    root = p.work / "paper-T"
    pairs = [(name, root / name / "encounter.h5", root / "dt0.5" / name / "encounter.h5") for _, name in PAPER_T]
    return (commands("tidalcrust run workflows/paper-T.toml --dt-factor 0.5",
                     "tidalcrust compare checkpoints/paper-T/T5/encounter.h5 "
                     "checkpoints/paper-T/dt0.5/T5/encounter.h5 --json   (and T1, T10, T10b)")
            + measured_line(p, *[b for _, _, b in pairs])
            + table(["run", "failures A / B", "total crack length A / B", "hemisphere A / B", "median angle A / B",
                     "longest crack A / B", "Jaccard overlap of the failed springs", "KS distance of the angles"],
                    half_dt_rows(p, pairs)))


@full_table("energy-paper-T")
def energy_paper_t(p):
    root = p.work / "paper-T"
    return (commands("tidalcrust run workflows/paper-T.toml --only T5 [--dt-factor 0.5]")
            + measured_line(p, root / "T5" / "encounter.h5", root / "dt0.5" / "T5" / "encounter.h5")
            + table(ENERGY_COLUMNS, energy_rows(p, "paper-T T5", [("0.002", root / "T5"),
                                                                 ("0.001", root / "dt0.5" / "T5")])))


@full_table("paper-N-shape")
def paper_n_shape(p):
    folder = p.work / "paper-N" / "N"
    s = summary(p, folder)
    rows = [[fixed(r["time_from_pericenter"], 2), fixed(r["b_over_a"], 3), fixed(r["c_over_a"], 3)]
            for r in s["principal_axis_ratios"]]
    con = s["conservation"]
    return (commands("tidalcrust run workflows/paper-N.toml") + measured_line(p, folder / "encounter.h5")
            + table(["t - t_peri (t_grav)", "b/a", "c/a"], rows)
            + ["", f"Largest change of the angular momentum over the encounter (relative): "
               f"{sci(con['max_relative_angular_momentum_change'], 1)}; of the momentum: "
               f"{sci(con['max_momentum_change'], 1)}."])


@full_table("relaxed-T")
def relaxed_t(p):
    rows = [relaxed_row(p, "paper-T, paper", p.work / "paper-T" / "body" / "relax.h5"),
            relaxed_row(p, "crust-T, balanced", p.work / "crust-T" / "body" / "relax.h5")]
    return (commands("tidalcrust run workflows/paper-T.toml", "tidalcrust run workflows/crust-T.toml",
                     "tidalcrust inspect checkpoints/{paper-T,crust-T}/body/relax.h5 --json")
            + measured_line(p, p.work / "paper-T" / "body" / "relax.h5", p.work / "crust-T" / "body" / "relax.h5")
            + table(RELAXED_COLUMNS, rows))


def eps_label(p, folder):
    return short(p.inspect(Path(folder) / "encounter.h5")["record"]["failure_strain"])


def plain_encounter_rows(p, folders):
    rows = []
    for label, folder in folders:
        f = summary(p, folder)["failures"]
        rows.append([label, eps_label(p, folder), f"{count(f['count'])} ({pct(f['fraction_shell'])})"]
                    + failures_row(f)[1:])
    return rows


PLAIN_COLUMNS = ["run", "eps_S", "failed shell springs (fraction)"] + FAILURE_COLUMNS[1:]


@full_table("crust-T-encounters")
def crust_t_encounters(p):
    root = p.work / "crust-T"
    folders = [("T5", root / "T5"), ("T1", root / "T1"), ("T1-eps1e-3", root / "T1-eps1e-3"),
               ("T10", root / "T10"), ("T10b", root / "T10b")]
    return (commands("tidalcrust run workflows/crust-T.toml")
            + measured_line(p, *[f / "encounter.h5" for _, f in folders])
            + table(PLAIN_COLUMNS, plain_encounter_rows(p, folders)))


@full_table("crust-T-convergence")
def crust_t_convergence(p):
    """T5 and T1-eps1e-3 at dt, dt/2, dt/4 and t_r/2, t_r/4; a setting not run yet is named, not shown."""
    root = p.work / "crust-T"
    rows, lines, missing = [], [], []
    for enc in ("T5", "T1-eps1e-3"):
        settings = [("dt = 0.002", root / enc), ("dt/2", root / "dt0.5" / enc), ("dt/4", root / "dt0.25" / enc),
                    ("t_r/2", root / f"{enc}-tr2"), ("t_r/4", root / f"{enc}-tr4")]
        counts = {}
        for label, folder in settings:
            if not (folder / "analysis" / "summary.json").is_file():
                missing.append(f"{enc} at {label}")
                continue
            f = summary(p, folder)["failures"]
            counts[label] = f
            rows.append([enc, label, f"{count(f['count'])} ({pct(f['fraction_shell'])})"] + failures_row(f)[1:])

        def change(a, b, key):
            return fixed(100.0 * (counts[b][key] - counts[a][key]) / counts[a][key], 1) + "%"
        finest = "dt/4" if "dt/4" in counts else "dt/2"
        parts = [f"from {a} to {b} the failed count changes by {change(a, b, 'count')} and the total crack length by "
                 f"{change(a, b, 'total_crack_length')}"
                 for a, b in (("dt = 0.002" if finest == "dt/2" else "dt/2", finest), ("t_r/2", "t_r/4"))
                 if a in counts and b in counts]
        if parts:
            lines.append(f"{enc}: " + "; ".join(parts) + ".")
    if missing:
        lines.append("Not run at this commit: " + ", ".join(missing) + ".")
    first = [root / enc / "encounter.h5" for enc in ("T5",)]
    finer = [root / d / "T5" / "encounter.h5" for d in ("dt0.5", "dt0.25") if (root / d / "T5" / "encounter.h5").is_file()]
    return (commands("tidalcrust run workflows/crust-T.toml",
                     "tidalcrust run workflows/crust-T.toml --dt-factor 0.5 --only T5 --only T1-eps1e-3   (and 0.25)")
            + measured_line(p, *first, *finer)
            + table(["run", "setting", "failed shell springs (fraction)"] + FAILURE_COLUMNS[1:], rows)
            + [""] + lines)


@full_table("crust-T-low-eps")
def crust_t_low_eps(p):
    root = p.work / "crust-T"
    folders = [("T5", root / "T5"), ("T5-eps1e-3", root / "T5-eps1e-3"), ("T5-eps5e-4", root / "T5-eps5e-4")]
    return (commands("tidalcrust run workflows/crust-T.toml --only T5 --only T5-eps1e-3 --only T5-eps5e-4")
            + measured_line(p, *[f / "encounter.h5" for _, f in folders])
            + table(PLAIN_COLUMNS, plain_encounter_rows(p, folders)))


MATERIAL = ["material-L3", "material-L4", "material-L5", "material-L6"]


@full_table("material-bodies")
def material_bodies(p):
    rows, files = [], []
    for name in ["paper-T"] + MATERIAL:
        body = p.work / name / "body"
        if not (body / "stretch.h5").is_file():
            continue
        b, st, rl = p.inspect(body / "build.h5"), p.inspect(body / "stretch.h5"), p.inspect(body / "relax.h5")
        c, d, ds = b["counts"], b["derived"], st["derived"]
        files.append(body / "stretch.h5")
        rows.append([name, f"{count(c['interior'])} / {count(c['shell'])} / {count(c['springs_cross'])}",
                     sig(d["k_I"], 3), sig(d["k_C"], 3), fixed(d["E_I"], 2), fixed(d["E_2D"], 4), fixed(d["h_S"], 4),
                     sci(d["D_F"], 2), sci(d["D_F_eq23"], 1), fixed(d["V_IP"], 2), fixed(d["V_SP"], 2),
                     fixed(d["V_Co"], 2), sig(ds["dt_max"], 3), sig(ds["dt_safe"], 3), sig(ds["dt_unstable"], 3),
                     sig(rl["dt"], 2)])
    return (commands("tidalcrust run workflows/material-L3.toml   (and -L4, -L5, -L6, paper-T)",
                     "tidalcrust inspect checkpoints/material-L3/body/build.h5 --json   (and stretch.h5, relax.h5)")
            + measured_line(p, *files)
            + table(["body", "N_I / N_S / N_C", "k_I", "k_C", "E_I", "E_2D", "h_S", "D_F (k_e / 4)", "D_F eq. 23",
                     "V_IP", "V_SP", "V_Co", "dt eq. 13", "dt safe (undamped)", "dt unstable", "dt of the run"], rows))


@full_table("material-runs")
def material_runs(p):
    rows, files = [], []
    for label, name in (("material-L4 (homogeneous)", "material-L4"),
                        ("core-T (core 0.5 R, 3x density, 10x modulus)", "core-T")):
        r = p.inspect(p.work / name / "body" / "relax.h5")["record"]
        f = summary(p, p.work / name / "T5")["failures"]
        files.append(p.work / name / "T5" / "encounter.h5")
        rows.append([label, sci(r["probe_max_shell_strain"], 1), str(r["probe_failures"]),
                     f"{count(f['count'])} ({pct(f['fraction_shell'])})"] + failures_row(f)[1:])
    return (commands("tidalcrust run workflows/material-L4.toml", "tidalcrust run workflows/core-T.toml")
            + measured_line(p, *files)
            + table(["body", "probe: largest shell strain", "probe failures", "T5: failed shell springs (fraction)"]
                    + FAILURE_COLUMNS[1:], rows))


@full_table("welded-T5")
def welded_t5(p):
    """T5 on the material of material-L4 with the paper's coupling, the welded crust and the welded
    lithostatic crust (issue 23 items 4-5)."""
    rows, files = [], []
    for label, name in (("material-L4: paper coupling, balanced crust", "material-L4"),
                        ("welded-L4: welded, balanced crust", "welded-L4"),
                        ("welded-L4: welded, lithostatic crust", "welded-L4-litho")):
        r = p.inspect(p.work / name / "body" / "relax.h5")["record"]
        f = summary(p, p.work / name / "T5")["failures"]
        files.append(p.work / name / "T5" / "encounter.h5")
        rows.append([label, sci(r["max_shell_strain"], 2), sci(r["max_shell_tension"], 1), str(r["probe_failures"]),
                     f"{count(f['count'])} ({pct(f['fraction_shell'])})"] + failures_row(f)[1:])
    return (commands("tidalcrust run workflows/material-L4.toml --out material-L4",
                     "tidalcrust run workflows/welded-L4.toml --out welded-L4",
                     "tidalcrust run workflows/welded-L4.toml --out welded-L4-litho --set relax.crust_support=lithostatic")
            + measured_line(p, *files)
            + table(["body", "relaxed: largest |shell strain|", "largest tension", "probe failures (eps_S = 3e-3)",
                     "T5: failed shell springs (fraction)"] + FAILURE_COLUMNS[1:], rows))


@full_table("welded-T-series")
def welded_t_series(p):
    """The paper's T-series encounters (T5, T1, T10, T10b) on the material of material-L4 with the
    paper's coupling and welded (issue 23 item 5): each statistic side by side and welded / paper."""
    rows, files = [], []
    for name in ("T5", "T1", "T10", "T10b"):
        pair = []
        for label, body in (("paper coupling", "material-L4"), ("welded", "welded-L4")):
            f = summary(p, p.work / body / name)["failures"]
            files.append(p.work / body / name / "encounter.h5")
            pair.append(f)
            rows.append([name, label] + failures_row(f))
        paper, welded = pair
        rows.append([name, "welded / paper"]
                    + [fixed(welded[k] / paper[k], 2) + "x" if paper[k] else "-"
                       for k in ("count", "failed_area_fraction", "total_crack_length")]
                    + [fixed(network_length(welded) / network_length(paper), 2) + "x" if paper["count"] else "-",
                       fixed(welded["clusters"] / paper["clusters"], 2) + "x" if paper["clusters"] else "-", "", ""])
    return (commands("tidalcrust run workflows/material-L4.toml --out material-L4",
                     "tidalcrust run workflows/welded-L4.toml --out welded-L4")
            + measured_line(p, *files)
            + table(["encounter", "coupling"] + FAILURE_COLUMNS, rows))


def resolution_lines(p, folders, command_lines):
    """compare --resolution of the T5 runs in `folders` (run folder names), one row per shell level."""
    files = [p.work / name / "T5" / "encounter.h5" for name in folders if (p.work / name / "T5").is_dir()]
    study = p.json_of("compare", "--resolution", *files, "--json")
    rows = []
    for r in study["rows"]:
        f = r["failures"]
        rows.append([str(r["shell_level"]), count(r["shell_nodes"]), count(r["particles"]), sig(r["dt"], 2),
                     count(f["count"]), pct(f["failed_area_fraction"]), fixed(f["total_crack_length"], 1) + " R",
                     fixed(network_length(f), 2) + " R", count(f["clusters"]), pct(f["hemisphere_fraction"]),
                     fixed(f["median_angle_from_subsatellite_deg"], 1) + " deg"]
                    + ["" if r.get("change_percent") is None else fixed(r["change_percent"][k], 1) + "%"
                       for k in ("failed_area_fraction", "total_crack_length", "hemisphere_fraction")])
    return (commands(*command_lines)
            + measured_line(p, *files)
            + table(["level", "N_S", "particles", "dt", "failed springs", "failed area", "total crack length",
                     "longest crack", "clusters", "hemisphere", "median angle", "d area", "d crack length",
                     "d hemisphere"], rows))


@full_table("resolution")
def resolution(p):
    return resolution_lines(p, MATERIAL, [
        "tidalcrust run workflows/material-L3.toml   (and -L4, -L5, -L6)",
        "tidalcrust compare --resolution checkpoints/material-L{3,4,5,6}/T5/encounter.h5 --json"])


@full_table("resolution-welded")
def resolution_welded(p):
    """T5 on the welded bodies of levels 3-6 (issue 23 item 5)."""
    return resolution_lines(p, ["welded-L3", "welded-L4", "welded-L5", "welded-L6"], [
        "tidalcrust run workflows/welded-L3.toml   (and -L4, -L5, -L6)",
        "tidalcrust compare --resolution checkpoints/welded-L{3,4,5,6}/T5/encounter.h5 --json"])


@full_table("resolution-welded-shadow")
def resolution_welded_shadow(p):
    """T5 on the welded bodies of levels 3-5 with the shadow failure rule (issue 24 item 4)."""
    return resolution_lines(p, ["shadow-welded-L3", "shadow-welded-L4", "shadow-welded-L5"], [
        "tidalcrust run workflows/welded-L3.toml --set encounter.failure_rule=shadow --out shadow-welded-L3   (and -L4, -L5)",
        "tidalcrust compare --resolution shadow-welded-L{3,4,5}/T5/encounter.h5 --json"])


def ensemble_line_lines(p, folder, label):
    """One (M2, V_q, eps_S) line of an ensemble sweep from report/ensembles.json and sweep.json: per q
    the members that cracked (Wilson 95% interval of the share) and the failed springs (mean +- sd),
    then where half the members crack and where eq. 5 puts strain = eps_S."""
    e = p.load(Path(folder) / "report" / "ensembles.json")
    d = p.load(Path(folder) / "report" / "sweep.json")
    rows = []
    for r in sorted(e["ensembles"], key=lambda r: r["pericenter"]):
        c, f = r["cracked"], r["statistics"]["failures"]
        rows.append([f"{short(r['pericenter'])} R", f"{c['members']} of {r['finished']} [{fixed(c['low'], 2)}, {fixed(c['high'], 2)}]",
                     f"{fixed(f['mean'], 1)} +- {fixed(f['sd'], 1)}", sig(r["strain_eq5"], 2)])
    b = d["crack_boundaries"][0]
    lo, hi = b.get("half_probability_q_low"), b.get("half_probability_q_high")
    return ([f"{label} (E_I = {fixed(d['youngs_modulus_E_I'], 2)} e_g):", ""]
            + table(["q", "members cracked (95% interval of the share)", "failed springs (mean +- sd)",
                     "eq. 5 strain"], rows)
            + ["", f"Half the members crack at q = {fixed(b['half_probability_q'], 3)} R (95% range "
               f"{'-' if lo is None else short(lo)} to {'-' if hi is None else short(hi)} R); "
               f"eq. 5 puts strain = eps_S at q = {fixed(b['eq5_q'], 2)} R.", ""])


@full_table("sweep-welded")
def sweep_welded(p):
    """sweep-T's M2 = 0.5 line (V_q = 1.6) on material-L4 (paper coupling) and welded-L4, 5 members a point."""
    folders = [("sweep-material-L4", "material-L4, the paper's coupling"), ("sweep-welded-L4", "welded-L4, welded")]
    present = [(p.work / f, label) for f, label in folders if (p.work / f / "report" / "ensembles.json").is_file()]
    first = [sorted(f.glob("M*_m0/encounter.h5"))[0] for f, _ in present]
    lines = (commands(*[f"tidalcrust run workflows/{f.name}.toml && tidalcrust report workflows/{f.name}.toml"
                        for f, _ in present])
             + measured_line(p, *first))
    for f, label in present:
        lines += ensemble_line_lines(p, f, label)
    return lines


ENSEMBLE_COLUMNS = [("failures", "failed shell springs", 1), ("total_crack_length", "total crack length [R]", 2),
                    ("largest_network_length", "largest connected crack [R]", 2), ("cracks", "cracks (clusters)", 1),
                    ("hemisphere_fraction", "on the pericenter hemisphere", 3), ("median_angle", "median angle [deg]", 1),
                    ("concentricity", "concentricity", 3), ("median_arc_radius", "median arc radius [deg]", 1)]


def ensemble_cell(stat, digits):
    """mean +- sd [95% interval of the mean] of one statistic of ensembles.json."""
    if not stat or stat.get("count", 0) < 2:
        return "-"
    return (f"{fixed(stat['mean'], digits)} +- {fixed(stat['sd'], digits)} "
            f"[{fixed(stat['low'], digits)}, {fixed(stat['high'], digits)}]")


def ensemble_row(p, table_file, encounter, label):
    """One table row: `label` and the ENSEMBLE_COLUMNS cells of ensemble `encounter` in `table_file`."""
    e = p.load(table_file)
    r = next(x for x in e["ensembles"] if x["name"] == encounter)
    return ([label.format(finished=r["finished"], members=r["members"], vary=e["vary"])]
            + [ensemble_cell(r["statistics"].get(key), digits) for key, _, digits in ENSEMBLE_COLUMNS])


def ensemble_rows(p, runs, encounter):
    """One row per (run folder, label): the ensemble `encounter` of its report/ensembles.json."""
    return [ensemble_row(p, p.work / folder / "report" / "ensembles.json", encounter,
                         label + " ({finished} of {members}, {vary})") for folder, label in runs]


@full_table("ensembles-T5")
def ensembles_t5(p):
    """crust-T T5 and material-L4 T5 as 10-member ensembles, members at perturbed pericenters and on
    bodies of their own seed (issue 24)."""
    runs = [("ens-crust-T", "crust-T"), ("ens-crust-T-seeds", "crust-T"),
            ("ens-material-L4", "material-L4"), ("ens-material-L4-seeds", "material-L4")]
    lines = commands(
        "tidalcrust run workflows/crust-T.toml --set ensemble.members=10 --only T5 --out ens-crust-T",
        "tidalcrust run workflows/crust-T.toml --set ensemble.members=10 --set ensemble.vary=body_seed --only T5 --out ens-crust-T-seeds",
        "(the same with workflows/material-L4.toml into ens-material-L4, ens-material-L4-seeds)",
        "tidalcrust report WORKFLOW (the same --set and --out)",
        "tidalcrust compare --ensembles ens-crust-T/report/ensembles.json ens-crust-T-seeds/report/ensembles.json")
    lines += measured_line(p, *[p.work / f / "T5_m0" / "encounter.h5" for f, _ in runs])
    lines += table(["ensemble (members finished, what varies)"] + [c for _, c, _ in ENSEMBLE_COLUMNS],
                   ensemble_rows(p, runs, "T5"))
    for a, b in (runs[0:2], runs[2:4]):
        lines += compare_ensembles_lines(p, p.work / a[0] / "report" / "ensembles.json",
                                         p.work / b[0] / "report" / "ensembles.json",
                                         f"{a[1]}: A members at perturbed pericenters, B members on bodies of seeds 1-10:")
    return lines


def resolution_welded_rule_lines(p, rule, settings="", only=""):
    """T5 on the welded bodies of levels 3-5 (and 6 where run) with failure rule `rule` and the
    extra `--set` options `settings` (the single runs also with `only`): the single runs, then each level as an ensemble of members at
    perturbed pericenters."""
    folders = [f"{rule}-welded-L{level}" for level in (3, 4, 5, 6) if level < 6 or (p.work / f"{rule}-welded-L6").is_dir()]
    levels = "-L4, -L5" + (", -L6" if len(folders) > 3 else "")
    # The ensembles only of the levels that have one (level 6 may be a single run).
    ensembles = [f"-L{f[-1]}" for f in folders[1:] if (p.work / f / "report" / "ensembles.json").is_file()]
    ensemble_levels = f"   (and {', '.join(ensembles)})" if ensembles else ""
    base = f"workflows/welded-L3.toml --set encounter.failure_rule={rule}{settings}"
    lines = resolution_lines(p, folders, [
        f"tidalcrust run {base}{only} --out {rule}-welded-L3   (and {levels})",
        f"tidalcrust run {base} --set ensemble.members=5 --only T5 --out {rule}-welded-L3{ensemble_levels}",
        f"tidalcrust report {base} --set ensemble.members=5 --out {rule}-welded-L3{ensemble_levels}",
        f"tidalcrust compare --resolution {rule}-welded-L{{{','.join(f[-1] for f in folders)}}}/T5/encounter.h5 --json"])
    runs = [(f, f"level {f[-1]}") for f in folders if (p.work / f / "report" / "ensembles.json").is_file()]
    if runs:
        lines += ["", "The same, each level as an ensemble (members at pericenters q (1 + 5e-3 u_k)):", ""]
        lines += table(["ensemble (members finished, what varies)"] + [c for _, c, _ in ENSEMBLE_COLUMNS],
                       ensemble_rows(p, runs, "T5"))
    return lines


# The welded resolution studies at eps_S = 2e-3 (the critical_distance and nonlocal rules): T5's
# failure strain, tree gravity at every level, no stability probe.
T5_AT_2E3_TREE = ("--set encounters.T5.failure_strain=0.002 --set gravity.method=tree "
                  "--set relax.stability_probe=false")


@full_table("resolution-welded-griffith")
def resolution_welded_griffith(p):
    """T5 on the welded bodies of levels 3-5 with the griffith failure rule (issue 24 item 4)."""
    return resolution_welded_rule_lines(p, "griffith")


@full_table("resolution-welded-critical-distance")
def resolution_welded_critical_distance(p):
    """T5 at eps_S = 2e-3 on the welded bodies of levels 3-5 (6 where run) with the critical_distance
    failure rule (issue 24 item 4); tree gravity at every level, no stability probe."""
    return resolution_welded_rule_lines(p, "critical_distance", " " + T5_AT_2E3_TREE, only=" --only T5")


# The crack neighbourhood of the nonlocal resolution study with r_ex a length: level 5's 3 L_S
# (0.0377804 R), which level 6's 6 L_S (0.0188869 R) matches to 2e-4; levels 3 and 4 take it as
# encounter.exclusion_distance.
NONLOCAL_REX = 0.11334


@full_table("resolution-welded-nonlocal-rex")
def resolution_welded_nonlocal_rex(p):
    """T5 at eps_S = 2e-3 on the welded bodies of levels 3-6 with the nonlocal failure rule and the
    crack neighbourhood r_ex = NONLOCAL_REX R at every level, each level an ensemble of members at
    perturbed pericenters (5 at levels 3-5, 3 at level 6); then levels 5 and 6 compared by
    `compare --ensembles` (issue 24 item 4)."""
    settings = "--set encounter.failure_rule=nonlocal " + T5_AT_2E3_TREE
    return nonlocal_study_lines(p, "nonlocal-rex-welded", commands(
        f"tidalcrust run workflows/welded-L3.toml {settings} --set encounter.exclusion_distance={NONLOCAL_REX} "
        "--set ensemble.members=5 --only T5 --out nonlocal-rex-welded-L3   (and -L4)",
        "(level 5: the same with --set encounter.exclusion_radius=3.0 in place of exclusion_distance: r_ex = 3 L_S)",
        "(level 6, 3 members on the relaxed body of nonlocal-welded-L6, copied to nonlocal-rex-welded-L6/body, for K = 0, 1, 2:",
        " tidalcrust encounter --from nonlocal-rex-welded-L6/body/relax.h5 --set ensemble.members=3 --encounter T5_mK "
        "--failure-strain 0.002 --set encounter.failure_rule=nonlocal --set encounter.exclusion_radius=6.0 "
        "--out nonlocal-rex-welded-L6/T5_mK/encounter.h5   r_ex = 6 L_S)",
        f"tidalcrust report workflows/welded-L3.toml {settings} --set encounter.exclusion_distance={NONLOCAL_REX} "
        "--set ensemble.members=5 --out nonlocal-rex-welded-L3   (and each level with its run's settings)",
        "tidalcrust compare --ensembles nonlocal-rex-welded-L5/report/ensembles.json nonlocal-rex-welded-L6/report/ensembles.json"))


@full_table("resolution-welded-nonlocal-principal")
def resolution_welded_nonlocal_principal(p):
    """The same study with the nonlocal_principal rule, each member branching from the relaxed
    body of the nonlocal study's level (issue 24 item 4)."""
    settings = "--set encounter.failure_rule=nonlocal_principal"
    return nonlocal_study_lines(p, "principal-welded", commands(
        "(for each level L = 3..6 with the relaxed body of nonlocal-rex-welded-LL linked into principal-welded-LL/body,",
        " N = 5 members at levels 3-5 and 3 at level 6, and K = 0 .. N - 1:)",
        "tidalcrust encounter --from principal-welded-LL/body/relax.h5 --set ensemble.members=N --encounter T5_mK "
        f"--failure-strain 0.002 {settings} --set encounter.exclusion_distance={NONLOCAL_REX} "
        "--out principal-welded-LL/T5_mK/encounter.h5 --threads 1",
        "(level 5, here and in report: --set encounter.exclusion_radius=3.0 in place of exclusion_distance, as its body "
        "was relaxed: r_ex = 3 L_S)",
        "tidalcrust analyze --from principal-welded-LL/T5_mK/encounter.h5 --out principal-welded-LL/T5_mK/analysis",
        f"tidalcrust report workflows/welded-LL.toml {settings} --set encounter.exclusion_distance={NONLOCAL_REX} "
        f"{T5_AT_2E3_TREE} --set ensemble.members=N --out principal-welded-LL",
        "tidalcrust compare --ensembles principal-welded-L5/report/ensembles.json principal-welded-L6/report/ensembles.json"))


def nonlocal_study_lines(p, prefix, command_lines):
    """A welded resolution study at levels 3-6 in folders PREFIX-L3 .. -L6, each an ensemble of
    T5: the ensembles' table, the crack length beside another crack at levels 5 and 6, and level 5
    against level 6 (`compare --ensembles`, with the rose's sectors)."""
    folders = [f"{prefix}-L{level}" for level in (3, 4, 5, 6)
               if (p.work / f"{prefix}-L{level}" / "report" / "ensembles.json").is_file()]
    lines = list(command_lines)
    lines += measured_line(p, *[p.work / f / "T5_m0" / "encounter.h5" for f in folders])
    lines += table(["ensemble (members finished, what varies)"] + [c for _, c, _ in ENSEMBLE_COLUMNS],
                   ensemble_rows(p, [(f, f"level {f[-1]}") for f in folders], "T5"))
    # 0.04 R is a lattice spacing at level 5 and two at level 6; below the spacing of levels 3 and 4.
    lines += parallel_crack_lines(p, [f for f in folders if f[-1] in "56"], "T5")
    lines += angle_band_lines(p, [f for f in folders if f[-1] in "56"], "T5")
    if all(f"{prefix}-L{level}" in folders for level in (5, 6)):
        lines += compare_ensembles_lines(p, p.work / f"{prefix}-L5" / "report" / "ensembles.json",
                                         p.work / f"{prefix}-L6" / "report" / "ensembles.json",
                                         "Level 5 (A) against level 6 (B), Welch's t test of the members' means "
                                         "(rose_*: the shares of the crack azimuths within 22.5 deg of 0, 45, 90, 135 deg):",
                                         more=ROSE_SECTORS)
    return lines


# The rose of crack azimuths in its four sectors of 45 deg (radial, oblique, concentric, oblique).
ROSE_SECTORS = ("rose_0", "rose_45", "rose_90", "rose_135")


def sibling_tool(name):
    """The module of tools/NAME.py (a tool whose functions a table uses)."""
    import importlib
    if str(Path(__file__).resolve().parent) not in sys.path:
        sys.path.insert(0, str(Path(__file__).resolve().parent))
    return importlib.import_module(name)


def parallel_crack_lines(p, folders, encounter, distance=0.04):
    """Per folder, over its members' cracks.json: the crack length within `distance` R of another
    crack (tools/parallel_cracks.py), mean +- sd, and its share of the total."""
    parallel_cracks = sibling_tool("parallel_cracks")
    rows = []
    for folder in folders:
        near, share = [], []
        for path in sorted((p.work / folder).glob(f"{encounter}_m*/analysis/cracks.json")):
            lengths = parallel_cracks.beside_another(p.load(path)["cracks"], distance)
            total = sum(t for t, _ in lengths)
            near.append(sum(n for _, n in lengths))
            share.append(near[-1] / total)
        if len(near) >= 2:
            rows.append([folder, str(len(near)), f"{statistics.mean(near):.2f} +- {statistics.stdev(near):.2f}",
                         f"{100 * statistics.mean(share):.1f}%"])
    if not rows:
        return []
    return (["", f"Crack length within {distance:g} R of another crack (`tools/parallel_cracks.py "
                 f"--distance {distance:g}` on each member's cracks.json), mean +- sd over the members:", ""] +
            table(["run", "members", "length beside another crack [R]", "share of the total"], rows))


def angle_band_lines(p, folders, encounter):
    """Per band of angle from the subsatellite point (tools/rose_by_angle.py), over each folder's
    members' cracks.json: the crack length and its radial and concentric shares, mean +- sd."""
    rose_by_angle = sibling_tool("rose_by_angle")
    per_folder = {}
    for folder in folders:
        members = [rose_by_angle.bands(c["cracks"], c["subsatellite"])
                   for c in (p.load(path) for path in
                             sorted((p.work / folder).glob(f"{encounter}_m*/analysis/cracks.json")))]
        if len(members) >= 2:
            per_folder[folder] = members
    if len(per_folder) < 2:
        return []

    def spread(values, digits):
        return f"{statistics.mean(values):.{digits}f} +- {statistics.stdev(values):.{digits}f}"

    rows = []
    for b, (lo, hi) in enumerate(zip(rose_by_angle.BANDS_DEG, rose_by_angle.BANDS_DEG[1:])):
        row = [f"{lo}-{hi}"]
        for column, digits in ((0, 2), (1, 3), (2, 3)):
            for members in per_folder.values():
                row.append(spread([m[b][column] if column == 0 else m[b][column] / m[b][0] for m in members], digits))
        rows.append(row)
    names = list(per_folder)
    header = (["angle from the subsatellite point [deg]"] + [f"crack length [R], {n}" for n in names] +
              [f"radial share, {n}" for n in names] + [f"concentric share, {n}" for n in names])
    return (["", "By the angle from the subsatellite point (`tools/rose_by_angle.py` on each member's cracks.json; "
                 "the shares of each band's length within 22.5 deg of radial and of concentric), mean +- sd over the "
                 "members:", ""] + table(header, rows))


def compare_ensembles_lines(p, a, b, title, *pair, more=()):
    """The statistics of ENSEMBLE_COLUMNS (and `more`) from `compare --ensembles A B [--pair ...]`,
    as a code block."""
    args = ["compare", "--ensembles", a, b] + [x for n in pair for x in ("--pair", n)]
    text = p(*args)
    keys = [k for k, _, _ in ENSEMBLE_COLUMNS] + list(more)
    wanted = [l for l in text.splitlines() if l.startswith("ensemble ") or (l.split() and l.split()[0] in keys)]
    return ["", title, "", "```"] + wanted + ["```"]


@full_table("crust-T-convergence-ensembles")
def crust_t_convergence_ensembles(p):
    """crust-T T5 at dt, dt/2 and t_r/2, t_r/4 as 10-member ensembles (issue 24: the convergence
    statements on the ensemble footing)."""
    root = p.work / "ens-crust-T2"
    at_dt, at_half = root / "report" / "ensembles.json", root / "dt0.5" / "report" / "ensembles.json"
    rows = [ensemble_row(p, table_file, name, label + " ({finished} of {members})")
            for table_file, name, label in ((at_dt, "T5", "T5, dt = 0.002"), (at_half, "T5", "T5, dt/2"),
                                            (at_dt, "T5-tr2", "T5, t_r/2"), (at_dt, "T5-tr4", "T5, t_r/4"))]
    lines = commands("tidalcrust run workflows/crust-T.toml --set ensemble.members=10 --only T5 --only T5-tr2 --only T5-tr4 --out ens-crust-T2",
                     "tidalcrust run workflows/crust-T.toml --set ensemble.members=10 --only T5 --out ens-crust-T2 --dt-factor 0.5",
                     "tidalcrust report workflows/crust-T.toml --set ensemble.members=10 --out ens-crust-T2 [--dt-factor 0.5]")
    lines += measured_line(p, root / "T5_m0" / "encounter.h5", root / "dt0.5" / "T5_m0" / "encounter.h5")
    lines += table(["ensemble (members finished)"] + [c for _, c, _ in ENSEMBLE_COLUMNS], rows)
    lines += compare_ensembles_lines(p, at_dt, at_half, "dt to dt/2 (`compare --ensembles` of the two reports):")
    lines += compare_ensembles_lines(p, at_dt, at_dt, "t_r to t_r/2 and t_r/2 to t_r/4 (`--pair T5:T5-tr2 --pair T5-tr2:T5-tr4`):",
                                     "T5:T5-tr2", "T5-tr2:T5-tr4")
    return lines


@full_table("sweep-T-ensemble")
def sweep_t_ensemble(p):
    """sweep-T's M2 = 0.5 grid with 5 members a point (issue 24): members cracked per (V_q, q) with
    the Wilson interval of the share, and per V_q where half the members crack against eq. 5."""
    folder = p.work / "ens-sweep-T"
    e = p.load(folder / "report" / "ensembles.json")
    d = p.load(folder / "report" / "sweep.json")
    points = [r for r in e["ensembles"] if r["perturber_mass"] == 0.5 and r["finished"] > 0]
    qs = sorted({r["pericenter"] for r in points})
    vs = sorted({r["pericenter_speed"] for r in points})
    at = {(r["pericenter_speed"], r["pericenter"]): r for r in points}

    def cell(v, q):
        r = at.get((v, q))
        if r is None:
            return "-"
        c = r["cracked"]
        return f"{c['members']} of {r['finished']} [{fixed(c['low'], 2)}, {fixed(c['high'], 2)}]"

    rows = [[f"V_q = {short(v)}"] + [cell(v, q) for q in qs] for v in vs]
    bounds = []
    for b in sorted((b for b in d["crack_boundaries"] if b["perturber_mass"] == 0.5), key=lambda b: b["pericenter_speed"]):
        h, lo, hi = b.get("half_probability_q"), b.get("half_probability_q_low"), b.get("half_probability_q_high")
        bounds.append([f"V_q = {short(b['pericenter_speed'])}", "-" if h is None else fixed(h, 2) + " R",
                       f"{'-' if lo is None else short(lo)} to {'-' if hi is None else short(hi)} R",
                       fixed(b["eq5_q"], 2) + " R"])
    first = sorted(folder.glob("M0.5_*_m0/encounter.h5"))[:1]
    return (commands("tidalcrust run workflows/sweep-T.toml --set ensemble.members=5 --only M0.5_q1.5_V1.4 ... "
                     "--only M0.5_q2.75_V2.2 --out ens-sweep-T   (the 30 points of M2 = 0.5)",
                     "tidalcrust report workflows/sweep-T.toml --set ensemble.members=5 --out ens-sweep-T")
            + measured_line(p, *first)
            + ["M2 = 0.5, eps_S = 0.003: members cracked (Wilson 95% interval of the share)", ""]
            + table([""] + [f"q = {short(q)} R" for q in qs], rows)
            + ["", "Where half the members crack, with the 95% range of the grid, and where eq. 5 puts strain = eps_S:", ""]
            + table(["", "half the members crack at", "95% range", "eq. 5"], bounds))


def coupling_seed_lines(p, prefix, settings=""):
    """The tide and 0S2 of welded-L4 validated on body seeds 1-3 in folders PREFIX-s1..s3 (with the
    extra `--set` options SETTINGS): each line's ratio per seed, mean +- sd, the tolerance."""
    columns = [(f"seed {k}", p.work / f"{prefix}-s{k}") for k in (1, 2, 3)
               if (p.work / f"{prefix}-s{k}" / "validate" / "validation.json").is_file()]
    docs = [p.load(folder / "validate" / "validation.json") for _, folder in columns]
    rows = []
    for key, label in COUPLING_ROWS:
        ratios = [d["comparisons"][key]["ratio"] for d in docs if key in d["comparisons"]]
        if not ratios:
            continue
        mean = sum(ratios) / len(ratios)
        sd = (sum((x - mean) ** 2 for x in ratios) / (len(ratios) - 1)) ** 0.5 if len(ratios) > 1 else float("nan")
        tol = docs[0]["comparisons"][key]["tolerance"]
        rows.append([label] + [fixed(x, 3) + "x" for x in ratios] + [f"{fixed(mean, 3)} +- {fixed(sd, 3)}",
                                                                     f"{round(tol * 100):d}%"])
    return (commands(*[f"tidalcrust validate workflows/welded-L4.toml --out {folder.name}{settings} --measure tide,ringdown"
                       + ("" if label == "seed 1" else f" --set workflow.seed={label.split()[1]}")
                       for label, folder in columns])
            + measured_line(p, *[folder / "body" / "relax.h5" for _, folder in columns])
            + ["Each cell: measured / theory (the homogeneous sphere of that body's measured network moduli); "
               "last columns: mean +- sd over the seeds, and the issue's tolerance.", ""]
            + table(["", *[label for label, _ in columns], "mean +- sd", "tolerance"], rows))


@full_table("crust-coupling-seeds")
def crust_coupling_seeds(p):
    """welded-L4's tide and 0S2 on three body seeds: the spread of each line between bodies."""
    return coupling_seed_lines(p, "welded-L4")


@full_table("crust-coupling-fine-interior")
def crust_coupling_fine_interior(p):
    """welded-L4 with level 5's interior spacing (d_IS = 0.0707 R) on three body seeds: the crust
    springs' correlation with the continuum is set by the interior's grain under the crust."""
    return coupling_seed_lines(p, "welded-L4-fine", " --set resolution.interior_spacing=0.0707")


@full_table("crust-coupling-interior-spacing")
def crust_coupling_interior_spacing(p):
    """welded-L4 (shell level 4, seed 1) over interiors of four spacings d_IS: the crust springs'
    correlation with the continuum and the spring-by-spring scatter against the interior's grain."""
    runs = [(0.141, "welded-L4-dIS0.141"), (0.10, "welded-L4-s1"), (0.085, "welded-L4-dIS0.085"),
            (0.0707, "welded-L4-fine-s1")]
    runs = [(d, p.work / f) for d, f in runs if (p.work / f / "validate" / "validation.json").is_file()]
    rows = []
    for d_is, folder in runs:
        v = p.load(folder / "validate" / "validation.json")
        i = p.inspect(folder / "body" / "relax.h5")
        c = v["comparisons"]
        rows.append([f"{d_is:g} R" + (" (default)" if d_is == 0.10 else ""), count(i["counts"]["interior"]),
                     count(i["counts"]["interior"] + i["counts"]["shell"]), fixed(i["dt"], 5), fixed(c["tide-correlation"]["measured"], 3),
                     fixed(v["details"]["tide"]["ratio_scatter"], 3), fixed(c["tide"]["ratio"], 3) + "x",
                     fixed(c["tide-l2-over-h2"]["ratio"], 3) + "x", fixed(c["tide-peak-tension"]["ratio"], 3) + "x"])
    return (commands(*[f"tidalcrust validate workflows/welded-L4.toml --out {folder.name}"
                       + ("" if d_is == 0.10 else f" --set resolution.interior_spacing={d_is:g}") + " --measure tide"
                       for d_is, folder in runs])
            + measured_line(p, *[folder / "body" / "relax.h5" for _, folder in runs])
            + table(["interior spacing d_IS", "interior nodes", "particles", "dt", "correlation with the continuum",
                     "scatter of the ratio", "h2 / TS72", "l2/h2 / TS72", "peak tension / TS72"], rows))


@full_table("sweep-T")
def sweep_t(p):
    folder = p.work / "sweep-T"
    first = sorted((folder).glob("M*/encounter.h5"))[:1]
    return (commands("tidalcrust run workflows/sweep-T.toml", "tidalcrust report workflows/sweep-T.toml")
            + measured_line(p, *first) + sweep_lines(p, folder))


@full_table("validate-T")
def validate_t(p):
    return (commands("tidalcrust validate workflows/paper-T.toml", "tidalcrust validate workflows/paper-N.toml")
            + measured_line(p, p.work / "paper-T" / "body" / "relax.h5", p.work / "paper-N" / "body" / "relax.h5")
            + validation_lines(p, [("paper-T (level 4, 4431 particles)", p.work / "paper-T"),
                                   ("paper-N (no crust, 798 particles)", p.work / "paper-N")]))


@full_table("validate-material")
def validate_material(p):
    columns = [(name, p.work / name) for name in MATERIAL
               if (p.work / name / "validate" / "validation.json").is_file()]
    return (commands("tidalcrust validate workflows/material-L3.toml   (and -L4, -L5)",
                     "tidalcrust validate workflows/material-L6.toml --measure love")
            + measured_line(p, *[f / "body" / "relax.h5" for _, f in columns])
            + validation_lines(p, columns))


COUPLING = [("quick-balanced", "quick-balanced (L3): paper coupling"), ("quick-welded", "quick-welded (L3): welded"),
            ("material-L4", "material-L4: paper coupling"), ("welded-L4", "welded-L4: welded"),
            ("material-L5", "material-L5: paper coupling"), ("welded-L5", "welded-L5: welded")]
COUPLING_ROWS = [("tide", "h2"), ("tide-l2", "l2"), ("tide-l2-over-h2", "l2 / h2"),
                 ("tide-correlation", "crust strain vs continuum: correlation"),
                 ("tide-median-ratio", "median ratio measured / continuum, spring by spring"),
                 ("tide-peak-tension", "peak meridional tension, gamma 75-90 deg (per unit eps)"),
                 ("tide-subsatellite", "mean strain, gamma < 15 deg (per unit eps)"),
                 ("ringdown", "0S2 period (t_grav) against TS72"), ("ringdown-lamb", "0S2 period against Lamb, no gravity")]


def coupling_lines(p, columns, command_lines):
    """The tide and ring-down of validation.json side by side: one column per (label, run folder)."""
    docs = [(label, p.load(folder / "validate" / "validation.json")) for label, folder in columns]
    rows = []
    for key, label in COUPLING_ROWS:
        cells, tolerance = comparison_cells(
            docs, key, lambda c: f"{sig(c['measured'], 4)} ({sig(c['theory'], 4)}, {fixed(c['ratio'], 3)}x)")
        rows.append([label] + cells + [tolerance])
    rows.append(["scatter of the ratio (half the 16-84% range)"]
                + [fixed(d["details"]["tide"]["ratio_scatter"], 3) for _, d in docs] + [""])
    rows.append(["layered TS72 h2 / 0S2 (eq. 15 per layer x the strain test's factor)"]
                + [f"{sig(d['details']['tide']['layered_h2'], 3)} / {sig(d['details']['ringdown']['layered_period'], 4)}"
                   if "ringdown" in d["details"] else sig(d["details"]["tide"]["layered_h2"], 3) for _, d in docs] + [""])
    rows.append(["sphere E, nu (network moduli)"]
                + [f"{fixed(d['network_moduli']['youngs_modulus'], 3)} e_g, {fixed(d['network_moduli']['poisson_ratio'], 3)}"
                   for _, d in docs] + [""])
    rows.append(["theory of the tide's rows"]
                + [d["details"]["tide"].get("reference", "homogeneous") + " sphere" for _, d in docs] + [""])
    return (commands(*command_lines)
            + measured_line(p, *[folder / "body" / "relax.h5" for _, folder in columns])
            + ["Each cell: measured (theory, measured / theory). Theory: Takeuchi & Saito (1972) for the homogeneous "
               "sphere of the network's measured moduli, or for a body with a core the layered sphere of its own "
               "layers (last row).", ""]
            + table(["", *[label for label, _ in docs], "tolerance"], rows))


@full_table("crust-coupling")
def crust_coupling(p):
    columns = [(label, p.work / name) for name, label in COUPLING
               if (p.work / name / "validate" / "validation.json").is_file()]
    return coupling_lines(p, columns, [f"tidalcrust validate workflows/{folder.name}.toml --measure tide,ringdown"
                                       for _, folder in columns])


@full_table("crust-coupling-crust-T")
def crust_coupling_crust_t(p):
    """crust-T's own body (the paper's spring constants) welded: the crust-T equivalent of issue 23."""
    return coupling_lines(p, [("crust-T welded (level 4)", p.work / "welded-crust-T")], [
        "tidalcrust validate workflows/crust-T.toml --out welded-crust-T --set cross.coupling=welded "
        "--set integrator.dt=0.0015 --measure tide,ringdown"])


@full_table("crust-coupling-L5")
def crust_coupling_l5(p):
    """Level 5 welded, and a welded body with a core (issue 23): the runs of this session's folder."""
    columns = [("welded-L5 (level 5): welded", p.work / "welded-L5"),
               ("core-T welded, level 3", p.work / "core-welded-L3")]
    return coupling_lines(p, columns, [
        "tidalcrust validate workflows/welded-L5.toml --out welded-L5 --measure tide,ringdown",
        "tidalcrust validate workflows/core-T.toml --out core-welded-L3 --set cross.coupling=welded "
        "--set resolution.shell_level=3 --measure tide,ringdown"])


MOON_RUNS = [("Tethys", "tethys", ["T5", "close", "close-second"]), ("Dione", "dione", ["T5"])]


@full_table("moons")
def moons(p):
    """The moons in SI (issue 25): each encounter of workflows/tethys.toml and dione.toml, a later
    pass of a history with the number of springs failed before it."""
    rows, finals = [], []
    for moon, folder, names in MOON_RUNS:
        for name in names:
            s = summary(p, p.work / folder / name)
            e, f, si = s["encounter"], s["failures"], s["si"]
            history = s.get("history")
            orbit = e["orbit"]
            finals.append(p.work / folder / name / "encounter.h5")
            rows.append([moon, name, history["after"] if history else "-",
                         f"{fixed(si['encounter']['subsatellite_planetocentric_longitude_deg'], 0)}, "
                         f"{fixed(orbit['subsatellite_latitude_deg'], 0)}",
                         sig(si["encounter"]["perturber_mass_kg"], 2) + " kg",
                         f"{fixed(si['encounter']['pericenter_km'], 0)} km",
                         f"{fixed(si['encounter']['pericenter_speed_km_s'], 3)} km/s",
                         count(f["count"]), count(history["earlier_failed"]) if history else "-",
                         f"{fixed(si['failures']['total_crack_length_km'], 0)} km",
                         f"{fixed(si['failures']['largest_network_length_km'], 0)} km" if f["count"] else "-",
                         count(f["clusters"]), pct(f["hemisphere_fraction"]) if f["count"] else "-",
                         fixed(f["median_angle_from_subsatellite_deg"], 1) + " deg" if f["count"] else "-"])
    return (commands("tidalcrust run workflows/tethys.toml --out tethys",
                     "tidalcrust run workflows/dione.toml --out dione")
            + measured_line(p, *finals)
            + table(["moon", "encounter", "after", "subsatellite point (planetocentric lon, lat; deg)", "M2", "q",
                     "V_q", "failed shell springs (this pass)", "failed before", "total crack length",
                     "largest network", "cracks (clusters)", "on the pericenter hemisphere",
                     "median angle from the subsatellite point"], rows))


def median(values):
    v = sorted(values)
    n = len(v)
    return None if not n else (v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2]))


BENCH_RUNS = [("paper-T", "tidalcrust bench --config workflows/paper-T.toml --steps 20 --json"),
              ("paper-T-tree", "tidalcrust bench --config workflows/paper-T.toml --steps 20 --set gravity.method=tree "
                               "--json"),
              ("bench-L5", "tidalcrust bench --config workflows/bench-L5.toml --steps 10 --repeats 3 "
                           "--textbook-steps 0 --json"),
              ("bench-L6", "tidalcrust bench --config workflows/bench-L6.toml --steps 5 --repeats 3 "
                           "--textbook-steps 0 --direct-steps 1 --json"),
              ("bench-L7", "tidalcrust bench --config workflows/bench-L7.toml --steps 3 --repeats 3 "
                           "--textbook-steps 0 --direct-steps 1 --json")]


def run_benchmarks(p, repeat):
    """Runs every BENCH_RUNS command `repeat` times into p.work/bench/NAME-<i>.json (and the
    program's version into version.txt), then prints the speed table of those files."""
    folder = p.work / "bench"
    folder.mkdir(parents=True, exist_ok=True)
    for stale in folder.glob("*.json"):
        stale.unlink()
    (folder / "version.txt").write_text(p("--version"))
    for i in range(1, repeat + 1):
        for name, command in BENCH_RUNS:
            out = p(*shlex.split(command)[1:])
            (folder / f"{name}-{i}.json").write_text(out)
            run = json.loads(out)
            print(f"bench {name} ({run['particles']:,} particles), run {i} of {repeat}: "
                  f"{run['ms_per_step']:.4g} ms per step", flush=True)
    print()
    print("\n".join(speed_here(p)))


@full_table("speed-here")
def speed_here(p):
    """Medians over the runs bench/NAME-<i>.json of the runs folder; ratios taken run by run."""
    rows, lines = [], []
    for name, command in BENCH_RUNS:
        # NAME-<digits>.json only: paper-T's runs are not paper-T-tree's.
        runs = [json.loads(f.read_text()) for f in sorted((p.work / "bench").glob(f"{name}-*.json"))
                if re.fullmatch(re.escape(name) + r"-\d+\.json", f.name)]
        if not runs:
            continue
        lines.append(command + f"   ({len(runs)} run{'' if len(runs) == 1 else 's'})")
        step = [r["ms_per_step"] for r in runs]
        tree = runs[0]["gravity_method"] == "tree"
        other = [r["direct_ms_per_step"] if tree else r.get("textbook_ms_per_step") for r in runs]
        ratio = [r["speedup_vs_direct"] if tree else r.get("speedup") for r in runs]
        portable = [r["portable_over_fast"] for r in runs if r.get("portable_over_fast")]
        rows.append([name, count(runs[0]["particles"]), runs[0]["gravity_method"], str(len(runs)),
                     f"{sig(median(step), 3)} ({sig(min(step), 3)}-{sig(max(step), 3)})",
                     "-" if None in other else f"{sig(median(other), 3)} ({'direct' if tree else 'textbook'})",
                     "-" if None in ratio else fixed(median(ratio), 2) + "x",
                     f"{sci(median([r['force_error']['median'] for r in runs]), 1)} / "
                     f"{sci(median([r['force_error']['p99'] for r in runs]), 1)}" if tree else "-",
                     fixed(median(portable), 2) + "x" if portable else "-",
                     fixed(max(r["peak_memory_mb"] for r in runs), 0) + " MB"])
    kernel = runs[0]["gravity_kernel"] if rows else "-"
    version = p.load_text(p.work / "bench" / "version.txt").strip()
    return (commands(*lines) + [f"Measured with `{version}`.", "",
                                f"Gravity kernel {kernel}, {runs[0]['threads']} threads; ms per full step "
                                "(springs with damping, hinges, gravity, perturber), median and range over the runs.", ""]
            + table(["body", "N", "gravity", "runs", "full step (ms)", "the other step (ms)",
                     "speed-up (median of the runs' ratios)", "tree force error median / p99",
                     "portable kernel / fast", "peak memory"], rows))


# A crust that varies (issue 25, docs/crust.md): T5 on welded-L3 as 5-member ensembles.
CRUST_RUNS = [
    ("crust-L3-uniform", "uniform", ""),
    ("crust-L3-thin-north", "thickness t = 1 - 0.5 z (thin north)", "--set \"crust.thickness_harmonics='c10 = -0.5'\""),
    ("crust-L3-weak-north", "strength f = 1 - 0.5 z (weak north)", "--set \"crust.strength_harmonics='c10 = -0.5'\""),
    ("crust-L3-thin-near", "thickness t = 1 - 0.5 y (thin toward the perturber)",
     "--set \"crust.thickness_harmonics='s11 = -0.5'\""),
    ("crust-L3-weak-near", "strength f = 1 - 0.5 y (weak toward the perturber)",
     "--set \"crust.strength_harmonics='s11 = -0.5'\""),
    ("crust-L3-weak-line", "weak great circle f = 0.5 within 5 deg (pole lon 0, lat 0)",
     "--set \"crust.weak_lines='pole_lon = 0 pole_lat = 0 half_width = 5 factor = 0.5'\""),
]


def mean_sd(values, digits):
    """mean +- sample sd of the members' values ("-" without two of them)."""
    values = [v for v in values if v is not None]
    if len(values) < 2:
        return "-"
    return f"{fixed(statistics.mean(values), digits)} +- {fixed(statistics.stdev(values), digits)}"


@full_table("crust-variation")
def crust_variation(p):
    """T5 on welded-L3, 5-member ensembles (members at perturbed pericenters), with a uniform crust,
    thickness and strength dichotomies north-south and near-far, and a weak great circle: per crust
    the relaxed body's probe, the failed count, the shares of the failures on the subsatellite
    hemisphere (summary.json failures.hemisphere_fraction) and in the north (failed_springs
    latitude > 0), and the failure and spring shares of the weak and thin parts (summary.json crust)."""
    present = [r for r in CRUST_RUNS if (p.work / r[0] / "T5_m0" / "analysis" / "summary.json").is_file()]
    lines = commands(*[f"tidalcrust run workflows/welded-L3.toml --set ensemble.members=5 {s} --threads 1 --out {f}".replace("  ", " ")
                       for f, _, s in CRUST_RUNS])
    lines += measured_line(p, *[p.work / f / "T5_m0" / "encounter.h5" for f, _, _ in present])
    rows = []
    for folder, label, _ in present:
        relax = p.inspect(p.work / folder / "body" / "relax.h5")["record"]
        members = [p.load(m) for m in sorted((p.work / folder).glob("T5_m*/analysis/summary.json"))]
        failures = [m["failures"] for m in members]
        north = [sum(1 for x in m["failed_springs"]["latitude_deg"] if x > 0) / len(m["failed_springs"]["latitude_deg"])
                 if m["failed_springs"]["latitude_deg"] else None for m in members]

        def part(name):
            if not members[0]["crust"][name]["springs"]:
                return "-"
            shares = lambda key: [m["crust"][name][key] for m in members]
            return (f"{mean_sd(shares('failure_share'), 3)} of the failures on {fixed(shares('spring_share')[0], 3)} "
                    f"of the springs: {mean_sd(shares('capture_ratio'), 2)}x")
        rows.append([label, f"{relax['probe_failures']} ({sci(relax['probe_max_shell_strain'])})", str(len(members)),
                     mean_sd([f["count"] for f in failures], 1), mean_sd([f["hemisphere_fraction"] for f in failures], 3),
                     mean_sd(north, 3), part("weak"), part("thin")])
    lines += table(["crust", "probe failures (largest strain)", "members", "failed shell springs",
                    "share on the subsatellite hemisphere", "share in the north", "weak part (f < 1)",
                    "thin part (t < 1)"], rows)
    return lines


# A spinning body (issue 26, docs/spin.md): T5 prograde and retrograde on welded-L3 spinning at 0.3
# and 0.6 of breakup, beside the body without spin (crust-variation's uniform crust), 5-member ensembles.
SPIN_RUNS = [("crust-L3-uniform", "T5", "no spin"),
             ("spin-L3-0.3", "T5-prograde", "0.3, prograde"), ("spin-L3-0.3", "T5-retrograde", "0.3, retrograde"),
             ("spin-L3-0.6", "T5-prograde", "0.6, prograde"), ("spin-L3-0.6", "T5-retrograde", "0.6, retrograde"),
             # members on bodies of their own seed (ensemble.vary = "body_seed"): the body's own asymmetries average out
             ("spin-L3-0-seeds", "T5-prograde", "no spin, body seeds"),
             ("spin-L3-0.6-seeds", "T5-prograde", "0.6, prograde, body seeds"),
             ("spin-L3-0.6-seeds", "T5-retrograde", "0.6, retrograde, body seeds")]

# Student's t_{0.975, n-1} for the 95% interval of a mean of n = 2 .. 10 members.
T_975 = {2: 12.706, 3: 4.303, 4: 3.182, 5: 2.776, 6: 2.571, 7: 2.447, 8: 2.365, 9: 2.306, 10: 2.262}


def mean_sd_interval(values, digits):
    """mean +- sample sd [95% interval of the mean] of the members' values ("-" without two of them)."""
    values = [v for v in values if v is not None]
    if len(values) < 2 or len(values) not in T_975:
        return mean_sd(values, digits)
    m, sd = statistics.mean(values), statistics.stdev(values)
    half = T_975[len(values)] * sd / len(values) ** 0.5
    return f"{fixed(m, digits)} +- {fixed(sd, digits)} [{fixed(m - half, digits)}, {fixed(m + half, digits)}]"


def east_share(summary):
    """The share of the failed springs east of the subsatellite point's meridian (longitude - the
    subsatellite longitude in (0, 180) deg: the side the spin carries the surface toward); None without failures."""
    lons = summary["failed_springs"]["longitude_deg"]
    if not lons:
        return None
    sub = summary["encounter"]["orbit"]["subsatellite_longitude_deg"]
    return sum(1 for x in lons if 0 < (x - sub) % 360 < 180) / len(lons)


def north_share(summary):
    lats = summary["failed_springs"]["latitude_deg"]
    return sum(1 for x in lats if x > 0) / len(lats) if lats else None


@full_table("spin")
def spin(p):
    """T5 on welded-L3 without spin and spinning at 0.3 and 0.6 of breakup, prograde (inclination 0) and
    retrograde (inclination 180, argument_of_pericenter 270), 5-member ensembles (members at perturbed
    pericenters): the relaxed body's flattening against h2 q / 2, then per run the failures, their
    share on the subsatellite hemisphere and east of its meridian (body frame), the median angle,
    the crack orientation (concentricity, rose peak) and where the subsatellite point fell."""
    runs = [r for r in SPIN_RUNS if (p.work / r[0] / f"{r[1]}_m0" / "analysis" / "summary.json").is_file()]
    lines = commands("tidalcrust run workflows/welded-L3.toml --set ensemble.members=5 --threads 1 --out crust-L3-uniform",
                     *[f"tidalcrust run workflows/spin-L3.toml --set spin.angular_velocity={w} --set ensemble.members=5 "
                       f"--threads 2 --jobs 2 --out spin-L3-{w}" for w in ("0.3", "0.6")],
                     *[f"tidalcrust run workflows/spin-L3.toml --set spin.angular_velocity={w} --set ensemble.members=5 "
                       f"--set ensemble.vary=body_seed {only}--threads 2 --jobs 2 --out spin-L3-{w}-seeds"
                       for w, only in (("0", "--only T5-prograde "), ("0.6", ""))])
    lines += measured_line(p, *[p.work / f / f"{e}_m0" / "encounter.h5" for f, e, _ in runs])
    shapes = []
    for folder in dict.fromkeys(f for f, _, _ in runs if not f.endswith("-seeds")):
        relax = p.inspect(p.work / folder / "body" / "relax.h5")
        s = relax.get("spin")
        record = relax["record"]
        shapes.append([folder, "0" if not s else short(s["angular_velocity"]),
                       "-" if not s else sci(s["flattening"], 4),
                       f"{record['probe_failures']} ({sci(record['probe_max_shell_strain'])})"])
    lines += table(["relaxed body", "Omega [sqrt(GM/R^3)]", "flattening (a - c)/a", "probe failures (largest strain)"],
                   shapes) + [""]
    rows = []
    for folder, encounter, label in runs:
        members = [p.load(m) for m in sorted((p.work / folder).glob(f"{encounter}_m*/analysis/summary.json"))]
        failures = [m["failures"] for m in members]
        column = lambda key: [f[key] for f in failures]
        sub = [m["encounter"]["orbit"]["subsatellite_longitude_deg"] for m in members]
        rows.append([label, str(len(members)), mean_sd_interval(column("count"), 1),
                     mean_sd_interval([100 * x for x in column("failed_area_fraction")], 2),
                     mean_sd_interval(column("hemisphere_fraction"), 3),
                     mean_sd_interval([east_share(m) for m in members], 3),
                     mean_sd_interval([north_share(m) for m in members], 3),
                     mean_sd_interval(column("median_angle_from_subsatellite_deg"), 1),
                     mean_sd_interval(column("concentricity"), 3),
                     mean_sd_interval(column("crack_rose_peak_deg"), 0),
                     mean_sd(sub, 1)])
    lines += table(["spin, orbit", "members", "failed shell springs", "failed area [%]",
                    "share on the subsatellite hemisphere", "share east of its meridian", "share in the north",
                    "median angle [deg]", "concentricity", "crack rose peak [deg]",
                    "subsatellite longitude [deg]"], rows)
    return lines


# An ocean under the crust (issue 26, docs/ocean.md): T5 on ocean-L3 (welded-L3's material, a
# floating crust over 0.3 R of liquid) at two shear fractions of the liquid's springs, beside the
# body without ocean (crust-variation's uniform crust), 5-member ensembles; the static tide of each.
OCEAN_RUNS = [("crust-L3-uniform", "workflows/welded-L3.toml", "", "no ocean (welded crust)"),
              ("ocean-L3", "workflows/ocean-L3.toml", "", "ocean, shear fraction 0.01"),
              ("ocean-L3-s1e-3", "workflows/ocean-L3.toml", "--set ocean.shear_fraction=0.001 ",
               "ocean, shear fraction 0.001"),
              ("ocean-L3-maxwell", "workflows/ocean-L3.toml", "--set ocean.maxwell_time=0.05 ",
               "ocean, Maxwell liquid (tau_M = 0.05)")]
# The same bodies under a perturber ten times lighter than T5's (its orbit kept): failures only.
LIGHT = "--set encounters.T5.perturber_mass=0.05 "
OCEAN_LIGHT_RUNS = [(f + "-m2-0.05", w, s + LIGHT, label + ", M2 = 0.05") for f, w, s, label in OCEAN_RUNS
                    if f != "ocean-L3-s1e-3"]


@full_table("ocean")
def ocean(p):
    """T5 on welded-L3 without an ocean and on ocean-L3 with shear fractions 0.01 and 0.001 and with a
    Maxwell liquid, 5-member ensembles (and with a perturber of M2 = 0.05 on T5's orbit, except at
    0.001): the relaxed body (probe, largest crust strain), the static
    tide's duration (validate's default for the body), h2 and l2 against
    TS72 with the body's own layers (the liquid with its springs' shear modulus) and with a fluid
    ocean, and per run the failures, their share on the subsatellite hemisphere, the median angle
    and the crack orientation."""
    runs = [r for r in OCEAN_RUNS if (p.work / r[0] / "T5_m0" / "analysis" / "summary.json").is_file()]
    lines = commands(*[f"tidalcrust run {w} {s}--set ensemble.members=5 --threads 1 --out {f}"
                       for f, w, s, _ in OCEAN_RUNS + OCEAN_LIGHT_RUNS],
                     *[f"tidalcrust validate {w} {s}--measure tide --threads 1 --out {f}" for f, w, s, _ in OCEAN_RUNS])
    lines += measured_line(p, *[p.work / f / "T5_m0" / "encounter.h5" for f, _, _, _ in runs])
    lines += validated_line(p, *[p.work / f / "validate" / "validation.json" for f, _, _, _ in runs
                                 if (p.work / f / "validate" / "validation.json").is_file()])
    bodies = []
    for folder, _, _, label in runs:
        record = p.inspect(p.work / folder / "body" / "relax.h5")["record"]
        tide = p.work / folder / "validate" / "validation.json"
        row = [label, f"{record['probe_failures']} ({sci(record['probe_max_shell_strain'])})",
               sci(record["max_shell_strain"])]
        if tide.is_file():
            v = p.load(tide)
            c = v["comparisons"]
            fluid_h = c.get("tide-fluid-ocean", {}).get("theory")
            fluid_l = c.get("tide-l2-fluid-ocean", {}).get("theory")
            row += [fixed(v["details"]["tide"]["duration"], 0), fixed(c["tide"]["measured"], 3), fixed(c["tide"]["theory"], 3),
                    "-" if fluid_h is None else fixed(fluid_h, 3), fixed(c["tide-l2"]["measured"], 3),
                    fixed(c["tide-l2"]["theory"], 3), "-" if fluid_l is None else fixed(fluid_l, 3),
                    fixed(c["tide-correlation"]["measured"], 3)]
        else:
            row += ["-"] * 8
        bodies.append(row)
    lines += table(["relaxed body", "probe failures (largest strain)", "largest crust strain relaxed",
                    "tide duration [t_grav]", "h2", "h2 TS72 own layers", "h2 TS72 fluid ocean", "l2", "l2 TS72 own layers",
                    "l2 TS72 fluid ocean", "crust strain correlation"], bodies) + [""]
    rows = []
    light = [r for r in OCEAN_LIGHT_RUNS if (p.work / r[0] / "T5_m0" / "analysis" / "summary.json").is_file()]
    for folder, _, _, label in runs + light:
        members = [p.load(m) for m in sorted((p.work / folder).glob("T5_m*/analysis/summary.json"))]
        failures = [m["failures"] for m in members]
        column = lambda key: [f[key] for f in failures]
        rows.append([label, str(len(members)), mean_sd_interval(column("count"), 1),
                     mean_sd_interval([100 * x for x in column("failed_area_fraction")], 2),
                     mean_sd_interval(column("hemisphere_fraction"), 3),
                     mean_sd_interval(column("median_angle_from_subsatellite_deg"), 1),
                     mean_sd_interval(column("concentricity"), 3),
                     mean_sd_interval(column("crack_rose_peak_deg"), 0),
                     sci(max(m["conservation"]["max_energy_error"] for m in members))])
    lines += table(["body", "members", "failed shell springs", "failed area [%]",
                    "share on the subsatellite hemisphere", "median angle [deg]", "concentricity",
                    "crack rose peak [deg]", "largest energy error (of 3/5 G M^2/R)"], rows)
    return lines


# The static tide of ocean-L3's floating shell on a Maxwell liquid (docs/ocean.md, "A Maxwell
# liquid"): tau_M and the tide's duration, h2 and l2 against the fluid ocean's.
MAXWELL_TIDES = [(3, 0.05, 30), (3, 0.05, 45), (3, 0.05, 60), (3, 0.05, 75), (3, 0.05, 90), (3, 0.02, 45),
                 (3, 0.2, 45), (3, 0.2, 90), (3, 1, 45), (4, 0.05, 60), (4, 0.05, 90)]


@full_table("ocean-maxwell")
def ocean_maxwell(p):
    """validate --measure tide on ocean-L3 with a Maxwell liquid, by tau_M and the tide's duration:
    h2 and l2 and their ratios to TS72 with a fluid ocean, h2 at two thirds of the run, the
    correlation of the crust springs' strain with the fitted degree-2 pattern and the shell's rms
    azimuthal displacement per unit of the tide's (the crust following the tide, not the liquid
    wandering)."""
    folder = lambda level, tau, d: f"ocean-L{level}-maxwell{tau:g}-d{d:g}"
    level_setting = lambda level: "" if level == 3 else f"--set resolution.shell_level={level} "
    done = [r for r in MAXWELL_TIDES if (p.work / folder(*r) / "validate" / "validation.json").is_file()]
    lines = commands(*[f"tidalcrust validate workflows/ocean-L3.toml --set ocean.maxwell_time={t:g} {level_setting(lv)}"
                       f"--measure tide --tide-duration {d:g} --threads 1 --out {folder(lv, t, d)}"
                       for lv, t, d in MAXWELL_TIDES])
    lines += measured_line(p, *[p.work / folder(*r) / "body" / "relax.h5" for r in done])
    lines += validated_line(p, *[p.work / folder(*r) / "validate" / "validation.json" for r in done])
    rows = []
    for level, tau, duration in done:
        v = p.load(p.work / folder(level, tau, duration) / "validate" / "validation.json")
        c, t = v["comparisons"], v["details"]["tide"]
        h, l = c["tide-fluid-ocean"], c["tide-l2-fluid-ocean"]
        rows.append([str(level), f"{tau:g}", f"{duration:g}", fixed(h["measured"], 3), fixed(h["ratio"], 3),
                     fixed(t["h2_at_two_thirds"] / h["theory"], 3), fixed(l["measured"], 3), fixed(l["ratio"], 3),
                     fixed(t["own_correlation"], 3), fixed(t["rms_azimuthal_displacement"], 3)])
    lines += table(["shell level", "tau_M [t_grav]", "tide [t_grav]", "h2", "h2 / fluid ocean", "h2 / fluid ocean at 2/3",
                    "l2", "l2 / fluid ocean", "crust strain vs own degree 2", "rms azimuthal"], rows)
    return lines


# ---------------------------------------------------------------- pages


def blocks(text):
    """{(kind, name): (first line index of the content, end marker line index)} of one page."""
    found, open_ = {}, None
    for n, line in enumerate(text.split("\n")):
        m = MARKER.match(line)
        if not m:
            continue
        kind, name, edge = m.groups()
        if edge == "begin":
            if open_:
                raise Failure(f"line {n + 1}: `{name}` begins inside `{open_[1]}`")
            open_ = (kind, name, n + 1)
        else:
            if not open_ or open_[:2] != (kind, name):
                raise Failure(f"line {n + 1}: end of `{name}` without its begin")
            if (kind, name) in found:
                raise Failure(f"line {n + 1}: `{name}` appears twice")
            found[(kind, name)] = (open_[2], n)
            open_ = None
    if open_:
        raise Failure(f"`{open_[1]}` is never ended")
    return found


def rewrite(text, kind, tables, known):
    """The page with every block of `kind` that `tables` holds replaced by it; the names it had."""
    lines = text.split("\n")
    spans = sorted(((s, e, name) for (k, name), (s, e) in blocks(text).items() if k == kind), reverse=True)
    for start, end, name in spans:
        if name not in known:
            raise Failure(f"unknown table `{name}` (no function makes it)")
        if name in tables:
            lines[start:end] = tables[name]
    return "\n".join(lines), {name for _, _, name in spans}


def pages_of(pages_dir):
    pages = sorted(Path(pages_dir).glob("*.md"))
    if not pages:
        raise Failure(f"{pages_dir}: no pages")
    return pages


def write_pages(pages_dir, kind, tables, verbose=True):
    seen = {}
    known = QUICK if kind == "quick" else FULL
    for page in pages_of(pages_dir):
        text = page.read_text()
        try:
            new, names = rewrite(text, kind, tables, known)
        except Failure as e:
            raise Failure(f"{page}: {e}")
        for name in names:
            if name in seen:
                raise Failure(f"table `{name}` is on two pages: {seen[name]} and {page}")
            seen[name] = page
        if new != text:
            page.write_text(new)
            if verbose:
                print(f"rewrote {page}")
    missing = sorted(set(known) - set(seen))
    if missing:
        raise Failure(f"no page holds the table(s) {', '.join(missing)}")


def differences(original_dir, regenerated_dir, kind):
    """One entry per table whose regenerated text differs: page, table, first differing line."""
    out = []
    for page in pages_of(original_dir):
        old, new = page.read_text(), (Path(regenerated_dir) / page.name).read_text()
        old_blocks, new_blocks = blocks(old), blocks(new)
        old_lines, new_lines = old.split("\n"), new.split("\n")
        for (k, name), (start, end) in sorted(old_blocks.items(), key=lambda kv: kv[1]):
            if k != kind:
                continue
            nstart, nend = new_blocks[(k, name)]
            a, b = old_lines[start:end], new_lines[nstart:nend]
            if a == b:
                continue
            i = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
            page_line = a[i] if i < len(a) else "(the table ends here)"
            made_line = b[i] if i < len(b) else "(the table ends here)"
            out.append(f"{page.name}: table `{name}` differs from what the program produces now; first difference "
                       f"at line {start + i + 1}:\n  page:    {page_line}\n  program: {made_line}")
    return out


def check(pages_dir, kind, tables, self_test):
    with tempfile.TemporaryDirectory(prefix="tidalcrust-results-") as tmp:
        copy = Path(tmp) / "results"
        shutil.copytree(pages_dir, copy)
        write_pages(copy, kind, tables, verbose=False)
        found = differences(pages_dir, copy, kind)
        for line in found:
            print(line)
        if found:
            how = "`make results-quick`" if kind == "quick" else "`tools/results_tables.py full ... --write`"
            print(f"{len(found)} table(s) differ: regenerate them with {how} and say in CHANGELOG.md what changed "
                  "the numbers and why")
            return 1
        print(f"all {len(tables)} {kind} tables of {pages_dir} are what the program produces now")
        if self_test:
            return self_check(pages_dir, copy, kind)
        return 0


def self_check(pages_dir, copy, kind):
    """Edit one digit of a table in the copy: the comparison must name that table and line."""
    for page in pages_of(copy):
        text = page.read_text()
        lines = text.split("\n")
        for (k, name), (start, end) in sorted(blocks(text).items(), key=lambda kv: kv[1]):
            for n in range(start, end):
                m = re.search(r"\d", lines[n]) if lines[n].startswith("|") and "---" not in lines[n] else None
                if not m:
                    continue
                digit = lines[n][m.start()]
                lines[n] = lines[n][:m.start()] + ("1" if digit != "1" else "2") + lines[n][m.end():]
                edited = Path(copy).parent / "edited"
                shutil.copytree(pages_dir, edited)
                (edited / page.name).write_text("\n".join(lines))
                found = differences(edited, copy, k)
                wanted = f"table `{name}` differs"
                if len(found) == 1 and wanted in found[0] and f"at line {n + 1}:" in found[0]:
                    print(f"self-check: a digit edited in `{name}` ({page.name} line {n + 1}) is reported")
                    return 0
                print(f"self-check FAILED: editing {page.name} line {n + 1} gave {found!r}")
                return 1
    print("self-check FAILED: no table line with a digit to edit")
    return 1


# ---------------------------------------------------------------- main


def has_fma():
    try:
        return any(" fma" in line for line in open("/proc/cpuinfo") if line.startswith("flags"))
    except OSError:
        return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("kind", choices=["quick", "full", "bench"])
    parser.add_argument("--exe", required=True, help="the tidalcrust executable")
    parser.add_argument("--source", default=Path(__file__).resolve().parent.parent, help="the repository")
    parser.add_argument("--pages", help="the folder of the pages (default SOURCE/docs/results)")
    parser.add_argument("--work", help="quick: run into this folder (default: a fresh temporary one); "
                                       "bench: run into FOLDER/bench (required)")
    parser.add_argument("--repeat", type=int, default=1, help="bench: runs of each benchmark (default 1)")
    parser.add_argument("--runs", help="full: the folder the runs were made into")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--write", action="store_true", help="rewrite the tables in the pages")
    mode.add_argument("--check", action="store_true", help="compare, do not write (exit 1 on a difference)")
    parser.add_argument("--no-self-check", action="store_true", help="--check without the edited-copy test")
    parser.add_argument("--only", action="append", default=[], metavar="NAME",
                        help="full: regenerate only this table (repeatable)")
    args = parser.parse_args()
    source = Path(args.source).resolve()
    pages = Path(args.pages).resolve() if args.pages else source / "docs" / "results"
    exe = Path(args.exe).resolve()
    if not exe.is_file():
        print(f"{exe}: no such executable", file=sys.stderr)
        return 2
    if args.kind == "bench":
        if not args.work or args.repeat < 1:
            print("results_tables.py: bench needs --work DIR and --repeat >= 1", file=sys.stderr)
            return 2
        try:
            run_benchmarks(Program(exe, source, Path(args.work).resolve()), args.repeat)
        except Failure as e:
            print(f"results_tables.py: {e}", file=sys.stderr)
            return 2
        return 0
    if not (args.write or args.check):
        print(f"results_tables.py: {args.kind} needs --write or --check", file=sys.stderr)
        return 2
    if args.kind == "quick" and not has_fma():
        print("SKIP: this CPU has no FMA; glibc's sin/cos/atan2 then round differently (docs/determinism.md), so the "
              "quick tables would not be the same bits")
        return 77
    try:
        if args.kind == "quick":
            tmp = None if args.work else tempfile.mkdtemp(prefix="tidalcrust-results-quick-")
            work = Path(args.work or tmp).resolve()
            work.mkdir(parents=True, exist_ok=True)
            try:
                p = Program(exe, source, work)
                print(f"running the quick workflows into {work} ...", flush=True)
                quick_runs(p)
                tables = {name: f(p) for name, f in QUICK.items()}
            finally:
                if tmp:
                    shutil.rmtree(tmp, ignore_errors=True)
        else:
            if not args.runs:
                raise Failure("full: --runs DIR is required")
            p = Program(exe, source, Path(args.runs).resolve())
            unknown = [name for name in args.only if name not in FULL]
            if unknown:
                raise Failure(f"--only: no table named {', '.join(unknown)}")
            tables = {name: f(p) for name, f in FULL.items() if not args.only or name in args.only}
        if args.write:
            write_pages(pages, args.kind, tables)
            return 0
        return check(pages, args.kind, tables, not args.no_self_check)
    except Failure as e:
        print(f"results_tables.py: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
