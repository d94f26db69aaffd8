#!/usr/bin/env python3
"""Run the examples of feps's manuals, so that the manuals cannot drift from the program.

Every fenced block of the manuals named in DOCS carries a marker, an HTML comment on the line
right before it (hidden in rendered Markdown) that says how it is checked; a block without one
fails, so a new example needs a marker too. An inline command may carry one as well, right
before its code span on the same line. A marker is

    <!-- check: KIND key=value ... [flag ...] -->

or the same spread over several lines, the lines after the first (up to `-->`) being its body:
records or code that the example needs but does not show. KINDs:

  deck      a complete deck: `feps DECK --check` accepts it. same-as=PATH: the block is that
            file's records (comments and blank lines aside).
  datain    a file holding only a DATAIN mesh: feps reports nodes=N and elements=M.
  records   records of a deck: base=PATH (a deck of the repository; before=TEXT cuts it at
            its first line starting with TEXT), then the body's records, then the block's
            (then the body's records after a line '---'), and `feps --check` accepts the whole. each: every record of the block on its own
            (alternatives, such as three MATERIAL records of one name). applied=fx,fy,fz:
            the applied force --check prints (to its 6 digits: 1e-5 of its largest component; with
            each, one triple per record separated by ';', '*' for none). run: run the deck
            too; h5=PATH@ATTR=VALUE;...: attributes of its results (VALUE a number or text,
            or empty for "exists"). stdout=REGEX: a line the run or check prints.
            files=NAME,...: files of test/data/docs beside the deck (for INCLUDE).
            in=PATH: the block's records are records of that deck too (an example said
            to be a deck's).
  excerpt   in=PATH: the records of the example (an inline code span, say) are records of
            that deck, in order.
  error     lines `feps: error: FILE:LINE: ...`: the body's first line is base=PATH, each
            further line the record that replaces line LINE of the base, in order. feps run on
            FILE (the base with that record, under the name the message gives) must exit 2
            and print exactly that line.
  usage     the usage lines of `feps --help`, word for word.
  command   a shell command (a block of them, or an inline code span), run by bash in a
            sandbox of the repository (its folders linked, input/ a real folder) with `feps`
            the program under test. check-only: --check added to every line that runs feps
            (a run too long here). status=N (default 0). stdout=REGEX,
            stderr=REGEX. only=REGEX: run only the lines that match.
            files=GLOB:COUNT: so many new files match GLOB afterwards.
  python    Python run in a temporary folder: h5=NAME:DECK first runs DECK into NAME; the
            body's lines are appended (assertions on what the block computed).
  h5-table  the table of docs/output-format.md right after the marker: every path it names
            exists in the results of decks covering every kind of field, with the shape
            (nnode, npoints, nelem, numbers) and `components` it gives, and the listed
            attributes of /summary, /steps/<NNNN>, /mesh/groups/<g> and /materials/<m>.
  xdmf-table the XDMF cell table right after the marker, against the XDMF files feps writes.
  gauss-table the table of integration points right after the marker (docs/output-format.md):
            each row's point count and its points, in the order the table gives, against
            test/reference/element_rules.py's integration_points (which test/cli/check_cli.sh holds to
            feps's own rows) and the points_per_element feps writes for the types run here.
  count     glob=GLOB n=N: so many files of the repository match GLOB (a folder's size that
            the text gives).
  none      not checked here; the rest of the marker says why.

Besides, every path of the repository that the manuals name (test/data/..., input/...,
scripts/..., docs/..., src/..., the benchmarks folder ../shared/...) must exist.

Usage: check_docs.py [--feps PATH] [--verbose]; exit 1 when an example fails.
"""
import argparse
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DOCS = ["README.md", "docs/input-format.md", "docs/output-format.md", "docs/performance.md",
        "docs/tradeoff.md"]
MARK = "<!-- check:"
KINDS = ("deck", "datain", "records", "excerpt", "count", "gauss-table", "error", "usage", "command", "python", "h5-table",
         "xdmf-table", "none")


class Example:
    """One marked example: where it is, its marker and its text."""

    def __init__(self, doc, line, kind, args, flags, body, text, table=None):
        self.doc, self.line, self.kind, self.args, self.flags = doc, line, kind, args, flags
        self.body, self.text, self.table = body, text, table

    @property
    def where(self):
        return f"{self.doc}:{self.line}"


def parse_marker(text):
    """KIND, {key: value}, {flags} of a marker's first line (after 'check:')."""
    words = shlex.split(text)
    if not words or words[0] not in KINDS:
        raise ValueError(f"unknown check kind {words[:1]} (kinds: {', '.join(KINDS)})")
    args, flags = {}, set()
    for w in words[1:]:
        if "=" in w and words[0] != "none":
            k, v = w.split("=", 1)
            args[k] = v
        else:
            flags.add(w)
    return words[0], args, flags


