"""Reading CovContact's results file (docs/output-format.md) from Python: what the scripts here
and the test scripts share. Run from scripts/ (its folder is on sys.path) or put scripts/ on
sys.path first."""


def set_names(dataset):
    """The node-set names of a step's set_reactions table, as str (h5py may give bytes)."""
    return [n.decode() if isinstance(n, bytes) else str(n) for n in dataset.attrs["names"]]


def set_reaction(step, name):
    """The summed reaction (Fx, Fy, Fz) of node set `name` in a step's group, h5["steps/N"]."""
    dataset = step["set_reactions"]
    return dataset[set_names(dataset).index(name)]
