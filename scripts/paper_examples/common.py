"""What every paper example needs: running a deck (or reusing fresh results) and reading results.

Results layout: docs/output-format.md. Each example module calls context.run() for its decks and
reads the returned HDF5 file with h5py.
"""
import re
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

import h5py
import numpy as np


@dataclass
class Context:
    repo: Path          # repository root
    covcontact: Path    # the program
    work: Path          # results files go here
    docs: Path          # docs/paper: figures, tables, pages
    rerun: bool = False
    threads: int | None = None
    wall_seconds: dict = field(default_factory=dict)  # run name -> wall time of the last run

    def run(self, deck: Path, name: str, extra_args=()) -> Path:
        """Run deck into WORK/name.h5 unless that file is complete and newer than its inputs."""
        deck = Path(deck)
        self.work.mkdir(parents=True, exist_ok=True)
        self.docs.mkdir(parents=True, exist_ok=True)
        results = self.work / f"{name}.h5"
        if not self.rerun and self._fresh(results, deck):
            with h5py.File(results, "r") as f:
                self.wall_seconds[name] = float(f["summary"].attrs["wall_seconds"])
            print(f"   {name}: reusing {results}", flush=True)
            return results
        command = [str(self.covcontact), "run", str(deck), "--output", str(results), "--quiet"]
        if self.threads:
            command += ["--threads", str(self.threads)]
        command += list(extra_args)
        print(f"   {name}: {' '.join(command)}", flush=True)
        start = time.monotonic()
        subprocess.run(command, check=True)
        self.wall_seconds[name] = time.monotonic() - start
        return results

    def _fresh(self, results: Path, deck: Path) -> bool:
        if not results.exists():
            return False
        inputs = [deck, self.covcontact] + mesh_files(deck)
        newest_input = max(p.stat().st_mtime for p in inputs if p.exists())
        if results.stat().st_mtime < newest_input:
            return False
        try:
            with h5py.File(results, "r") as f:
                return f["summary"].attrs["outcome"] in ("completed", b"completed")
        except (OSError, KeyError):
            return False


def mesh_files(deck: Path) -> list:
    """The .geo/.msh files and includes a deck names (for the freshness check)."""
    found = []
    for line in deck.read_text().splitlines():
        for quoted in re.findall(r'"([^"]+\.(?:geo|msh|deck|inc))"', line):
            found.append((deck.parent / quoted).resolve())
    return found


def steps(results: Path):
    """Yield (step attributes dict, step group) in step order; the file stays open meanwhile."""
    with h5py.File(results, "r") as f:
        for name in sorted(f["steps"]):
            group = f["steps"][name]
            yield dict(group.attrs), group


def iterations_per_step(results: Path) -> list:
    """Newton iterations of the converged attempt of every written step."""
    with h5py.File(results, "r") as f:
        return [int(f["steps"][name].attrs["iterations"]) for name in sorted(f["steps"])]


def convergence_table(results: Path) -> np.ndarray:
    """The /convergence table (one row per Newton iteration, cut-back attempts included)."""
    with h5py.File(results, "r") as f:
        return f["convergence"][...]


def markdown_table(header, rows) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"
