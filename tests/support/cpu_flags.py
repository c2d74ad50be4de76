"""The instruction-set flags of this machine's CPU, as /proc/cpuinfo lists them (empty where there
is no /proc/cpuinfo), for the test scripts that choose or predict OpenBLAS's kernels.
Scripts in tests/regression/* import it after `sys.path.insert(0, SUPPORT)`, SUPPORT being this
folder."""


def cpu_flags():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("flags"):
                    return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()