def examples(doc):
    """The examples of one manual, and the problems of its markers (unmarked blocks)."""
    lines = open(os.path.join(ROOT, doc), encoding="utf-8").read().split("\n")
    found, problems = [], []
    pending = None
    i = 0
    while i < len(lines):
        line = lines[i]
        inline = re.findall(r"<!-- check:(.*?)-->\s*`([^`]+)`", line)
        # CommonMark: a line that starts with '<!--' is an HTML block (the code span after the
        # marker would show as raw text), and an inline comment may not contain '--'.
        if inline and line.lstrip().startswith("<!--"):
            problems.append(f"{doc}:{i + 1}: an inline marker must not start its line (it would hide the code span)")
        for marker, code in inline:
            if "--" in marker:
                problems.append(f"{doc}:{i + 1}: an inline marker must not contain '--' (it would show as text)")
            kind, args, flags = parse_marker(marker)
            found.append(Example(doc, i + 1, kind, args, flags, [], code))
        if line.startswith(MARK) and not inline:
            start = i
            head = line[len(MARK):]
            body = []
            if "-->" in head:
                head = head.split("-->", 1)[0]
            else:
                i += 1
                while "-->" not in lines[i]:
                    body.append(lines[i])
                    i += 1
                if lines[i].split("-->", 1)[0].strip():
                    body.append(lines[i].split("-->", 1)[0])
            try:
                pending = (i + 1, *parse_marker(head), body)
            except ValueError as e:
                problems.append(f"{doc}:{start + 1}: {e}")
            i += 1
            continue
        fence = re.match(r"^```(\S*)", line)
        if fence:
            j = i + 1
            while not lines[j].startswith("```"):
                j += 1
            text = "\n".join(lines[i + 1:j]) + "\n"
            if pending and pending[0] == i:
                found.append(Example(doc, i + 1, pending[1], pending[2], pending[3], pending[4], text))
            else:
                problems.append(f"{doc}:{i + 1}: a fenced block without a '{MARK} KIND ... -->' line before it")
            pending = None
            i = j + 1
            continue
        if pending and line.startswith("|") and pending[1] in ("h5-table", "xdmf-table", "gauss-table") and pending[0] == i:
            j = i
            while j < len(lines) and lines[j].startswith("|"):
                j += 1
            rows = [[c.strip() for c in r.strip().strip("|").split("|")] for r in lines[i + 2:j]]
            found.append(Example(doc, i + 1, pending[1], pending[2], pending[3], pending[4], "", rows))
            pending = None
            i = j
            continue
        if pending and line.strip():
            problems.append(f"{doc}:{i}: the marker is not right before a fenced block or table")
            pending = None
        i += 1
    return found, problems


