"""What the LAMMPS tests read: proto/lammps.md's fenced blocks, and the thermo output of a log.

blocks(doc, tag): the text of each block fenced as ```TAG (a language and its marks: "sh",
"lammps 3d"); commands(doc, tag): their lines, one command each.
thermo_values(log, column): {step: value} of a thermo keyword as the log prints it, the first
value of a step printed twice (the last row of one run, the first of the next).
test_arguments(description): the command line of the tests that run the page's blocks:
--fnet-analyze, --lmp (default lmp), --doc (proto/lammps.md), --workdir.
"""
import argparse
import re


def blocks(doc, tag):
    return re.findall(r"```" + tag + r"\n(.*?)```", doc, re.S)


def commands(doc, tag):
    return [l for b in blocks(doc, tag) for l in b.splitlines() if l.strip()]


def thermo_values(log, column):
    printed, header = {}, None
    for l in open(log):
        w = l.split()
        if w[:1] == ["Step"]:
            header = w
        elif l.startswith("Loop time"):
            header = None
        elif header and column in header and len(w) == len(header):
            printed.setdefault(int(w[0]), float(w[header.index(column)]))
    return printed


def test_arguments(description):
    ap = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fnet-analyze", required=True)
    ap.add_argument("--lmp", default="lmp")
    ap.add_argument("--doc", required=True)
    ap.add_argument("--workdir", required=True)
    return ap.parse_args()
