"""The command line: ``python -m whittaker_teach derive sledge``.

Commands::

    list                          the built-in examples
    derive NAME [--latex] [--coordinate Q] [--direction {1,-1}]
                                  every step of the paper for a built-in system,
                                  each with its paper number and its check
    bench derivation [--repeat N] fresh-process time of the whole derivation with
                                  verification, against sympy.physics.mechanics
    bench derivation --scale [--n 2..8] [--family F] [--no-memory] [--repeat N]
                                  the same for families of n coordinates: a table of
                                  reduce, verify and peer times and peak memory;
                                  --family chain, rotors, coins or all: families of
                                  vehicles against LagrangesMethod and KanesMethod
    bench numerics [--quick] [--json FILE] [--csv FILE] [--plot FILE] [--quiet]
                                  speed against error: the full, reduced and exact
                                  models of the sledge (whittaker_teach.numerics)
    grade --exercise ID --roster ROSTER.csv SUBMISSIONS... --out grades.csv
          [--canvas GRADEBOOK.csv] [--moodle WORKSHEET.csv] [--feedback DIR]
                                  run the students' exercise notebooks, each in a
                                  fresh confined kernel, match each to one student
                                  of the roster, and write their grades, also into
                                  the LMS's own files (whittaker_teach.grading)
"""

import argparse
import sys


def _list(args):
    from .examples import catalogue
    for e in catalogue():
        print(f"{e.name:18s} {e.description}  (q_eps = {e.coordinate})")
    return 0


def _derive(args):
    from .errors import ModelError
    from .examples import get
    try:
        ex = get(args.name)
        red = ex.build().reduce(args.coordinate or ex.coordinate, args.direction)
    except ModelError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    red.show(latex=args.latex)
    checks = [s.check for s in red.steps if s.check]
    if ex.name == "sledge":
        from .examples import section3
        sec3 = section3(args.direction, reduction=red)
        print()
        sec3.show(latex=args.latex)
        checks += [s.check for s in sec3 if s.check]
    from .steps import Report
    report = Report(checks)
    print()
    import textwrap
    from .render import terminal_width
    print(textwrap.fill(report.summary(), terminal_width()))
    return 0 if report.ok else 1


def _bench(args):
    if args.what == "numerics":
        from .numerics.work_precision import main as numerics
        return numerics(args)
    from .bench import main
    return main(args)