class Checker:
    def __init__(self, feps, tmp, verbose):
        self.feps, self.tmp, self.verbose = feps, tmp, verbose
        self.passed, self.failed, self.count = 0, 0, 0
        self.results = {}

    def run(self, args, cwd=None):
        p = subprocess.run(args, cwd=cwd or self.tmp, capture_output=True, text=True, timeout=120)
        return p.returncode, p.stdout, p.stderr

    def fresh(self):
        """An empty folder for one example."""
        self.count += 1
        d = os.path.join(self.tmp, f"ex{self.count}")
        os.makedirs(d)
        return d

    # -- decks -----------------------------------------------------------------------------
    def feps_check(self, deck, cwd, run=False):
        """--check (and with run, a run) of a deck: exit 0; the printed text."""
        rc, out, err = self.run([self.feps, deck, "--check"], cwd)
        if rc != 0:
            raise AssertionError(f"feps --check exits {rc}: {err.strip() or out[-300:]}")
        if run:
            rc, out2, err = self.run([self.feps, deck, "--output", "run.h5"], cwd)
            if rc != 0:
                raise AssertionError(f"feps exits {rc}: {err.strip()}")
            out += out2
        return out

    def check_deck(self, ex):
        d = self.fresh()
        open(os.path.join(d, "example.dat"), "w").write(ex.text)
        out = self.feps_check("example.dat", d)
        if "same-as" in ex.args:
            mine = records_of(ex.text)
            theirs = records_of(open(os.path.join(ROOT, ex.args["same-as"])).read())
            assert mine == theirs, f"not the records of {ex.args['same-as']}: " + first_difference(mine, theirs)
        return "accepted by --check" + (f", = {ex.args['same-as']}" if "same-as" in ex.args else "") \
            + f" ({number(out, 'nodes')} nodes)"

    def check_datain(self, ex):
        d = self.fresh()
        open(os.path.join(d, "example.datain"), "w").write(ex.text)
        rc, out, err = self.run([self.feps, "example.datain"], d)
        assert rc == 0, f"feps exits {rc}: {err.strip()}"
        got = (number(out, "nodes"), number(out, "elements"))
        want = (ex.args["nodes"], ex.args["elements"])
        assert got == want, f"{got[0]} nodes and {got[1]} elements, the text says {want[0]} and {want[1]}"
        return f"{got[0]} nodes, {got[1]} elements"

    def check_records(self, ex):
        base = open(os.path.join(ROOT, ex.args["base"])).read().split("\n")
        if "before" in ex.args:
            cut = next(i for i, l in enumerate(base) if l.startswith(ex.args["before"]))
            base = base[:cut]
        parts = split_records(ex.text) if "each" in ex.flags else [ex.text]
        applied = ex.args.get("applied", "").split(";") if "applied" in ex.args else [None] * len(parts)
        assert len(applied) == len(parts), f"{len(parts)} records, {len(applied)} applied= values"
        said = []
        for part, force in zip(parts, applied):
            d = self.fresh()
            for name in filter(None, ex.args.get("files", "").split(",")):
                shutil.copy(os.path.join(ROOT, "test/data/docs", name), d)
            before, after = (ex.body[:ex.body.index("---")], ex.body[ex.body.index("---") + 1:]) \
                if "---" in ex.body else (ex.body, [])
            deck = "\n".join(base + ["! --- the marker's context ---"] + before
                             + ["! --- the example ---", part, "! --- what uses it ---"] + after)
            open(os.path.join(d, "example.dat"), "w").write(deck)
            try:
                out = self.feps_check("example.dat", d, run="run" in ex.flags)
            except AssertionError as e:
                raise AssertionError(f"{e} [deck: {d}/example.dat]" if self.verbose else str(e))
            if force and force != "*":
                want = [float(v) for v in force.split(",")]
                got = [float(v) for v in re.search(r"^applied force +(\S+) +(\S+) +(\S+)", out, re.M).groups()]
                scale = max(abs(v) for v in want + got) or 1.0
                assert max(abs(a - b) for a, b in zip(got, want)) <= 1e-5 * scale, \
                    f"applied force {got}, the text says {want} ({part.strip()[:60]})"
                said.append(f"applied {force}")
            if "stdout" in ex.args:
                assert re.search(ex.args["stdout"], out, re.M), f"no line matching {ex.args['stdout']!r}"
            if "h5" in ex.args:
                said.append(check_attributes(os.path.join(d, "run.h5"), ex.args["h5"]))
        if "in" in ex.args:
            said.append(self.check_excerpt(ex))
        return f"{len(parts)} deck(s) on {os.path.basename(ex.args['base'])} accepted" + \
            (": " + "; ".join(said) if said else "")

    def check_excerpt(self, ex):
        mine = records_of(ex.text)
        theirs = records_of(open(os.path.join(ROOT, ex.args["in"])).read())
        at = 0
        for r in mine:
            assert r in theirs[at:], f"{r!r} is no record of {ex.args['in']}" + \
                (" after the one before" if r in theirs else "")
            at = theirs.index(r, at) + 1
        return f"records of {ex.args['in']}"

    def check_count(self, ex):
        got = len(glob.glob(os.path.join(ROOT, ex.args["glob"])))
        assert got == int(ex.args["n"]), f"{got} files {ex.args['glob']}, the text says {ex.args['n']}"
        return f"{got} files {ex.args['glob']}"

    def check_error(self, ex):
        head = dict(w.split("=", 1) for w in ex.body[0].split())
        base = open(os.path.join(ROOT, head["base"])).read().split("\n")
        expected = [l for l in ex.text.split("\n") if l.strip()]
        records = ex.body[1:]
        assert len(records) == len(expected), f"{len(expected)} messages, {len(records)} records in the marker"
        for want, record in zip(expected, records):
            m = re.match(r"feps: error: (.+?):(\d+):", want)
            name, line = m.group(1), int(m.group(2))
            d = self.fresh()
            deck = list(base)
            deck[line - 1] = record.strip()
            os.makedirs(os.path.join(d, os.path.dirname(name)) or d, exist_ok=True)
            open(os.path.join(d, name), "w").write("\n".join(deck))
            rc, out, err = self.run([self.feps, name], d)
            assert rc == 2 and err.strip() == want.strip(), \
                f"exit {rc}, printed {err.strip()!r}; the text says exit 2 and {want.strip()!r}"
            assert not os.path.exists(os.path.join(d, os.path.splitext(name)[0] + ".h5")), "a result file"
        return f"{len(expected)} message(s) as printed, exit 2, no result file"

    def check_usage(self, ex):
        rc, out, err = self.run([self.feps, "--help"])
        assert rc == 0, f"--help exits {rc}"
        usage = out.split("usage:", 1)[1].split("\n\n", 1)[0].split()
        assert ex.text.split() == usage, f"--help says: {' '.join(usage)}"
        return "= feps --help"

    # -- commands --------------------------------------------------------------------------
    def sandbox(self):
        """A folder that looks like the repository (and ../shared beside it) to a command."""
        d = self.fresh()
        work = os.path.join(d, "feps")
        os.makedirs(os.path.join(work, "input"))
        for name in os.listdir(ROOT):
            if name not in ("input", "build", ".git", "results"):
                os.symlink(os.path.join(ROOT, name), os.path.join(work, name))
        for name in os.listdir(os.path.join(ROOT, "input")):
            os.symlink(os.path.join(ROOT, "input", name), os.path.join(work, "input", name))
        shared = os.path.join(os.path.dirname(ROOT), "shared")
        if os.path.isdir(shared):
            os.symlink(shared, os.path.join(d, "shared"))
        return work

    def check_command(self, ex):
        work = self.sandbox()
        lines = [l for l in ex.text.split("\n") if l.strip() and not l.lstrip().startswith("#")]
        if "only" in ex.args:
            lines = [l for l in lines if re.search(ex.args["only"], l)]
        if "check-only" in ex.flags:                     # a run too long here: its --check
            lines = [re.sub(r"(^|&& *)(feps .*?)(\s+#.*)?$", lambda m: m.group(1) + m.group(2) + " --check", l)
                     for l in lines]
        script = "set -e\nfeps() { \"$FEPS\" \"$@\"; }\n" + "\n".join(lines) + "\n"
        env = dict(os.environ, FEPS=self.feps)
        # files a command leaves are counted as new ones: the sandbox links the working tree's
        # own files (a modelB.h5 of the README's main job, say), which are not the command's
        before = set(glob.glob(os.path.join(work, ex.args["files"].rsplit(":", 1)[0]))) if "files" in ex.args else set()
        p = subprocess.run(["bash", "-c", script], cwd=work, capture_output=True, text=True, env=env, timeout=120)
        want = int(ex.args.get("status", 0))
        assert p.returncode == want, f"exit {p.returncode} (expected {want}): {(p.stderr or p.stdout).strip()[-400:]}"
        for stream, text in (("stdout", p.stdout), ("stderr", p.stderr)):
            if stream in ex.args:
                assert re.search(ex.args[stream], text, re.M), \
                    f"no line matching {ex.args[stream]!r} in its {stream}: {text[-400:]}"
        said = f"exit {want}"
        if "files" in ex.args:
            pattern, count = ex.args["files"].rsplit(":", 1)
            got = len(set(glob.glob(os.path.join(work, pattern))) - before)
            assert got == int(count), f"{got} files {pattern}, expected {count}"
            said += f", {count} files {pattern}"
        return said

    def check_python(self, ex):
        d = self.fresh()
        if "h5" in ex.args:
            name, deck = ex.args["h5"].split(":", 1)
            rc, out, err = self.run([self.feps, os.path.join(ROOT, deck), "--quiet", "--output", name], d)
            assert rc == 0, f"feps {deck} exits {rc}: {err.strip()}"
        code = ex.text + "\n".join(ex.body) + "\n"
        p = subprocess.run([sys.executable, "-c", code], cwd=d, capture_output=True, text=True, timeout=120)
        assert p.returncode == 0, (p.stderr or p.stdout).strip()[-600:]
        return f"runs{' with its assertions' if ex.body else ''}"

    # -- results files ---------------------------------------------------------------------
    def result(self, deck):
        """The results file of a deck of the repository (run once)."""
        if deck not in self.results:
            d = self.fresh()
            path, *change = deck.split("|")
            out = os.path.join(d, os.path.splitext(os.path.basename(path))[0] + ".h5")
            text = open(os.path.join(ROOT, path)).read()
            if change:
                assert change[0] in text, f"{path} has no {change[0]}"
                text = text.replace(change[0], change[1])
            open(os.path.join(d, "deck.dat"), "w").write(text)
            rc, _, err = self.run([self.feps, "deck.dat", "--quiet", "--output", out], d)
            assert rc == 0, f"feps {deck} exits {rc}: {err.strip()}"
            self.results[deck] = out
        return self.results[deck]

    def check_h5_table(self, ex):
        import h5py
        files = [h5py.File(self.result(d)) for d in LAYOUT_DECKS]
        checked = 0
        for row in ex.table:
            path, shape, content = row[0].strip("`"), row[1], row[2]
            if path in ("/summary", "/materials/<name>", "/steps/<NNNN>", "/constraints/<kkkk>"):
                checked += check_attribute_row(files, path, content)
                continue
            datasets = [(f, name) for f in files for name in expand(f, path)]
            assert datasets, f"no file has {path}"
            comps = [c for c in re.findall(r"`([a-z_0-9]+(?: [a-z_0-9]+)+|axial_force)`", content)
                     if "components" in content or path.startswith("/steps")]
            comps += re.findall(r'`components = "([^"]+)"`', content)
            for f, name in datasets:
                ds = f[name]
                check_shape(f, name, ds, shape, content)
                if comps:
                    got = text(ds.attrs["components"])
                    assert got in comps, f"{name}: components {got!r}, the table says {comps}"
                checked += 1
            if path == "/mesh/groups/<group>/connectivity":
                checked += check_group_attributes(files, content)
            if path.endswith("/reaction_nodal"):     # "written when some node has a nodal system"
                assert "written when some node has a nodal system" in content
                cube = files[LAYOUT_DECKS.index("test/data/cube.dat")]
                assert not any("reaction_nodal" in cube["steps"][s] for s in cube["steps"]), \
                    "reaction_nodal written for a model without nodal systems"
        # "Every results dataset has a string attribute components"
        for f in files:
            for s in f["steps"]:
                def visit(name, obj):
                    if hasattr(obj, "shape"):
                        assert "components" in obj.attrs, f"/steps/{s}/{name} has no components"
                f["steps"][s].visititems(visit)
        # "iterations (... 1 in a linear model ...)": the cube is linear
        cube = files[LAYOUT_DECKS.index("test/data/cube.dat")]
        assert all(cube["steps"][s].attrs["iterations"] == 1 for s in cube["steps"])
        return f"{len(ex.table)} rows, {checked} datasets/attributes in {len(files)} results files"

    def check_xdmf_table(self, ex):
        cells = {}
        for deck in LAYOUT_DECKS:
            h5 = self.result(deck)
            import h5py
            with h5py.File(h5) as f:
                types = {g: text(f[f"mesh/groups/{g}"].attrs["element_type"]) for g in f["mesh/groups"]}
            xmf = open(os.path.splitext(h5)[0] + ".xmf").read()
            for grid, topo in re.findall(r'<Grid Name="([^"]+)"[^>]*>\s*(?:<Time [^>]*/>\s*)?<Topology ([^>]*)>', xmf):
                group = next((g for g in types if grid == g or grid.startswith(g + "_") or grid.endswith("_" + g)), None)
                if group:
                    cells[types[group]] = topo
        seen = 0
        for row in ex.table:
            names = re.findall(r"`([a-z0-9-]+)`", row[0])
            span = re.fullmatch(r"`([a-z]+)(\d)` \.\.\. `\1(\d)`", row[0])   # `bar2` ... `bar5`
            if span:
                names = [span.group(1) + str(k) for k in range(int(span.group(2)), int(span.group(3)) + 1)]
            cell = re.findall(r"`([A-Za-z_0-9]+)`", row[1])[0]
            for name in names + [n + "-nodal" for n in names if n.startswith("interface-")]:
                if name in cells:
                    topo = cells[name]
                    got = re.search(r'TopologyType="([^"]+)"', topo).group(1)
                    assert got == cell, f"{name}: XDMF cell {got}, the table says {cell}"
                    nodes = re.search(r'NodesPerElement="(\d+)"', topo)
                    if nodes:
                        want = re.findall(r"\d+", row[2])
                        assert nodes.group(1) in want or row[2].startswith("all"), \
                            f"{name}: NodesPerElement {nodes.group(1)}, the table says {row[2]}"
                    seen += 1
        assert seen >= 18, f"only {seen} element types of the table met in the results ({sorted(cells)})"
        return f"{seen} element types against the XDMF files feps wrote ({', '.join(sorted(cells))})"

    def check_gauss_table(self, ex):
        import h5py
        import numpy as np
        sys.path.insert(0, os.path.join(ROOT, "test", "reference"))
        import element_rules as er
        ppe_run = {}                                       # points_per_element feps wrote
        for deck in LAYOUT_DECKS:
            with h5py.File(self.result(deck)) as f:
                last = max(f["steps"], key=int)
                for kind in f["steps"][last]:
                    if kind in ("stress", "interface", "bar"):
                        for g in f["steps"][last][kind]:
                            t = text(f[f"mesh/groups/{g}"].attrs["element_type"])
                            ppe_run[t] = int(f["steps"][last][kind][g].attrs["points_per_element"])
        nodes_of, points_of, checked = {}, {}, []
        for row in ex.table:
            names = re.findall(r"`([a-z0-9-]+)`", row[0])
            span = re.match(r"`([a-z]+)(\d)` \.\.\. `\1(\d)`", row[0])
            if span:
                names = [span.group(1) + str(k) for k in range(int(span.group(2)), int(span.group(3)) + 1)]
            rule, order = row[2], row[3]
            for name in names:
                same = re.match(r"as ([a-z0-9-]+)", row[1])
                nodes_of[name] = nodes_of[same.group(1)] if same else gauss_nodes(row[1], name, nodes_of)
                want = gauss_order(order, rule, name, nodes_of[name], points_of)
                points_of[name] = want
                p = int(re.search(r"(\d+)$", rule).group(1)) if not name.startswith("bar") else int(name[3:]) - 1
                got, _ = er.integration_points(name)
                assert len(got) == p == len(want), f"{name}: {len(got)} points in the reference, the table says {p}"
                assert np.allclose(got, want, atol=1e-12), f"{name}: the reference's points {got.tolist()}, the table's {want.tolist()}"
                if name in ppe_run:
                    assert ppe_run[name] == p, f"{name}: feps writes {ppe_run[name]} points per element, the table says {p}"
                checked.append(name)
        return f"{len(checked)} element types; points_per_element as feps wrote it for {len(set(checked) & set(ppe_run))}"

    # -- driver ----------------------------------------------------------------------------
    def check(self, ex):
        if ex.kind == "none":
            return None
        try:
            said = getattr(self, "check_" + ex.kind.replace("-", "_"))(ex)
        except (AssertionError, subprocess.TimeoutExpired, KeyError, StopIteration, OSError) as e:
            self.failed += 1
            print(f"  FAIL {ex.where} {ex.kind}: {type(e).__name__ + ': ' if not isinstance(e, AssertionError) else ''}{e}")
            return False
        self.passed += 1
        print(f"  ok   {ex.where} {ex.kind}: {said}")
        return True


