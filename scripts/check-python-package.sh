#!/usr/bin/env bash
# The Python package as a user installs it (README.md, "The Python package"): pip
# installs this checkout into a fresh virtual environment of Debian's python3 (system
# site packages: Debian's numpy, pytest and pyopencl), then runs the README's Python
# example exactly as written, in a scratch folder that sees the repository's data/,
# and tests/python/test_pyopencl.py against the installed package.
# Usage: scripts/check-python-package.sh   (FINFLEX_SYSTEM_PYTHON: another python3)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
python=${FINFLEX_SYSTEM_PYTHON:-/usr/bin/python3}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
export PYTHONDONTWRITEBYTECODE=1

"$python" -m venv --system-site-packages "$scratch/venv"
"$scratch/venv/bin/python3" -m pip install -q "$root"

# The first python block after the heading "## The Python package".
awk '/^## The Python package/ {section = 1}
     section && /^```python/ {inside = 1; next}
     inside && /^```/ {exit}
     inside {print}' "$root/README.md" > "$scratch/example.py"
test -s "$scratch/example.py"
ln -s "$root/data" "$scratch/data"
(cd "$scratch" && "$scratch/venv/bin/python3" example.py)
test -s "$scratch/blub_bent.obj"
echo "check-python-package: the README example wrote blub_bent.obj"

cd "$scratch" && "$scratch/venv/bin/python3" -m pytest -q -p no:cacheprovider \
  "$root/tests/python/test_pyopencl.py"
