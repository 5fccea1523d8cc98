#!/usr/bin/env python3
"""Summarises what PoCL's loop vectoriser did with each kernel, from the remarks that
POCL_VECTORIZER_REMARKS=1 prints while PoCL compiles (stderr of a run with an empty
POCL_CACHE_DIR):

    POCL_VECTORIZER_REMARKS=1 POCL_CACHE_DIR=$(mktemp -d) finflex bench ... 2> remarks.txt
    python3 docs/tools/vectorizer_remarks.py remarks.txt [more.txt ...]

Lines "== <name>" in the file (scripts/device/run.sh remarks writes one before each
run) start a section: the verdicts are grouped by section and kernel.

PoCL compiles a kernel into work-group functions whose loops run its work-items; the
remarks name the work-group function ('_pocl_kernel_<name>_workgroup') before the loop
vectoriser's verdicts on its loops ("vectorized loop (vectorization width: 8, ...)",
"loop not vectorized: <reason>"). Prints, per kernel, each verdict and how many times
it was given (once per work-group function and loop)."""
import collections
import re
import sys

KERNEL = re.compile(r"_pocl_kernel_([A-Za-z0-9_]+?)_workgroup")
VERDICT = re.compile(r"^(vectorized loop \(vectorization width: \d+[^)]*\)|loop not vectorized(: .*)?)$")


def remarks(text):
    # PoCL 3.1 prints remarks back to back, PoCL 5 one a line: split on the location.
    for piece in re.split(r"<unknown>:0:0: |\n", text):
        piece = piece.strip()
        if piece:
            yield piece


def printable(counts):
    """LLVM follows each reasoned verdict with a bare "loop not vectorized": shown
    only where no reason was given."""
    reasoned = any(v.startswith("loop not vectorized:") for v in counts)
    return [(v, n) for v, n in counts.items() if not (reasoned and v == "loop not vectorized")]


def summarise(paths):
    verdicts = collections.OrderedDict()
    for path in paths:
        kernel = None
        section = path
        with open(path, errors="replace") as f:
            for remark in remarks(f.read()):
                if remark.startswith("== "):
                    section, kernel = remark[3:], None
                    continue
                found = KERNEL.search(remark)
                if found:
                    kernel = found.group(1)
                    verdicts.setdefault((section, kernel), collections.Counter())
                    continue
                # The reason's detail ("Unknown data dependence.") follows on its own.
                verdict = VERDICT.match(remark.split(" Use #pragma")[0].rstrip("."))
                if verdict and kernel:
                    verdicts[(section, kernel)][verdict.group(1)] += 1
    return verdicts


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for (section, kernel), counts in summarise(sys.argv[1:]).items():
        print("%s: %s" % (section, kernel))
        if not counts:
            print("    (no loop vectoriser remark)")
        for verdict, count in printable(counts):
            print("    %dx %s" % (count, verdict))


if __name__ == "__main__":
    main()
