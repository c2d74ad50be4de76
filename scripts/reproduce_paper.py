#!/usr/bin/python3
"""Reproduce the paper's numerical examples 6.1, 6.2 and 6.3 (issue 5).

Runs every deck of input/paper/ (or reuses results that are newer than the deck, its mesh and the
program), then writes the figures, the iteration tables and one page per example into docs/paper/.
Each example lives in scripts/paper_examples/example_6_X.py and exposes reproduce(context).

    /usr/bin/python3 scripts/reproduce_paper.py                 # all examples
    /usr/bin/python3 scripts/reproduce_paper.py --only 6.1      # one example
    /usr/bin/python3 scripts/reproduce_paper.py --rerun         # ignore existing results
"""
import argparse
import importlib
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from paper_examples.common import Context  # noqa: E402

EXAMPLES = ["6.1", "6.2", "6.3"]


def main():
    repo = Path(__file__).resolve().parent.parent
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", type=Path, default=repo / "build",
                        help="build directory holding src/app/covcontact (default: build)")
    parser.add_argument("--work", type=Path, default=None,
                        help="where results files go (default: BUILD/paper)")
    parser.add_argument("--only", choices=EXAMPLES, action="append",
                        help="reproduce only this example (repeatable)")
    parser.add_argument("--rerun", action="store_true", help="run every deck again")
    parser.add_argument("--threads", type=int, default=None, help="assembly threads per run")
    args = parser.parse_args()

    covcontact = args.build / "src" / "app" / "covcontact"
    if not covcontact.exists():
        sys.exit(f"{covcontact} not found: build first (cmake --build {args.build})")
    context = Context(repo=repo, covcontact=covcontact,
                      work=args.work or args.build / "paper", docs=repo / "docs" / "paper",
                      rerun=args.rerun, threads=args.threads)
    for example in args.only or EXAMPLES:
        module = importlib.import_module("paper_examples.example_" + example.replace(".", "_"))
        print(f"== example {example}", flush=True)
        module.reproduce(context)


if __name__ == "__main__":
    main()