# The decks whose results cover every dataset of docs/output-format.md's table: solids, bars with
# prestress (prestress_block), 3D interfaces (block_shear), nodal cylindrical systems (lame_hex20:
# reaction_nodal, hex20), plane strain with line interfaces (contact_2d); and, for the XDMF
# table, more element types: curved bars of 3, 4 and 5 nodes (Tables 2.2 and 2.3), and decks
# with one type changed ("deck|OLD|NEW"): hex8b, hex20r, tri6-6 and -nodal interfaces.
LAYOUT_DECKS = ["test/data/prestress_block.dat", "test/data/block_shear.dat", "test/data/lame_hex20.dat", "test/data/lists_lame_hex20.dat",
                "test/data/contact_2d.dat", "test/data/cube.dat", "input/verification/table2_2_bar3.dat",
                "input/verification/table2_3_bar4.dat", "input/verification/table2_2_bar5.dat",
                "test/data/lame_hex8.dat|TYPE=hex8,|TYPE=hex8b,", "test/data/cantilever_hex20.dat|TYPE=hex20,|TYPE=hex20r,",
                "test/data/contact_2d.dat|TYPE=interface-line3,|TYPE=interface-line3-nodal,",
                "test/data/block_shear.dat|TYPE=interface-quad4,|TYPE=interface-quad4-nodal,",
                "test/data/contact_2d.dat|TYPE=tri6,|TYPE=tri6-6,",
                "test/data/friction_pull.dat",   # LINESEARCH=energy: /summary line_searches
                "test/data/bending_hex20.dat",   # FIELDS, all, nodal_stress, nodal_principal
                "test/data/beam_point_state.dat",   # FIELDS, point_state
                # tet10, with the cylindrical stresses at the points and the nodes
                "test/data/lame_tet10.dat|PRESSURE, bore, VALUE=10.|PRESSURE, bore, VALUE=10.\n"
                "FIELDS, all, stress_cyl, nodal_stress_cyl",
                "test/data/lame_tet4.dat", "test/data/lame_wedge6.dat", "test/data/lame_wedge15.dat",
                "test/data/block_contact_nodal.dat"]   # FIELDS, interface, nodal_interface


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def expand(f, pattern):
    """The names in file f that a path of the table (with <NNNN>, <group>, <kind> ...) stands for."""
    parts = pattern.strip("/").split("/")
    names = [""]
    for part in parts:
        new = []
        for n in names:
            g = f[n] if n else f
            if not hasattr(g, "keys"):
                continue
            if part.startswith("<"):
                new += [f"{n}/{k}" if n else k for k in g.keys()]
            elif part in g:
                new.append(f"{n}/{part}" if n else part)
        names = new
    return [n for n in names if hasattr(f[n], "shape")]


