#!/bin/bash
# README's figures re-run and compared (the table of claims is in scripts/readme_check.py); exit 1 names each README
# line whose figure no longer holds. Usage: bash scripts/readme-check.sh [--readme README.md] [BUILD_DIR] (default build/)
exec /usr/bin/python3 "$(dirname "$0")/readme_check.py" "$@"
