"""Where things are: the repository, bench/results/ (every benchmark writes
there; docs and README link its files), examples/, and example-robot-data's
robots."""

import os
import site
import sys
import sysconfig

BENCH = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROOT = os.path.dirname(BENCH)
RESULTS = os.path.join(BENCH, "results")
EXAMPLES = os.path.join(ROOT, "examples")
TESTS = os.path.join(ROOT, "tests")


def robots_dir():
    """example-robot-data's robots directory (its pip package installs it
    under cmeel.prefix); exits with the install hint when it is missing."""
    for base in sorted({sysconfig.get_paths()["purelib"], *site.getsitepackages()}):
        path = os.path.join(base, "cmeel.prefix", "share", "example-robot-data", "robots")
        if os.path.isdir(path):
            return path
    sys.exit("example-robot-data is not installed (pip install 'lagmb[robots]')")