def check_shape(f, name, ds, shape, content):
    import numpy as np
    """A dataset's shape against the table's 'nnode x 3', 'npoints x 6', 'nelem x k' ..."""
    nnode = f["mesh/coordinates"].shape[0]
    dims = [s.strip() for s in shape.split(" x ")]
    rows, cols = ds.shape
    group = name.split("/")[-2] if name.endswith(("connectivity", "topology", "points", "point_weights", "element_ids")) \
        else name.split("/")[-1]
    conn = f[f"mesh/groups/{group}/connectivity"] if f"mesh/groups/{group}/connectivity" in f else None
    if dims[0] == "nnode":
        assert rows == nnode, f"{name}: {rows} rows, nnode = {nnode}"
    elif dims[0] == "nelem":
        assert conn is not None and rows == conn.shape[0], f"{name}: {rows} rows, not nelem"
    elif dims[0] == "npoints":
        ppe = int(ds.attrs["points_per_element"])
        assert rows == conn.shape[0] * ppe, f"{name}: {rows} rows, nelem x points_per_element = {conn.shape[0] * ppe}"
    two_d = "interface" in name and "2D" in content and np.ptp(f["mesh/coordinates"][:, 2]) == 0
    if dims[1].isdigit():
        want = int(dims[1])
        if two_d:
            want = int(re.search(r"2D[^:]*: npoints x (\d)", content).group(1))
        assert cols == want, f"{name}: {cols} columns, the table says {want}"
    elif dims[1] == "k":
        assert cols == conn.shape[1]
    elif dims[1] == "c":
        etype = text(f[f"mesh/groups/{group}"].attrs["element_type"])
        assert cols == (conn.shape[1] // 2 if etype.startswith("interface") else conn.shape[1]), f"{name}: {cols} columns"


def check_attribute_row(files, path, content):
    """The attributes a row of the table lists (backticked lower-case names) are there."""
    if path == "/summary":
        # the attribute names it lists; not the values of `analysis` and `solver`, nor
        # lu_min_rcond (only after an LU factorization), nor the ranks' (only under MPI:
        # test/cli/check_mumps.sh)
        names = [n for n in re.findall(r"`([a-z_]+)`", content)
                 if n not in ("linear", "nonlinear", "cholmod", "skyline", "mumps", "lu_min_rcond", "ranks",
                              "rank_memory_mb", "rank_factorization_time")]
        # only when a stage ran with LINESEARCH=energy: both or neither, and some file has them
        searched = ("line_searches", "line_search_evaluations")
        # only with --mixed-precision (these decks run without; check_cli.sh runs one with it)
        mixed = ("single_precision_factors", "test_solve_error", "precision_fallbacks")
        for f in files:
            missing = [n for n in names if n not in f["summary"].attrs and n not in searched + mixed]
            assert not missing, f"/summary lacks {missing}"
            assert len({n in f["summary"].attrs for n in searched}) == 1, f"/summary has one of {searched}"
            assert len({n in f["summary"].attrs for n in mixed}) == 1, f"/summary has some of {mixed}"
        assert any(searched[0] in f["summary"].attrs for f in files), f"no file has {searched}"
        return len(names)
    if path == "/constraints/<kkkk>":
        # every attribute the row lists (`node` only on a LIST row's), on every record of every
        # file, and the records numbered 0001, 0002, ... in the deck's order
        names = [n for n in re.findall(r"`([a-z_]+)`", content)
                 if n not in ("fix", "displace", "release", "node", "file")]
        seen = 0
        for f in files:
            keys = sorted(f["constraints"]) if "constraints" in f else []
            assert keys == [f"{k:04d}" for k in range(1, len(keys) + 1)], f"/constraints: {keys}"
            for k in keys:
                attrs = f["constraints"][k].attrs
                assert all(n in attrs for n in names), f"/constraints/{k}: {list(attrs)}, the table lists {names}"
                assert text(attrs["kind"]) in ("fix", "displace", "release"), f"/constraints/{k}: kind"
                seen += 1
        assert seen, "no file has /constraints"
        return len(names)
    if path == "/steps/<NNNN>":
        names = ("load_factor", "iterations", "residual")
        for f in files:
            for s in f["steps"]:
                assert all(n in f["steps"][s].attrs for n in names), f"/steps/{s}: {list(f['steps'][s].attrs)}"
        for f in files:
            for s in f["steps"]:
                assert re.fullmatch(r"\d{4,}", s) and s == f"{int(s):04d}", f"step name {s}"
        return len(names)
    if path == "/materials/<name>":
        kinds = set(re.findall(r"`(elastic|matsuoka|interface|bar)`", content))
        seen = set()
        for f in files:
            for m in f["materials"]:
                k = text(f["materials"][m].attrs["kind"])
                assert k in kinds, f"/materials/{m}: kind {k!r}, the table says one of {sorted(kinds)}"
                seen.add(k)
        return len(seen)
    return 0


def check_group_attributes(files, content):
    names = ["element_type", "material", "point_state_bytes", "point_state_bytes_per_element"]
    for n in names:
        assert f"`{n}`" in content, f"the table no longer names {n}"
    count = 0
    for f in files:
        for g in f["mesh/groups"]:
            a = f["mesh/groups"][g].attrs
            assert all(n in a for n in names), f"/mesh/groups/{g}: {list(a)}"
            count += 1
    return count


def tuples(text, a=None):
    """The points '(x, y)' or '(x,y,z)' of a text, fractions and 'a' (as in 1-2a) allowed."""
    out = []
    for t in re.findall(r"\(([-+0-9./a, ]+)\)", text):
        parts = [s.strip() for s in t.split(",")]
        if not all(re.fullmatch(r"[-+0-9./a]+", s) for s in parts) or len(parts) < 2:
            continue
        out.append([eval(re.sub(r"(\d)a", r"\1*a", s), {"a": a}) for s in parts])
    return out


def gauss_nodes(text, name, known):
    """Natural coordinates of the nodes a row of the table gives (for 'in node order')."""
    if name.startswith("interface-line"):
        return [[float(v)] for v in re.search(r"s1 = ([-+0-9, ]+)", text).group(1).replace(" ", "").split(",") if v]
    corners = known.get("interface-quad4", []) if "corners as quad4" in text else []
    return corners + tuples(text)


def gauss_order(order, rule, name, nodes, known):
    """The points of a row, in the order its last column gives."""
    import numpy as np
    g = {2: [-1 / 3 ** 0.5, 1 / 3 ** 0.5], 3: [-0.6 ** 0.5, 0.0, 0.6 ** 0.5]}
    n = re.match(r"(\d)(?:x\d)* Gauss", rule)
    same = re.fullmatch(r"as ([a-z0-9-]+)", order)
    if same:
        return known[same.group(1)]
    if "fastest" in order:                                 # tensor product, first coordinate fastest
        dims = rule.split()[0].count("x") + 1
        grids = np.meshgrid(*([g[int(n.group(1))]] * dims), indexing="ij")
        return np.column_stack([x.ravel(order="F") for x in grids])
    if order.startswith("ascending s1"):
        return np.array(g[int(n.group(1))])[:, None]
    if order.startswith("ascending s:"):
        return np.polynomial.legendre.leggauss(int(name[3:]) - 1)[0][:, None]
    if "with a =" in order:
        a = [float(v) for v in re.findall(r"a = ([0-9.]+)", order)]
        head = order.split(" with ")[0]
        return np.array(tuples(head, a[0]) + tuples(head, a[1]))
    if m := re.match(r"the (\d) lower nodes in node order", order):
        pts = nodes[:int(m.group(1))] + (tuples(order.split("then the centre")[1]) if "centre" in order else [])
        return np.array(pts, dtype=float)
    if m := re.match(r"nodes ([\d, ]+)$", order):
        return np.array([nodes[int(i) - 1] for i in m.group(1).split(",")], dtype=float)
    if order.startswith("node order:"):
        return np.array([[float(v)] for v in order.split(":")[1].split(",")])
    return np.array(tuples(order), dtype=float)


def check_attributes(path, spec):
    """h5=PATH@ATTR=VALUE;... against a results file."""
    import h5py
    with h5py.File(path) as f:
        for item in spec.split(";"):
            where, pair = item.split("@")
            name, _, want = pair.partition("=")
            attrs = f[where].attrs
            assert name in attrs, f"{where} has no attribute {name} ({sorted(attrs)})"
            if want:
                got = attrs[name]
                try:
                    ok = float(got) == float(want) and not isinstance(got, (bytes, str))
                except (TypeError, ValueError):
                    ok = text(got) == want
                assert ok, f"{where}@{name} = {got!r}, the text says {want}"
    return f"h5 {spec}"


def records_of(text):
    """The records of a deck: comments and blank lines dropped, spaces trimmed."""
    out = []
    for line in text.split("\n"):
        line = line.split("!", 1)[0].strip()
        if line:
            out.append(line)
    return out


def first_difference(a, b):
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            return f"record {i + 1}: {x!r} against {y!r}"
    return f"{len(a)} records against {len(b)}"


def split_records(text):
    """The records of a block, each with its continuation lines (those starting with a digit,
    a sign or a point)."""
    out = []
    for line in text.split("\n"):
        if not line.strip():
            continue
        if out and re.match(r"\s*[0-9+\-.]", line):
            out[-1] += "\n" + line
        else:
            out.append(line)
    return out


def number(out, label):
    m = re.search(rf"^{label} +(\S+)$", out, re.M)
    return m.group(1) if m else None


def missing_paths(doc):
    """The paths of the repository (or of ../shared) that a manual names and that do not exist."""
    out = []
    fenced = False
    for n, line in enumerate(open(os.path.join(ROOT, doc), encoding="utf-8"), 1):
        if line.startswith("```"):
            fenced = not fenced
        if fenced or line.startswith("<!-- check:"):    # examples: their markers check them
            continue
        for path, after in re.findall(r"(?<![\w/.])((?:\.\./shared|test/data|input|scripts|docs|src|app)/[\w./-]*\w)(.?)",
                                      line):
            if after in "*<{" and after:                  # a pattern such as scripts/make_*.py
                continue
            if not os.path.exists(os.path.join(ROOT, path)):
                out.append(f"{doc}:{n}: {path} does not exist")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--feps", default=os.environ.get("FEPS"), help="the program (default $FEPS)")
    ap.add_argument("--verbose", action="store_true", help="keep the temporary folder, name it")
    a = ap.parse_args()
    if not a.feps:
        ap.error("--feps (or $FEPS) names the program")
    feps = os.path.abspath(a.feps)
    all_examples, problems = [], []
    for doc in DOCS:
        found, bad = examples(doc)
        all_examples += found
        problems += bad + missing_paths(doc)
    tmp = tempfile.mkdtemp(prefix="check_docs_")
    c = Checker(feps, tmp, a.verbose)
    try:
        for p in problems:
            c.failed += 1
            print(f"  FAIL {p}")
        for ex in all_examples:
            c.check(ex)
    finally:
        if a.verbose:
            print(f"(kept {tmp})")
        else:
            shutil.rmtree(tmp, ignore_errors=True)
    skipped = sum(ex.kind == "none" for ex in all_examples)
    print(f"check_docs: {c.passed} examples passed, {c.failed} failed, {skipped} marked as not checked")
    return 1 if c.failed else 0


if __name__ == "__main__":
    sys.exit(main())
