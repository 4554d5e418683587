#!/usr/bin/env bash
# Makes `import membrane_flow` and `python3 -m membrane_flow <command>` work for the Debian
# Python (/usr/bin/python3): writes
# membrane_flow.pth, naming this checkout's build/python, into its site-packages
# directory (/usr/local/lib/python3.X/dist-packages). Run by setup.sh; run it again
# to point the import at another checkout. Without write access it prints the
# PYTHONPATH to use instead.
set -euo pipefail
cd "$(dirname "$0")/.."
package="$(pwd)/build/python"
if [ ! -f "$package/membrane_flow/__init__.py" ]; then
  echo "[python] $package/membrane_flow is missing: build first (./scripts/build.sh)" >&2
  exit 1
fi
[ -f "$package"/membrane_flow/_core*.so ] ||
  echo "[python] warning: the compiled module is missing (pybind11-dev and python3-dev at configure time?);" \
       "only the pure-Python part (the reader of runs, the launcher, python3 -m membrane_flow) will work" >&2
site=$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')
if mkdir -p "$site" 2>/dev/null && echo "$package" > "$site/membrane_flow.pth" 2>/dev/null; then
  echo "[python] /usr/bin/python3 imports membrane_flow from $package ($site/membrane_flow.pth)"
else
  echo "[python] cannot write $site; use: PYTHONPATH=$package /usr/bin/python3" >&2
fi
