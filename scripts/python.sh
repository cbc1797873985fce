#!/bin/sh
# Prints the Python interpreter the Makefile uses: a project venv if there is
# one, else python3 itself, unless python3 is "externally managed" (PEP 668,
# e.g. Debian's system Python), in which case the venv is created by setup.sh.
if [ -x .venv/bin/python ]; then echo .venv/bin/python; exit 0; fi
py=$(command -v python3 || echo python3)
if "$py" -c 'import sys, sysconfig, os; sys.exit(not os.path.exists(os.path.join(sysconfig.get_path("stdlib"), "EXTERNALLY-MANAGED")))' 2>/dev/null; then
  echo .venv/bin/python
else
  echo "$py"
fi
