"""`python -m rigidfmu ...` is the `rigidfmu` command."""
import sys

from rigidfmu.cli import main

sys.exit(main())