def _grade(args):
    from .grading.run import main
    return main(args)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m whittaker_teach",
                                     description="Mei (1983): the generalized Whittaker "
                                     "equations, derived and checked step by step.")
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("list", help="list the built-in examples").set_defaults(func=_list)
    d = sub.add_parser("derive", help="print every step of the paper for a built-in system")
    d.add_argument("name", help="a built-in example (see 'list')")
    d.add_argument("--latex", action="store_true", help="print LaTeX instead of Unicode")
    d.add_argument("--coordinate", help="the coordinate q_eps that replaces time")
    d.add_argument("--direction", type=int, choices=(1, -1), default=1,
                   help="the sign of qdot_eps (default +1)")
    d.set_defaults(func=_derive)
    b = sub.add_parser("bench", help="benchmarks that print figures")
    b.add_argument("what", choices=("derivation", "numerics"))
    b.add_argument("--repeat", type=int, default=3, help="fresh processes per measurement")
    b.add_argument("--scale", action="store_true",
                   help="derivation: the families of n coordinates (bench.family)")
    b.add_argument("--n", default="2..8",
                   help="derivation --scale: the range of n, e.g. 2..4, or a list, 8,12,24")
    b.add_argument("--family", choices=("both", "nonholonomic", "holonomic", "chain", "rotors",
                                        "coins", "all"),
                   default="both", help="derivation --scale: which family (both, "
                   "nonholonomic, holonomic: bench.family against LagrangesMethod; chain: "
                   "spring-coupled sleighs, rotors: a train of sleighs with rotors, coins: "
                   "rolling coins with off-centre masses, all: these three, each against "
                   "LagrangesMethod and KanesMethod)")
    b.add_argument("--no-memory", action="store_true",
                   help="derivation --scale: skip the traced runs for peak memory")
    b.add_argument("--quick", action="store_true", help="numerics: a smaller study")
    b.add_argument("--json", metavar="FILE", help="numerics: write every run to FILE")
    b.add_argument("--plot", metavar="FILE", help="numerics: the error-against-time figure")
    b.add_argument("--csv", metavar="FILE", help="numerics: every run as CSV")
    b.add_argument("--quiet", action="store_true", help="numerics: no progress bar")
    b.set_defaults(func=_bench)
    g = sub.add_parser("grade", help="grade the students' exercise notebooks into a CSV")
    g.add_argument("submissions", nargs="*", help="the submitted .ipynb files, or the "
                   "folder an LMS download was extracted into (after '--', or as existing "
                   "files, names may begin with '-')")
    g.add_argument("--exercise", metavar="ID", help="the assignment's exercise: every "
                   "notebook is graded as it, or refused if it is of another exercise")
    g.add_argument("--roster", metavar="CSV", help="the students: Canvas's gradebook export, "
                   "Moodle's grading worksheet, or a CSV with id and name columns (default: "
                   "the --canvas or --moodle file)")
    g.add_argument("--report", metavar="FILE", help="the identity report (default: "
                   "<out>-identities.csv): who each notebook was graded under, and why not")
    g.add_argument("--out", required=True, help="the CSV to write: "
                   "submission,exercise,part,ok,points,max_points,message")
    g.add_argument("--gradebook", metavar="FILE", help="points per part and total, per "
                   "submission (CSV)")
    g.add_argument("--canvas", metavar="CSV", help="your Canvas gradebook export: written "
                   "back, with the assignment's column filled in, to --canvas-out")
    g.add_argument("--canvas-out", metavar="CSV", help="default: <canvas>-graded.csv")
    g.add_argument("--canvas-column", metavar="'TITLE (ID)'", help="the assignment's column "
                   "(default: the one titled as the exercise's id or title)")
    g.add_argument("--moodle", metavar="CSV", help="your Moodle offline grading worksheet: "
                   "written back, Grade and Feedback comments filled in, to --moodle-out")
    g.add_argument("--moodle-out", metavar="CSV", help="default: <moodle>-graded.csv")
    g.add_argument("--overwrite-feedback", action="store_true", help="replace Moodle's "
                   "feedback comments instead of appending to them")
    g.add_argument("--unsafe", action="store_true", help="run the notebooks without the "
                   "sandbox where it cannot be had (not root, no bubblewrap)")
    g.add_argument("--feedback", metavar="DIR", help="write one HTML page per submission")
    g.add_argument("--jobs", type=int, default=2, help="notebooks run at a time (default 2)")
    g.add_argument("--cell-timeout", type=float, default=60, help="seconds per cell (60)")
    g.add_argument("--timeout", type=float, default=300, help="seconds per notebook (300)")
    g.add_argument("--memory", type=int, default=3000, help="MB of memory per kernel (3000)")
    g.add_argument("--cpus", type=float, default=None,
                   help="CPUs' worth of time per notebook, over all its processes (1)")
    g.add_argument("--quiet", action="store_true", help="no progress bar")
    g.set_defaults(func=_grade)
    args, extra = parser.parse_known_args(argv)
    if args.command == "grade":   # file names that begin with '-' (grade *.ipynb)
        import os
        unknown = [e for e in extra if not os.path.isfile(e)]
        if unknown:
            parser.error("unrecognized arguments: " + " ".join(unknown))
        args.submissions = list(args.submissions) + extra
        if not args.submissions:
            parser.error("grade: no submissions given")
    elif extra:
        parser.error("unrecognized arguments: " + " ".join(extra))
    return args.func(args)


if __name__ == "__main__":
    try:
        sys.exit(main())
    except BrokenPipeError:  # output piped into head, say
        sys.exit(0)
